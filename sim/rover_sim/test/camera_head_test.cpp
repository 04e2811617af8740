#include "rover/sim/rover_sim/camera_head.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "rover/sim/terrain/terrain.hpp"

namespace rover::sim::rover_sim {
namespace {

std::shared_ptr<const terrain::Terrain> SmallTerrain() {
  terrain::TerrainParams p;
  p.size_x = p.size_y = 16.0;
  p.craters.count = 0;
  p.rocks.preset = terrain::RockPreset::kNone;
  p.seed = 5;
  auto t = terrain::GenerateTerrain(p);
  EXPECT_TRUE(t.ok()) << t.status().message();
  return std::make_shared<const terrain::Terrain>(std::move(*t));
}

CameraHeadOptions SmallImages() {
  CameraHeadOptions o;
  o.image_size = 128;
  return o;
}

const Eigen::Vector3d kSun = Eigen::Vector3d(0.3, 0.2, 0.9).normalized();

// Takes a shot or skips the test when this machine has no headless OpenGL.
#define TAKE_OR_SKIP(var, head, ...)                                              \
  auto var##_result = (head).Take(__VA_ARGS__);                                   \
  if (!var##_result.ok() && var##_result.status().code() == StatusCode::kUnavailable) \
    GTEST_SKIP() << var##_result.status().message();                              \
  ASSERT_TRUE(var##_result.ok()) << var##_result.status().message();              \
  const CameraShot& var = *var##_result

TEST(CameraHeadOptionsTest, ValidatesTheImageSize) {
  EXPECT_TRUE(CameraHeadOptions{}.Validate().ok());
  CameraHeadOptions o;
  o.image_size = 32;
  EXPECT_NE(o.Validate().message().find("image_size"), std::string::npos);
}

TEST(CameraHeadTest, UnknownCameraIsNotFoundWithoutStartingTheRenderer) {
  CameraHead head(SmallImages(), SmallTerrain(), {});
  auto shot = head.Take("pancam", 0, Eigen::Isometry3d::Identity(), {}, kSun);
  ASSERT_FALSE(shot.ok());
  EXPECT_EQ(shot.status().code(), StatusCode::kNotFound);
  EXPECT_NE(shot.status().message().find("navcam"), std::string::npos) << shot.status().message();
  EXPECT_EQ(head.frames(), 0u);
}

TEST(CameraHeadTest, BadMastAngleIsRefused) {
  CameraHead head(SmallImages(), SmallTerrain(), {});
  auto shot = head.Take("navcam", 0, Eigen::Isometry3d::Identity(), {std::nan(""), 0.0}, kSun);
  ASSERT_FALSE(shot.ok());
  EXPECT_EQ(shot.status().code(), StatusCode::kInvalidArgument);
}

TEST(CameraHeadTest, TakesAPairOfTheRequestedSizeAndCountsFrames) {
  CameraHead head(SmallImages(), SmallTerrain(), {});
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.4);
  TAKE_OR_SKIP(shot, head, "front_hazcam", 0, pose, render::MastState{}, kSun);
  EXPECT_EQ(shot.images.left.image.cols, 128);
  EXPECT_EQ(shot.images.right.image.rows, 128);
  EXPECT_GE(shot.exposure_us, 1u);
  EXPECT_TRUE(shot.exposure_refused.empty());
  EXPECT_GT(cv::mean(shot.images.left.image)[0], 1.0);  // the ground is lit
  EXPECT_EQ(head.frames(), 1u);
}

TEST(CameraHeadTest, AFixedExposureIsUsedAndReportedInMicroseconds) {
  CameraHead head(SmallImages(), SmallTerrain(), {});
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.4);
  TAKE_OR_SKIP(shot, head, "navcam", 20000, pose, render::MastState{0.0, -0.5}, kSun);
  EXPECT_EQ(shot.exposure_us, 20000u);
  TAKE_OR_SKIP(longer, head, "navcam", 80000, pose, render::MastState{0.0, -0.5}, kSun);
  EXPECT_EQ(longer.exposure_us, 80000u);
  // Four times the integration time gives a brighter image (until it saturates).
  EXPECT_GT(cv::mean(longer.images.left.image)[0], cv::mean(shot.images.left.image)[0]);
}

TEST(CameraHeadTest, ANightSunStillLightsTheSceneFromJustAboveTheHorizon) {
  CameraHead head(SmallImages(), SmallTerrain(), {});
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.4);
  TAKE_OR_SKIP(shot, head, "front_hazcam", 0, pose, render::MastState{},
               Eigen::Vector3d(0.0, 0.6, -0.8));
  EXPECT_GT(cv::mean(shot.images.left.image)[0], 0.5);
}

TEST(CameraHeadTest, ReadoutsTheSensorCannotProduceAreRefusedByValue) {
  EXPECT_TRUE(CameraHead::CheckReadout(0, 1024, "navcam").ok());
  EXPECT_TRUE(CameraHead::CheckReadout(256, 1024, "navcam").ok());
  const Status wide = CameraHead::CheckReadout(2048, 1024, "navcam");
  EXPECT_NE(wide.message().find("readout_width 2048 px is wider than the navcam sensor (1024 px)"),
            std::string::npos)
      << wide.message();
  const Status odd = CameraHead::CheckReadout(300, 1024, "front_hazcam");
  EXPECT_NE(odd.message().find("readout_width 300 px is not the front_hazcam sensor width"),
            std::string::npos)
      << odd.message();
  EXPECT_FALSE(CameraHead::CheckReadout(-4, 1024, "navcam").ok());
  CameraHead head(SmallImages(), SmallTerrain(), {});
  auto shot = head.Take("front_hazcam", 0, Eigen::Isometry3d::Identity(), {}, kSun, 48);
  ASSERT_FALSE(shot.ok());
  EXPECT_EQ(shot.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(head.frames(), 0u);
}

TEST(CameraHeadTest, ABinnedReadoutRendersOnlyItsPixels) {
  CameraHead head(SmallImages(), SmallTerrain(), {});
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0.0, 0.0, 0.4);
  TAKE_OR_SKIP(full, head, "front_hazcam", 0, pose, render::MastState{}, kSun, 0);
  TAKE_OR_SKIP(binned, head, "front_hazcam", 0, pose, render::MastState{}, kSun, 64);
  EXPECT_EQ(full.images.left.image.cols, 128);
  EXPECT_EQ(binned.images.left.image.cols, 64);
  EXPECT_EQ(binned.images.right.image.rows, 64);
  // The same scene: the binned image is the full one at half the resolution, up to noise.
  cv::Mat full_f, binned_f, down;
  full.images.left.image.convertTo(full_f, CV_32F);
  binned.images.left.image.convertTo(binned_f, CV_32F);
  cv::resize(full_f, down, binned_f.size(), 0, 0, cv::INTER_AREA);
  EXPECT_LT(cv::norm(down, binned_f, cv::NORM_L1) / down.total(), 6.0);
}

}  // namespace
}  // namespace rover::sim::rover_sim
