#include "rover/dl/vo/odometry_prior.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace rover::dl::vo {
namespace {

Eigen::Isometry3d Pose(double x, double y, double yaw) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(x, y, 0.0);
  return t;
}

TEST(OdometryPrior, IsTheRoverFrameMotionBetweenTheTwoPoses) {
  // Heading 90 deg (site +y), then 0.5 m forward and a 0.1 rad turn left.
  const Eigen::Isometry3d a = Pose(2.0, 3.0, std::numbers::pi / 2);
  const Eigen::Isometry3d b = Pose(2.0, 3.5, std::numbers::pi / 2 + 0.1);
  OdometryPriorOptions o;
  const MotionPrior p = OdometryPrior(a, b, o);
  EXPECT_NEAR(p.delta.translation().x(), 0.5, 1e-12);  // forward in the rover frame
  EXPECT_NEAR(p.delta.translation().y(), 0.0, 1e-12);
  EXPECT_NEAR(RotationAngle(p.delta.linear()), 0.1, 1e-12);
  const double st = 0.02 + 0.1 * 0.5, sr = 0.02 + 0.1 * 0.1;
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(p.covariance(i, i), st * st, 1e-15);
    EXPECT_NEAR(p.covariance(i + 3, i + 3), sr * sr, 1e-15);
  }
  EXPECT_EQ((p.covariance - Matrix6d(p.covariance.diagonal().asDiagonal())).norm(), 0.0);
}

TEST(OdometryPrior, VaguePriorIsZeroMotionWithTheVagueSigmas) {
  OdometryPriorOptions o;
  o.vague_translation_sigma = 0.4;
  o.vague_rotation_sigma = 0.3;
  const MotionPrior p = VaguePrior(o);
  EXPECT_TRUE(p.delta.isApprox(Eigen::Isometry3d::Identity()));
  EXPECT_DOUBLE_EQ(p.covariance(0, 0), 0.16);
  EXPECT_DOUBLE_EQ(p.covariance(5, 5), 0.09);
}

TEST(OdometryPrior, CameraFramePriorMapsBackToTheBodyFrame) {
  const MotionPrior body = OdometryPrior(Pose(0, 0, 0), Pose(0.4, 0.05, 0.2), {});
  Eigen::Isometry3d t_rc = Eigen::Isometry3d::Identity();  // camera 45 deg down, 0.5 m ahead
  t_rc.linear().col(0) = Eigen::Vector3d(0, -1, 0);
  t_rc.linear().col(2) = Eigen::Vector3d(1, 0, -1).normalized();
  t_rc.linear().col(1) = t_rc.linear().col(2).cross(t_rc.linear().col(0));
  t_rc.translation() = Eigen::Vector3d(0.5, 0.0, 0.5);
  const MotionPrior cam = ToCameraFrame(body, t_rc);
  // delta_c = T_rc^-1 delta_b T_rc.
  EXPECT_TRUE(cam.delta.isApprox(t_rc.inverse() * body.delta * t_rc, 1e-12));
  MotionEstimate e;
  e.delta = cam.delta;
  e.covariance = cam.covariance;
  const MotionEstimate back = ToBodyFrame(e, t_rc);
  EXPECT_TRUE(back.delta.isApprox(body.delta, 1e-12));
  EXPECT_LT((back.covariance - body.covariance).norm(), 1e-12);
}

TEST(OdometryPrior, OptionsAreValidated) {
  EXPECT_TRUE(OdometryPriorOptions{}.Validate().ok());
  OdometryPriorOptions o;
  o.translation_sigma_min = 0.0;
  EXPECT_NE(o.Validate().message().find("translation_sigma_min"), std::string::npos);
  o = OdometryPriorOptions{};
  o.rotation_sigma_fraction = -1.0;
  EXPECT_NE(o.Validate().message().find("rotation_sigma_fraction"), std::string::npos);
}

}  // namespace
}  // namespace rover::dl::vo
