#include "rover/dl/vo/stereo_camera.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace rover::dl::vo {
namespace {

StereoCamera Kittiish() {
  StereoCamera c;
  c.width = 1226;
  c.height = 370;
  c.fx = c.fy = 707.0912;
  c.cx = 601.8873;
  c.cy = 183.1104;
  c.baseline = 0.5371;
  return c;
}

TEST(StereoCamera, ValidAccepted) { EXPECT_TRUE(Kittiish().Validate().ok()); }

TEST(StereoCamera, RejectsSingularOrMissingCamera) {
  StereoCamera c;  // all zero: a missing camera
  EXPECT_EQ(c.Validate().code(), StatusCode::kInvalidArgument);
  c = Kittiish();
  c.fx = 0.0;
  EXPECT_NE(c.Validate().message().find("fx"), std::string::npos);
  c = Kittiish();
  c.fy = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(c.Validate().ok());
  c = Kittiish();
  c.baseline = -0.5;
  EXPECT_NE(c.Validate().message().find("baseline"), std::string::npos);
  c = Kittiish();
  c.width = 0;
  EXPECT_NE(c.Validate().message().find("size"), std::string::npos);
  c = Kittiish();
  c.cx = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(c.Validate().ok());
}

TEST(StereoCamera, FromKittiProjectionMatrices) {
  Eigen::Matrix<double, 3, 4> p0, p1;
  p0 << 707.0912, 0, 601.8873, 0, 0, 707.0912, 183.1104, 0, 0, 0, 1, 0;
  p1 = p0;
  p1(0, 3) = -379.8145;
  const Result<StereoCamera> c = StereoCamera::FromProjectionMatrices(p0, p1, 1226, 370);
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  EXPECT_NEAR(c->baseline, 0.537151, 1e-5);
  EXPECT_DOUBLE_EQ(c->fx, 707.0912);
  EXPECT_DOUBLE_EQ(c->cy, 183.1104);
  EXPECT_EQ(c->width, 1226);
}

TEST(StereoCamera, RejectsNonRectifiedMatrices) {
  Eigen::Matrix<double, 3, 4> p0, p1;
  p0 << 700, 0, 600, 0, 0, 700, 180, 0, 0, 0, 1, 0;
  p1 = p0;
  p1(0, 3) = -350;
  Eigen::Matrix<double, 3, 4> bad = p1;
  bad(0, 0) = 710;  // different focal length
  EXPECT_FALSE(StereoCamera::FromProjectionMatrices(p0, bad, 100, 100).ok());
  bad = p1;
  bad(1, 3) = 5;  // vertical offset
  EXPECT_FALSE(StereoCamera::FromProjectionMatrices(p0, bad, 100, 100).ok());
  bad = p1;
  bad(0, 3) = 350;  // right camera on the left
  EXPECT_FALSE(StereoCamera::FromProjectionMatrices(p0, bad, 100, 100).ok());
  bad = p0;
  bad(0, 1) = 3;  // skew
  EXPECT_FALSE(StereoCamera::FromProjectionMatrices(bad, p1, 100, 100).ok());
  EXPECT_FALSE(StereoCamera::FromProjectionMatrices(p0, p0, 100, 100).ok());  // no baseline
}

TEST(StereoCamera, ProjectionAndRayAgree) {
  const StereoCamera c = Kittiish();
  const Eigen::Vector3d p(1.5, -0.4, 12.0);
  const Eigen::Vector2d ul = c.ProjectLeft(p);
  const Eigen::Vector2d ur = c.ProjectRight(p);
  EXPECT_NEAR(ul.y(), ur.y(), 1e-12);
  EXPECT_NEAR(ul.x() - ur.x(), c.fx * c.baseline / p.z(), 1e-9);
  EXPECT_TRUE((c.Ray(ul) * p.z() - p).norm() < 1e-9);
  EXPECT_TRUE((c.RightCentre() + c.Ray(ur) * p.z() - p).norm() < 1e-9);
}

TEST(StereoCamera, ProjectionJacobianMatchesFiniteDifferences) {
  const StereoCamera c = Kittiish();
  const Eigen::Vector3d p(-2.0, 0.7, 8.0);
  const Eigen::Matrix<double, 2, 3> j = c.ProjectLeftJacobian(p);
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    d(k) = 1e-6;
    const Eigen::Vector2d num = (c.ProjectLeft(p + d) - c.ProjectLeft(p - d)) / 2e-6;
    EXPECT_NEAR((num - j.col(k)).norm(), 0.0, 1e-4) << "column " << k;
  }
}

TEST(StereoCamera, Inside) {
  const StereoCamera c = Kittiish();
  EXPECT_TRUE(c.Inside({10, 10}, 5));
  EXPECT_FALSE(c.Inside({3, 10}, 5));
  EXPECT_FALSE(c.Inside({1222, 10}, 5));
  EXPECT_TRUE(c.Inside({1220, 364}, 5));
  EXPECT_FALSE(c.Inside({1220, 365}, 5));
}

}  // namespace
}  // namespace rover::dl::vo
