// Runs the rover-stereo command-line tool (built next to the tests) on a synthetic pair.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "rover/dl/stereo/disparity_io.hpp"
#include "test_images.hpp"

namespace rover::dl::stereo {
namespace {

class RoverStereoToolTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const char* bin = std::getenv("ROVER_BIN_DIR");
    tool_ = std::string(bin != nullptr ? bin : ROVER_BINARY_DIR "/bin") + "/rover-stereo";
    if (!std::filesystem::exists(tool_)) GTEST_SKIP() << "rover-stereo not built at " << tool_;
    dir_ = std::filesystem::temp_directory_path() /
           ("rover_stereo_tool_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::create_directories(dir_);
    cv::Mat l, r;
    testing::ConstantDisparityPair(testing::Texture(4), cv::Size(160, 100), 9.5, &l, &r);
    ASSERT_TRUE(cv::imwrite(Path("l.png"), l));
    ASSERT_TRUE(cv::imwrite(Path("r.png"), r));
  }
  void TearDown() override {
    if (!dir_.empty()) std::filesystem::remove_all(dir_);
  }
  std::string Path(const std::string& name) const { return (dir_ / name).string(); }
  int Run(const std::string& args) const {
    const std::string cmd = tool_ + " " + args + " > " + Path("log.txt") + " 2>&1";
    const int rc = std::system(cmd.c_str());
    return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
  }

  std::string tool_;
  std::filesystem::path dir_;
};

TEST_F(RoverStereoToolTest, WritesDisparityColourAndRange) {
  ASSERT_EQ(Run("--left " + Path("l.png") + " --right " + Path("r.png") +
                " --num-disparities 32 --focal 200 --baseline 0.1 --disparity " + Path("d.pfm") +
                " --color " + Path("d.png") + " --range " + Path("r.tif")),
            0);
  auto d = ReadPfm(Path("d.pfm"));
  ASSERT_TRUE(d.ok()) << d.status().ToString();
  ASSERT_EQ(d->size(), cv::Size(160, 100));
  int valid = 0, good = 0;
  for (int v = 0; v < d->rows; ++v) {
    for (int u = 0; u < d->cols; ++u) {
      const float x = d->at<float>(v, u);
      if (std::isnan(x)) continue;
      ++valid;
      good += std::abs(x - 9.5f) < 0.25f;
    }
  }
  EXPECT_GT(valid, 0.8 * 160 * 100);
  EXPECT_GT(good, 0.98 * valid);
  EXPECT_EQ(cv::imread(Path("d.png")).type(), CV_8UC3);
  const cv::Mat range = cv::imread(Path("r.tif"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(range.type(), CV_32FC1);
  EXPECT_NEAR(range.at<float>(50, 80), 200 * 0.1 / 9.5, 0.05);  // near the image centre
}

// Two parallel CAHV cameras 0.1 m apart along H' (principal point at the image centre, so
// rectification is the identity): the tool rectifies through core/geometry and ranges.
std::string CahvLabel(double cy_world) {
  // Camera at (0, cy_world, 0) of the label's frame looking along +x: A = (1, 0, 0),
  // H = f H' + hc A, V = f V' + vc A with H' = (0, -1, 0), V' = (0, 0, -1), f = 200,
  // (hc, vc) = (79.5, 49.5), the centre of the 160x100 image.
  return "PDS_VERSION_ID = PDS3\n"
         "GROUP = GEOMETRIC_CAMERA_MODEL_PARMS\n"
         "  MODEL_TYPE = CAHV\n"
         "  MODEL_COMPONENT_1 = (0.0, " +
         std::to_string(cy_world) +
         ", 0.0)\n"
         "  MODEL_COMPONENT_2 = (1.0, 0.0, 0.0)\n"
         "  MODEL_COMPONENT_3 = (79.5, -200.0, 0.0)\n"
         "  MODEL_COMPONENT_4 = (49.5, 0.0, -200.0)\n"
         "END_GROUP = GEOMETRIC_CAMERA_MODEL_PARMS\n"
         "OBJECT = IMAGE\n  LINES = 100\n  LINE_SAMPLES = 160\nEND_OBJECT = IMAGE\nEND\n";
}

TEST_F(RoverStereoToolTest, RectifiesWithCameraModelLabels) {
#ifndef ROVER_STEREO_HAVE_GEOMETRY
  GTEST_SKIP() << "built without core/geometry";
#endif
  for (const auto& [name, y] : {std::pair<std::string, double>{"l.LBL", 0.05}, {"r.LBL", -0.05}}) {
    std::ofstream(Path(name)) << CahvLabel(y);
  }
  ASSERT_EQ(Run("--left " + Path("l.png") + " --right " + Path("r.png") + " --left-model " +
                Path("l.LBL") + " --right-model " + Path("r.LBL") +
                " --num-disparities 32 --disparity " + Path("d.pfm") + " --range " + Path("r.tif")),
            0);
  const cv::Mat range = cv::imread(Path("r.tif"), cv::IMREAD_UNCHANGED);
  ASSERT_EQ(range.type(), CV_32FC1);
  EXPECT_NEAR(range.at<float>(50, 80), 200 * 0.1 / 9.5, 0.05);
  EXPECT_EQ(Run("--left " + Path("l.png") + " --right " + Path("r.png") + " --left-model " +
                Path("l.LBL") + " --disparity " + Path("d.pfm")),
            2);  // one model only
  EXPECT_EQ(
      Run("--left " + Path("l.png") + " --right " + Path("r.png") + " --left-model " +
          Path("l.LBL") + " --right-model " + Path("none.LBL") + " --disparity " + Path("d.pfm")),
      3);  // missing label
}

TEST_F(RoverStereoToolTest, ClearErrors) {
  EXPECT_EQ(Run("--left " + Path("missing.png") + " --right " + Path("r.png") + " --disparity " +
                Path("d.pfm")),
            3);
  EXPECT_EQ(Run("--left " + Path("l.png") + " --right " + Path("r.png") + " --disparity " +
                Path("d.jpg")),
            2);
  EXPECT_EQ(Run("--left " + Path("l.png") + " --right " + Path("r.png") + " --disparity " +
                Path("d.pfm") + " --range " + Path("r.tif")),
            2);  // range without focal length and baseline
  EXPECT_EQ(Run("--left " + Path("l.png") + " --right " + Path("r.png") + " --disparity " +
                Path("d.pfm") + " --window 4"),
            2);
  EXPECT_NE(Run("--right " + Path("r.png") + " --disparity " + Path("d.pfm")), 0);
  EXPECT_FALSE(std::filesystem::exists(Path("d.pfm")));
}

}  // namespace
}  // namespace rover::dl::stereo
