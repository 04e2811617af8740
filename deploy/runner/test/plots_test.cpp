#include "rover/deploy/plots.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>

#include "rover/sim/terrain/terrain.hpp"
#include "rover/sim/terrain/terrain_params.hpp"

namespace rover::deploy {
namespace {

RunResult SampleRun() {
  RunResult r;
  r.scenario = "plot-test";
  r.seed = 4;
  r.pass = true;
  for (int i = 0; i <= 100; ++i) {
    const double t = i * 0.5;
    r.truth_track.push_back({t, 0.1 * t, 0.0});
    r.estimate_track.push_back({t, 0.1 * t, 0.002 * t});
    r.estimate_error.push_back({Time::FromSeconds(t), 0.002 * t, 0.001 * std::sin(t)});
  }
  return r;
}

TEST(Plots, ErrorPlotHasBothCurves) {
  const std::string path = ::testing::TempDir() + "/err.png";
  ASSERT_TRUE(WriteErrorPlot(SampleRun(), path).ok());
  const cv::Mat img = cv::imread(path);
  ASSERT_FALSE(img.empty());
  // Each panel's curve colour appears.
  int orange = 0, blue = 0;
  for (int r = 0; r < img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) {
      const cv::Vec3b p = img.at<cv::Vec3b>(r, c);
      if (p == cv::Vec3b(200, 90, 20)) ++orange;
      if (p == cv::Vec3b(20, 110, 230)) ++blue;
    }
  }
  EXPECT_GT(orange, 100);
  EXPECT_GT(blue, 100);
  std::remove(path.c_str());
  EXPECT_FALSE(WriteErrorPlot(SampleRun(), "/nonexistent/dir/err.png").ok());
}

TEST(Plots, TrackMapDrawsPaths) {
  sim::TerrainParams p;
  p.size_x = 12;
  p.size_y = 12;
  p.resolution = 0.05;
  auto terrain = sim::GenerateTerrain(p);
  ASSERT_TRUE(terrain.ok()) << terrain.status().message();
  const std::string path = ::testing::TempDir() + "/map.png";
  const Status st = WriteTrackMap(*terrain, SampleRun(), {{0, 0}, {5, 0}}, path);
  ASSERT_TRUE(st.ok()) << st.message();
  const cv::Mat img = cv::imread(path);
  ASSERT_FALSE(img.empty());
  int green = 0;
  for (int r = 0; r < img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) {
      const cv::Vec3b v = img.at<cv::Vec3b>(r, c);  // BGR
      if (v[1] == 170 && v[2] == 20 && v[0] == 40) ++green;
    }
  }
  EXPECT_GT(green, 20);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace rover::deploy
