#include "rover/sim/render/cameras.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rover/base/units.hpp"

namespace rover::sim::render {

using terrain::HeightField;

namespace {

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::acos(std::clamp(a.normalized().dot(b.normalized()), -1.0, 1.0)) / kDegree;
}

TEST(CamerasTest, DefaultsAreMerLike) {
  const auto cams = DefaultStereoCameras();
  ASSERT_EQ(cams.size(), 3u);
  auto nav = FindStereoCamera(cams, "navcam");
  ASSERT_TRUE(nav.ok());
  EXPECT_EQ(nav->mount, CameraMount::kMastHead);
  EXPECT_EQ(nav->left.width(), 1024);
  EXPECT_EQ(nav->left.kind(), geometry::CameraModel::Kind::kCahvor);
  EXPECT_NEAR((nav->left.Center() - nav->right.Center()).norm(), 0.20, 1e-12);
  // Horizontal field: rays through the left and right edge centres.
  auto l = nav->left.Unproject(Eigen::Vector2d(-0.5, 511.5));
  auto r = nav->left.Unproject(Eigen::Vector2d(1023.5, 511.5));
  ASSERT_TRUE(l && r);
  EXPECT_NEAR(AngleDeg(l->direction, r->direction), 45.0, 0.5);

  auto haz = FindStereoCamera(cams, "front_hazcam");
  ASSERT_TRUE(haz.ok());
  EXPECT_EQ(haz->mount, CameraMount::kBody);
  EXPECT_EQ(haz->left.kind(), geometry::CameraModel::Kind::kCahvor);
  EXPECT_NEAR((haz->left.Center() - haz->right.Center()).norm(), 0.10, 1e-12);
  EXPECT_NEAR(haz->left.Center().z(), 0.50, 1e-12);
  l = haz->left.Unproject(Eigen::Vector2d(-0.5, 511.5));
  r = haz->left.Unproject(Eigen::Vector2d(1023.5, 511.5));
  ASSERT_TRUE(l && r);
  EXPECT_NEAR(AngleDeg(l->direction, r->direction), 120.0, 0.5);
  // Boresight 45 deg below horizontal, forward; the left camera is on the +y side.
  auto axis = haz->left.Unproject(Eigen::Vector2d(511.5, 511.5));
  ASSERT_TRUE(axis);
  EXPECT_NEAR(axis->direction.x(), std::cos(45 * kDegree), 1e-6);
  EXPECT_NEAR(axis->direction.z(), -std::sin(45 * kDegree), 1e-6);
  EXPECT_GT(haz->left.Center().y(), haz->right.Center().y());
  auto rear = FindStereoCamera(cams, "rear_hazcam");
  ASSERT_TRUE(rear.ok());
  auto rear_axis = rear->left.Unproject(Eigen::Vector2d(511.5, 511.5));
  ASSERT_TRUE(rear_axis);
  EXPECT_LT(rear_axis->direction.x(), -0.7);
  EXPECT_LT(rear->left.Center().x(), 0.0);
}

TEST(CamerasTest, ScaledModelsAreBinned) {
  const auto full = DefaultStereoCameras(1024);
  const auto half = DefaultStereoCameras(512);
  for (std::size_t k = 0; k < full.size(); ++k) {
    EXPECT_EQ(half[k].left.width(), 512);
    // The same ray lands at x_new = 0.5 (x_old + 0.5) - 0.5.
    const Eigen::Vector3d p = full[k].left.Center() + full[k].left.Unproject(Eigen::Vector2d(700, 300))->direction;
    const auto a = full[k].left.Project(p);
    const auto b = half[k].left.Project(p);
    ASSERT_TRUE(a && b);
    EXPECT_NEAR(b->x(), 0.5 * (a->x() + 0.5) - 0.5, 1e-6);
    EXPECT_NEAR(b->y(), 0.5 * (a->y() + 0.5) - 0.5, 1e-6);
  }
}

TEST(CamerasTest, MastPanTiltMovesNavcam) {
  const auto nav = *FindStereoCamera(DefaultStereoCameras(), "navcam");
  auto spec0 = MakeCameraPairSpec(nav, {0.0, 0.0});
  ASSERT_TRUE(spec0.ok());
  EXPECT_NEAR(spec0->LeftInRover().Center().z(), 1.50, 1e-12);
  EXPECT_NEAR(spec0->rover_from_head.translation().x(), 0.35, 1e-12);
  // Pan +90 deg looks left (+y); tilt -30 deg looks down.
  auto spec = MakeCameraPairSpec(nav, {90 * kDegree, -30 * kDegree});
  ASSERT_TRUE(spec.ok());
  const auto left = spec->LeftInRover();
  const auto axis = left.Unproject(Eigen::Vector2d(511.5, 511.5));
  ASSERT_TRUE(axis);
  EXPECT_NEAR(axis->direction.y(), std::cos(30 * kDegree), 1e-3);
  EXPECT_NEAR(axis->direction.z(), -std::sin(30 * kDegree), 1e-3);
  // The baseline turns with the pan: the left camera is now behind (-x) the right one.
  EXPECT_LT(left.Center().x(), spec->RightInRover().Center().x());
  EXPECT_FALSE(MakeCameraPairSpec(nav, {std::nan(""), 0.0}).ok());
}

TEST(CamerasTest, UnknownCameraNamesKnownOnes) {
  auto c = FindStereoCamera(DefaultStereoCameras(), "pancam");
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.status().code(), StatusCode::kNotFound);
  EXPECT_NE(c.status().message().find("pancam"), std::string::npos);
  EXPECT_NE(c.status().message().find("navcam, front_hazcam, rear_hazcam"), std::string::npos);
}

TEST(CamerasTest, RoverPoseOnGroundFollowsSlope) {
  HeightField hf(101, 101, 0.1, Eigen::Vector2d(-5, -5));
  const double slope = std::tan(10 * kDegree);
  for (int j = 0; j < 101; ++j)
    for (int i = 0; i < 101; ++i) hf.at(i, j) = static_cast<float>(slope * (-5 + 0.1 * i));
  const Eigen::Isometry3d pose = RoverPoseOnGround(hf, 1.0, 0.5, 0.0);
  EXPECT_NEAR(pose.translation().z(), slope * 1.0, 1e-5);
  // Facing uphill (+x): the nose is up by 10 deg.
  EXPECT_NEAR(std::asin(pose.linear().col(0).z()) / kDegree, 10.0, 1e-3);
  EXPECT_NEAR(pose.linear().col(1).z(), 0.0, 1e-6);
}

}  // namespace
}  // namespace rover::sim::render
