#include "rover/dl/pose/pose_resume.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "pose_test_support.hpp"
#include "rover/base/units.hpp"
#include "rover/dl/pose/pose_estimator.hpp"

namespace rover::dl::pose {

using locomotion::RoverGeometry;
using locomotion::WheelOdometryOptions;

namespace {

using testing::T;

SavedFilter Saved(double t_s) {
  SavedFilter s;
  s.stamp = T(t_s);
  s.position = {1.0 / 3.0, -2.5, 0.125};
  s.attitude = Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ()));
  s.position_sigma = {0.02, 0.03, 0.01};
  s.rpy_sigma = {0.01, 0.015, 0.05};
  s.gyro_bias = {1e-5, -2e-5, 3.3e-6};
  s.odometer = 12.345678901234567;
  return s;
}

void ExpectSame(const SavedFilter& a, const SavedFilter& b) {
  EXPECT_EQ(a.stamp.ns, b.stamp.ns);
  EXPECT_EQ(a.position, b.position);  // exactly: 17 significant digits
  EXPECT_EQ(a.attitude.coeffs(), b.attitude.coeffs());
  EXPECT_EQ(a.position_sigma, b.position_sigma);
  EXPECT_EQ(a.rpy_sigma, b.rpy_sigma);
  EXPECT_EQ(a.gyro_bias, b.gyro_bias);
  EXPECT_EQ(a.odometer, b.odometer);
}

TEST(PoseCheckpoint, FieldsRoundTripExactly) {
  PoseCheckpoint c;
  c.main = Saved(12.5);
  c.odometry_only = Saved(12.5);
  c.odometry_only->position.x() = 7.0;
  const auto back = PoseCheckpointFromFields(CheckpointFields(c));
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  ExpectSame(back->main, c.main);
  ASSERT_TRUE(back->odometry_only.has_value());
  ExpectSame(*back->odometry_only, *c.odometry_only);
}

TEST(PoseCheckpoint, BadMainFieldsAreErrorsNamingTheKey) {
  PoseCheckpoint c;
  c.main = Saved(1.0);
  auto fields = CheckpointFields(c);
  {
    auto f = fields;
    f.erase("gyro_bias");
    const auto r = PoseCheckpointFromFields(f);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.status().message().find("missing key 'gyro_bias'"), std::string::npos)
        << r.status().message();
  }
  {
    auto f = fields;
    f["position"] = "1 nan 2";
    const auto r = PoseCheckpointFromFields(f);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.status().message().find("'position' = '1 nan 2'"), std::string::npos)
        << r.status().message();
  }
  {
    auto f = fields;
    f["odometer"] = "3 4";
    EXPECT_FALSE(PoseCheckpointFromFields(f).ok());
  }
  {
    auto f = fields;
    f["attitude_wxyz"] = "1 1 0 0";
    const auto r = PoseCheckpointFromFields(f);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.status().message().find("unit quaternion"), std::string::npos);
  }
}

TEST(PoseCheckpoint, AnIncompleteOdometryOnlyPartIsDropped) {
  PoseCheckpoint c;
  c.main = Saved(1.0);
  c.odometry_only = Saved(1.0);
  auto f = CheckpointFields(c);
  f.erase("odometry_only.position");
  const auto r = PoseCheckpointFromFields(f);
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_FALSE(r->odometry_only.has_value());
}

TEST(PoseCheckpoint, SavedFilterOfTakesTheCovarianceDiagonalAsSigmas) {
  PoseEstimate e;
  e.stamp = T(3.0);
  e.position = {1, 2, 3};
  e.covariance.diagonal() << 4e-4, 9e-4, 1e-4, 1e-6, 4e-6, 2.5e-3;
  e.odometer = 5.0;
  const SavedFilter s = SavedFilterOf(e);
  EXPECT_NEAR(s.position_sigma.x(), 0.02, 1e-12);
  EXPECT_NEAR(s.position_sigma.y(), 0.03, 1e-12);
  EXPECT_NEAR(s.rpy_sigma.z(), 0.05, 1e-12);
  EXPECT_EQ(s.odometer, 5.0);
}

