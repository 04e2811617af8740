#include "rover/msg/pose_idl.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "rover/geometry/transforms.hpp"
#include "rover/idl/access.hpp"

namespace rover::msg {
namespace {

TEST(PoseIdl, IsometryRoundTripNormalisesTheQuaternion) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 3).normalized()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(1.5, -2.0, 0.25);
  rover_Pose3 wire{};
  IsometryToIdl(t, &wire);
  EXPECT_EQ(wire.position.x, 1.5);
  EXPECT_EQ(wire.position.z, 0.25);
  EXPECT_TRUE(IsometryFromIdl(wire).isApprox(t, 1e-12));
  // 90 deg about z, scaled by 2: normalised on the way in.
  wire.orientation = {2 * std::cos(M_PI / 4), 0, 0, 2 * std::sin(M_PI / 4)};
  const Eigen::Isometry3d r = IsometryFromIdl(wire);
  EXPECT_TRUE((r.linear() * Eigen::Vector3d::UnitX()).isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  EXPECT_NEAR(r.linear().determinant(), 1.0, 1e-12);
}

TEST(PoseIdl, EstimateRoundTripRowMajorCovariance) {
  PoseEstimate e;
  e.stamp = Time{1234};
  e.position = Eigen::Vector3d(1, -2, 0.5);
  e.orientation = geometry::QuaternionFromRpy(0.1, -0.2, 2.0);
  e.rpy = Eigen::Vector3d(0.1, -0.2, 2.0);
  e.covariance(2, 4) = 5.0;
  e.velocity = Eigen::Vector3d(0.05, 0, 0);
  e.gyro_bias = Eigen::Vector3d(1e-5, -2e-5, 3e-5);
  e.stationary = true;
  e.odometer = 3.5;
  e.rejected_measurements = 4;
  rover_dl_PoseEstimate w{};
  PoseEstimateToIdl(e, &w);
  EXPECT_EQ(w.header.stamp_ns, 1234);
  EXPECT_EQ(w.covariance[2 * 6 + 4], 5.0);
  EXPECT_EQ(w.covariance[4 * 6 + 2], 0.0);
  EXPECT_EQ(w.odometer, 3.5);
  EXPECT_EQ(w.rejected_measurements, 4u);
  EXPECT_EQ(w.pose.orientation.w, e.orientation.w());
  auto back = PoseEstimateFromIdl(w);
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->stamp, e.stamp);
  EXPECT_EQ(back->position, e.position);
  EXPECT_LT((back->orientation.coeffs() - e.orientation.coeffs()).norm(), 1e-15);
  EXPECT_LT((back->rpy - e.rpy).norm(), 1e-12);
  EXPECT_EQ(back->covariance, e.covariance);
  EXPECT_EQ(back->velocity, e.velocity);
  EXPECT_EQ(back->gyro_bias, e.gyro_bias);
  EXPECT_TRUE(back->stationary);
  EXPECT_EQ(back->odometer, 3.5);
  EXPECT_EQ(back->rejected_measurements, 4u);

  PoseEstimate identity;
  PoseEstimateToIdl(identity, &w);
  EXPECT_EQ(w.pose.orientation.w, 1.0);
}

TEST(PoseIdl, PoseSampleAndAttitudeFromAnEstimate) {
  rover_dl_PoseEstimate p{};
  p.header.stamp_ns = 5;
  const Eigen::Quaterniond q = geometry::QuaternionFromRpy(0.1, -0.2, 2.5);
  p.pose.orientation = {q.w(), q.x(), q.y(), q.z()};
  p.pose.position = {3, 4, 5};
  p.odometer = 7.0;
  p.velocity = {0.1, 0.0, 0.0};
  p.stationary = true;
  const auto a = AttitudeSampleFromIdl(p);
  ASSERT_TRUE(a.ok());
  EXPECT_NEAR(a->roll, 0.1, 1e-12);
  EXPECT_NEAR(a->pitch, -0.2, 1e-12);
  EXPECT_NEAR(a->yaw, 2.5, 1e-12);
  EXPECT_EQ(a->stamp.ns, 5);
  EXPECT_TRUE(a->healthy);
  const auto s = PoseSampleFromIdl(p);
  ASSERT_TRUE(s.ok());
  EXPECT_EQ(s->stamp.ns, 5);
  EXPECT_EQ(s->site_from_rover.translation(), Eigen::Vector3d(3, 4, 5));
  EXPECT_LT((s->site_from_rover.linear() - q.toRotationMatrix()).norm(), 1e-12);
  EXPECT_EQ(s->odometer, 7.0);
  EXPECT_EQ(s->velocity, Eigen::Vector3d(0.1, 0, 0));
  EXPECT_TRUE(s->stationary);

  // Attitude takes any quaternion of norm 0.5..2 (and normalises it); the pose history wants a
  // unit one.
  p.pose.orientation = {2 * q.w(), 2 * q.x(), 2 * q.y(), 2 * q.z()};
  EXPECT_TRUE(AttitudeSampleFromIdl(p).ok());
  auto not_unit = PoseSampleFromIdl(p);
  ASSERT_FALSE(not_unit.ok());
  EXPECT_NE(not_unit.status().message().find("not a unit quaternion (norm 2)"), std::string::npos)
      << not_unit.status().message();
  p.pose.orientation.w = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(AttitudeSampleFromIdl(p).ok());
  EXPECT_FALSE(PoseSampleFromIdl(p).ok());
  p.pose.orientation = {0.0, 0.0, 0.0, 0.0};
  EXPECT_FALSE(AttitudeSampleFromIdl(p).ok());
}

