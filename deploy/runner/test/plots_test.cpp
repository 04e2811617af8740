#include "rover/deploy/plots.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
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

// A 12 x 12 m terrain at 5 cm, with or without rocks.
Result<sim::terrain::Terrain> SmallTerrain(bool rocks) {
  sim::terrain::TerrainParams p;
  p.size_x = 12;
  p.size_y = 12;
  p.resolution = 0.05;
  if (!rocks) p.rocks.preset = sim::terrain::RockPreset::kNone;
  return sim::terrain::GenerateTerrain(p);
}

int CountColour(const cv::Mat& img, const cv::Vec3b& bgr) {
  int n = 0;
  for (int r = 0; r < img.rows; ++r) {
    for (int c = 0; c < img.cols; ++c) n += img.at<cv::Vec3b>(r, c) == bgr;
  }
  return n;
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

// A hazard contact is ringed in magenta on the map, and survives result.json.
TEST(Plots, TrackMapMarksHazardContacts) {
  auto terrain = SmallTerrain(/*rocks=*/false);
  ASSERT_TRUE(terrain.ok()) << terrain.status().message();
  RunResult run = SampleRun();
  auto rendered = sim::terrain::RenderTopDownMap(*terrain, TrackMapOptions(run, {}));
  ASSERT_TRUE(rendered.ok());
  auto magenta = [](const sim::terrain::MapImage& m) {
    int n = 0;
    for (int r = m.map_row0; r < m.map_row0 + m.map_height; ++r) {
      for (int c = m.map_col0; c < m.map_col0 + m.map_width; ++c) {
        const sim::terrain::MapColor v = m.At(c, r);
        n += v.r == 255 && v.g == 0 && v.b == 255;
      }
    }
    return n;
  };
  EXPECT_EQ(magenta(*rendered), 0);
  run.hazard_contacts.push_back({7, {2.0, -1.0}, 0.31, "wheel_lf", 12.5});
  rendered = sim::terrain::RenderTopDownMap(*terrain, TrackMapOptions(run, {}));
  ASSERT_TRUE(rendered.ok());
  EXPECT_GT(magenta(*rendered), 30);
  auto back = RunResultFromJson(ToJson(run));
  ASSERT_TRUE(back.ok()) << back.status().message();
  ASSERT_EQ(back->hazard_contacts.size(), 1u);
  EXPECT_EQ(back->hazard_contacts[0].part, "wheel_lf");
  EXPECT_DOUBLE_EQ(back->hazard_contacts[0].t_s, 12.5);
  EXPECT_EQ(back->hazard_contacts[0].xy, Eigen::Vector2d(2.0, -1.0));
}

// The criterion's limit as a dashed red line, an injected fault's window shaded, and the zero
// tick written as 0.
TEST(Plots, ErrorPlotDrawsTheLimitAndTheFaultWindows) {
  RunResult run = SampleRun();
  run.criteria.push_back({"max_estimate_error", 0.1, 0.15, "m", true, ""});
  InjectedFault f;
  f.id = 2;
  f.kind = "bias";
  f.start_s = 10;
  f.end_s = 20;
  run.faults.push_back(f);
  const std::string path = ::testing::TempDir() + "/err_limit.png";
  ASSERT_TRUE(WriteErrorPlot(run, path).ok());
  const cv::Mat img = cv::imread(path);
  ASSERT_FALSE(img.empty());
  auto count = [&](cv::Vec3b colour, int row0, int row1) {
    int n = 0;
    for (int r = row0; r < row1; ++r) {
      for (int c = 0; c < img.cols; ++c) n += img.at<cv::Vec3b>(r, c) == colour;
    }
    return n;
  };
  const int half = img.rows / 2;
  EXPECT_GT(count({0, 0, 220}, 0, half), 200);      // the limit, in the position panel only
  EXPECT_EQ(count({0, 0, 220}, half, img.rows), 0);  // no heading criterion: no line
  EXPECT_GT(count({200, 230, 255}, 0, half), 2000);  // the window, in both panels
  EXPECT_GT(count({200, 230, 255}, half, img.rows), 2000);
  // Without a criterion or a fault, neither.
  ASSERT_TRUE(WriteErrorPlot(SampleRun(), path).ok());
  const cv::Mat plain = cv::imread(path);
  EXPECT_EQ(CountColour(plain, {0, 0, 220}), 0);
  EXPECT_EQ(CountColour(plain, {200, 230, 255}), 0);
  std::remove(path.c_str());
}

TEST(Plots, TrackMapDrawsPaths) {
  auto terrain = SmallTerrain(/*rocks=*/true);
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

TEST(Plots, TrackMapShowsTheGoodnessMapTheArcsAndEveryPathOverlapping) {
  auto terrain = SmallTerrain(/*rocks=*/false);
  ASSERT_TRUE(terrain.ok()) << terrain.status().message();
  RunResult run = SampleRun();
  // Truth, odometry, estimate and plan all on the same line: each must still show.
  run.odometry_only_track = run.truth_track;
  run.estimate_track = run.truth_track;
  MobilityOutcome mob;
  mob.task = "autonav";
  mob.outcome = "reached";
  GoodnessGrid g;
  g.origin_x = -4;
  g.origin_y = -4;
  g.resolution = 0.2;
  g.width = 20;
  g.height = 20;
  g.goodness.assign(400, 255);
  g.flags.assign(400, 1);
  for (int k = 0; k < 200; ++k) g.goodness[static_cast<std::size_t>(k)] = 0;  // y < -2: black
  mob.last_map = g;
  mob.arcs.push_back({1, -2, 0, false, 0.5, 1, 0});
  run.mobility = mob;
  const std::string path = ::testing::TempDir() + "/map_mobility.png";
  ASSERT_TRUE(WriteTrackMap(*terrain, run, {{0, 0}, {5, 0}}, path).ok());
  ASSERT_FALSE(cv::imread(path).empty());
  // The same map in memory: count colours on the map itself, not in the legend beside it.
  auto rendered = sim::terrain::RenderTopDownMap(*terrain, TrackMapOptions(run, {{0, 0}, {5, 0}}));
  ASSERT_TRUE(rendered.ok()) << rendered.status().message();
  cv::Mat full(rendered->height, rendered->width, CV_8UC3);
  for (int r = 0; r < full.rows; ++r) {
    for (int c = 0; c < full.cols; ++c) {
      const sim::terrain::MapColor m = rendered->At(c, r);
      full.at<cv::Vec3b>(r, c) = cv::Vec3b(m.b, m.g, m.r);
    }
  }
  const cv::Mat img = full(cv::Rect(rendered->map_col0, rendered->map_row0, rendered->map_width,
                                    rendered->map_height));
  // Goodness layer (x in [-4, 0), y in [-4, 0)): known cells are blended toward black
  // (obstacle) or white (perfect), so the obstacle half is darker than the perfect half.
  const auto px = [&](double x, double y) {
    const Eigen::Vector2d at = rendered->ToPixel(x, y);
    return full.at<cv::Vec3b>(static_cast<int>(at.y()), static_cast<int>(at.x()));
  };
  const cv::Vec3b dark = px(-2, -3), light = px(-2, -1);
  EXPECT_LT(dark[0] + dark[1] + dark[2], light[0] + light[1] + light[2] - 200);
  EXPECT_GT(CountColour(img, {180, 105, 255}), 5);  // the chosen arc, pink
  EXPECT_GT(CountColour(img, {40, 170, 20}), 20);   // truth (green) under the others
  EXPECT_GT(CountColour(img, {200, 60, 170}), 20);  // odometry (purple)
  EXPECT_GT(CountColour(img, {255, 90, 40}), 10);   // planned (blue, dashed)
  EXPECT_GT(CountColour(img, {0, 140, 255}), 10);   // estimate (orange), on top
  if (const char* keep = std::getenv("ROVER_KEEP_PLOTS")) {
    cv::imwrite(std::string(keep) + "/map_mobility.png", full);
  }
  std::remove(path.c_str());
}

}  // namespace
}  // namespace rover::deploy