TEST(PoseCheckpoint, ResumedStateInflatesPositionAndHeadingByTheGap) {
  const SavedFilter s = Saved(10.0);
  PoseResumeOptions o;
  o.max_speed = 0.1;
  o.max_yaw_rate = 0.02;
  const EkfInitialState init = ResumedInitialState(s, T(13.0), o, 0.002);
  EXPECT_EQ(init.stamp.ns, T(13.0).ns);
  EXPECT_EQ(init.position, s.position);
  EXPECT_NEAR(init.position_sigma.x(), std::hypot(0.02, 0.3), 1e-12);
  EXPECT_NEAR(init.position_sigma.z(), std::hypot(0.01, 0.3), 1e-12);
  EXPECT_NEAR(init.rpy_sigma.z(), std::hypot(0.05, 0.06), 1e-12);
  EXPECT_EQ(init.rpy_sigma.x(), s.rpy_sigma.x());  // the accelerometer re-levels
  EXPECT_EQ(init.odometer, s.odometer);
  EXPECT_EQ(init.gyro_bias_sigma, 0.002);
  // No negative gap (a sample slightly before the checkpoint): no inflation, no shrinking.
  EXPECT_NEAR(ResumedInitialState(s, T(9.9), o, 0.002).position_sigma.x(), 0.02, 1e-12);
}

// ---- the estimator's restart ----------------------------------------------------------------

class PoseEstimatorResumeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    PoseFusionOptions fusion;
    fusion.start.level_samples = 50;
    EkfOptions ekf;
    ekf.gravity = kMarsGravity;
    auto e = PoseEstimator::Create(ekf, RoverGeometry(), WheelOdometryOptions(), fusion);
    ASSERT_TRUE(e.ok()) << e.status().ToString();
    est_.emplace(std::move(*e));
  }
  void Imu(double t_s) {
    msg::Imu m;
    m.stamp = T(t_s);
    m.linear_acceleration = Eigen::Vector3d(0, 0, kMarsGravity);
    est_->OnImu(m);
  }
  std::optional<PoseEstimator> est_;
};

TEST_F(PoseEstimatorResumeTest, ResumesOnTheFirstSampleFromTheCheckpoint) {
  PoseCheckpoint c;
  c.main = Saved(20.0);
  est_->ResumeFrom(c, PoseResumeOptions());
  EXPECT_TRUE(est_->resuming());
  EXPECT_FALSE(est_->started());
  Imu(22.0);
  ASSERT_TRUE(est_->started()) << "no levelling after a restart with a checkpoint";
  EXPECT_FALSE(est_->resuming());
  const PoseEstimate e = est_->ekf().Estimate();
  EXPECT_NEAR((e.position - c.main.position).norm(), 0.0, 1e-9);
  EXPECT_NEAR(e.odometer, c.main.odometer, 1e-9);
  EXPECT_GT(std::sqrt(e.covariance(0, 0)), 0.19);  // 0.1 m/s for 2 s
  // The baseline resumed from the main filter's state (no checkpoint of its own).
  ASSERT_NE(est_->odometry_only(), nullptr);
  ASSERT_TRUE(est_->odometry_only()->initialized());
  EXPECT_NEAR((est_->odometry_only()->Estimate().position - c.main.position).norm(), 0.0, 1e-9);
  // And the checkpoint it now makes is the resumed state.
  EXPECT_NEAR((est_->Checkpoint().main.position - c.main.position).norm(), 0.0, 1e-9);
}

TEST_F(PoseEstimatorResumeTest, ACheckpointOlderThanMaxAgeMakesThePoseUnknownForGood) {
  PoseCheckpoint c;
  c.main = Saved(20.0);
  PoseResumeOptions o;
  o.max_age_s = 5.0;
  est_->ResumeFrom(c, o);
  Imu(26.0);
  EXPECT_FALSE(est_->started());
  ASSERT_TRUE(est_->pose_unknown().has_value());
  EXPECT_NE(est_->pose_unknown()->find("resume.max_age_s"), std::string::npos);
  for (int k = 1; k <= 200; ++k) Imu(26.0 + 0.01 * k);  // a still rover: it must not level
  EXPECT_FALSE(est_->started());
}

TEST_F(PoseEstimatorResumeTest, ACheckpointFromALaterRunTimeIsIgnoredAndTheFilterLevels) {
  PoseCheckpoint c;
  c.main = Saved(500.0);
  est_->ResumeFrom(c, PoseResumeOptions());
  for (int k = 0; k < 60; ++k) Imu(1.0 + 0.01 * k);
  ASSERT_TRUE(est_->started());
  EXPECT_FALSE(est_->pose_unknown().has_value());
  EXPECT_NEAR(est_->ekf().Estimate().position.norm(), 0.0, 1e-9);  // start.*, not the checkpoint
}

TEST_F(PoseEstimatorResumeTest, DeclaredUnknownStopsEstimation) {
  est_->DeclareUnknown("pose unknown after restart: test");
  for (int k = 0; k < 100; ++k) Imu(1.0 + 0.01 * k);
  EXPECT_FALSE(est_->started());
  EXPECT_EQ(*est_->pose_unknown(), "pose unknown after restart: test");
}

}  // namespace
}  // namespace rover::dl::pose