TEST(PoseIdl, PoseSampleRejectsNonFinitePositionVelocityAndOdometer) {
  rover_dl_PoseEstimate p{};
  p.pose.orientation = {1.0, 0.0, 0.0, 0.0};
  ASSERT_TRUE(PoseSampleFromIdl(p).ok());
  p.pose.position.y = std::numeric_limits<double>::quiet_NaN();
  auto bad = PoseSampleFromIdl(p);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "pose.position.y is nan (must be finite)");
  p.pose.position.y = 0.0;
  p.velocity.z = std::numeric_limits<double>::infinity();
  bad = PoseSampleFromIdl(p);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "velocity.z is inf (must be finite)");
  p.velocity.z = 0.0;
  p.odometer = -std::numeric_limits<double>::infinity();
  EXPECT_FALSE(PoseSampleFromIdl(p).ok());
}

TEST(PoseIdl, RelativePoseRoundTripAndBadInput) {
  rover_dl_RelativePose m{};
  idl::SetRawEnum(&m.source, 9);
  auto r = RelativePoseFromIdl(m);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(), "dl/relative_pose: source = 9 is not a MotionSource (0..4)");
  m.source = rover_dl_SOURCE_VISUAL_ODOMETRY;
  m.header.stamp_ns = 2;
  m.t_from_ns = 1;
  m.t_to_ns = 2;
  m.delta.position = {1, 2, 3};
  m.delta.orientation = {1, 0, 0, 0};
  m.covariance[1] = 7.0;  // row 0, column 1
  m.status = rover_dl_RELPOSE_LIMITS_FAILED;
  m.features = 41;
  const auto rel = RelativePoseFromIdl(m);
  ASSERT_TRUE(rel.ok());
  EXPECT_EQ(rel->covariance(0, 1), 7.0);
  EXPECT_EQ(rel->covariance(1, 0), 0.0);
  EXPECT_EQ(rel->delta.translation(), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(rel->source, MotionSource::kVisualOdometry);
  EXPECT_EQ(rel->status, RelativePoseStatus::kLimitsFailed);
  EXPECT_EQ(rel->features, 41u);
  EXPECT_EQ(rel->t_from.ns, 1);
  EXPECT_EQ(rel->t_to.ns, 2);

  RelativePose out = *rel;
  out.delta.linear() = geometry::RotationFromRpy(0.01, 0.02, -0.3);
  rover_dl_RelativePose w{};
  RelativePoseToIdl(out, &w);
  EXPECT_EQ(w.header.stamp_ns, 2);
  EXPECT_EQ(w.covariance[1], 7.0);
  EXPECT_EQ(w.status, rover_dl_RELPOSE_LIMITS_FAILED);
  auto back = RelativePoseFromIdl(w);
  ASSERT_TRUE(back.ok());
  EXPECT_LT((back->delta.matrix() - out.delta.matrix()).norm(), 1e-12);
  EXPECT_EQ(back->covariance, out.covariance);
  EXPECT_EQ(back->features, 41u);

  w.delta.orientation = {0.5, 0.0, 0.0, 0.0};
  auto bad = RelativePoseFromIdl(w);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("quaternion has norm 0.5"), std::string::npos);
  w.delta.orientation = {1, 0, 0, 0};
  idl::SetRawEnum(&w.status, 5);
  EXPECT_FALSE(RelativePoseFromIdl(w).ok());
}

TEST(PoseIdl, EstimatorEventRoundTrip) {
  EstimatorEvent e;
  e.stamp = Time{99};
  e.source = MotionSource::kSunSensor;
  e.accepted = false;
  e.mahalanobis_sq = std::numeric_limits<double>::quiet_NaN();
  e.gate = 13.8;
  e.message = std::string(140, 'e');
  rover_dl_EstimatorEvent w{};
  EstimatorEventToIdl(e, &w);
  EXPECT_EQ(w.header.stamp_ns, 99);
  EXPECT_EQ(w.source, rover_dl_SOURCE_SUN_SENSOR);
  EXPECT_EQ(std::strlen(w.message), 127u);
  auto back = EstimatorEventFromIdl(w);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->stamp, e.stamp);
  EXPECT_EQ(back->source, MotionSource::kSunSensor);
  EXPECT_FALSE(back->accepted);
  EXPECT_TRUE(std::isnan(back->mahalanobis_sq));
  EXPECT_EQ(back->gate, 13.8);
  EXPECT_EQ(back->message, std::string(127, 'e'));
  idl::SetRawEnum(&w.source, 5);
  EXPECT_FALSE(EstimatorEventFromIdl(w).ok());
}

}  // namespace
}  // namespace rover::msg
