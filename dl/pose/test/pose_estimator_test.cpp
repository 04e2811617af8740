#include "rover/dl/pose/pose_estimator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "pose_test_support.hpp"
#include "rover/base/units.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::dl::pose {

using locomotion::RoverGeometry;
using locomotion::WheelOdometryOptions;

namespace {

using testing::T;

msg::Imu Imu(Time t, const Eigen::Vector3d& w = Eigen::Vector3d::Zero(),
             msg::SensorHealth health = msg::SensorHealth::kOk) {
  msg::Imu m;
  m.stamp = t;
  m.angular_velocity = w;
  m.linear_acceleration = Eigen::Vector3d(0, 0, kMarsGravity);  // level, at rest
  m.health = health;
  return m;
}

class PoseEstimatorTest : public ::testing::Test {
 protected:
  void SetUp() override { Make(PoseFusionOptions()); }
  void Make(PoseFusionOptions fusion) {
    fusion.start.level_samples = 50;
    ekf_.gravity = kMarsGravity;
    auto e = PoseEstimator::Create(ekf_, RoverGeometry(), WheelOdometryOptions(), fusion);
    ASSERT_TRUE(e.ok()) << e.status().ToString();
    est_.emplace(std::move(*e));
  }
  // The sun-sensor events since the last call (accelerometer updates make events too).
  std::vector<EstimatorEvent> SunEvents() {
    std::vector<EstimatorEvent> out;
    for (const EstimatorEvent& e : est_->TakeEvents()) {
      if (e.source == MotionSource::kSunSensor) out.push_back(e);
    }
    return out;
  }
  // IMU samples at 100 Hz from `from` for `seconds`, at `rate` about z.
  void Feed(double from, double seconds, double rate = 0.0) {
    for (int k = 0; k < static_cast<int>(std::lround(seconds * 100)); ++k) {
      est_->OnImu(Imu(T(from + 0.01 * k), Eigen::Vector3d(0, 0, rate)));
    }
  }
  // The sun as the rover's sensor sees it at `t` with the rover level, heading `yaw`.
  msg::SunSensor Sun(double t, double yaw = 0.0) const {
    const geometry::SunEphemeris eph(est_->options().ephemeris);
    msg::SunSensor s;
    s.stamp = T(t);
    s.sun_vector = geometry::RotationFromRpy(0.0, 0.0, yaw).transpose() * eph.At(t).direction_site;
    s.valid = true;
    s.intensity = 1.0;
    return s;
  }

  EkfOptions ekf_;
  std::optional<PoseEstimator> est_;
};

TEST_F(PoseEstimatorTest, StartsOnceLevelledAndNotBefore) {
  Feed(1.0, 0.3);
  EXPECT_FALSE(est_->started());
  // FAILED or STALE samples do not count.
  for (int k = 0; k < 100; ++k) {
    est_->OnImu(Imu(T(1.3 + 0.01 * k), Eigen::Vector3d::Zero(), msg::SensorHealth::kFailed));
  }
  EXPECT_FALSE(est_->started());
  Feed(1.3, 0.19);  // 49 still samples
  EXPECT_FALSE(est_->started());
  est_->OnImu(Imu(T(1.49)));  // the 50th
  ASSERT_TRUE(est_->started());
  EXPECT_EQ(est_->ekf().time(), T(1.49));
  ASSERT_NE(est_->odometry_only(), nullptr);
  EXPECT_TRUE(est_->odometry_only()->initialized());
  Feed(1.6, 1.0);
  EXPECT_NEAR(est_->ekf().time().seconds(), 2.59, 1e-9);
  EXPECT_NEAR(est_->ekf().Estimate().rpy.norm(), 0.0, 1e-6);
}

TEST_F(PoseEstimatorTest, ASampleFromBeforeTheFilterRestartsEverything) {
  Feed(100.0, 1.0);
  ASSERT_TRUE(est_->started());
  est_->OnImu(Imu(T(100.5)));  // 0.49 s late: a reordered sample, dropped by the filter
  EXPECT_TRUE(est_->started());
  est_->OnImu(Imu(T(2.0)));  // the run clock went back
  EXPECT_FALSE(est_->started());
  Feed(2.01, 0.6);
  EXPECT_TRUE(est_->started());
  EXPECT_LT(est_->ekf().time().seconds(), 3.0);
}

TEST_F(PoseEstimatorTest, SunUpdatesOnlyWhenSteadyAndTheSunIsHighEnough) {
  Feed(0.0, 1.0);
  ASSERT_TRUE(est_->started());
  est_->OnSunSensor(Sun(0.99));
  auto events = SunEvents();
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].source, MotionSource::kSunSensor);
  EXPECT_TRUE(events[0].accepted) << events[0].message;
  // Turning faster than sun.max_rate (0.2 deg/s): no update.
  Feed(1.0, 0.5, 1.0 * kDegree);
  est_->OnSunSensor(Sun(1.49));
  EXPECT_TRUE(SunEvents().empty());
  // Not valid, or FAILED: no update.
  Feed(1.5, 0.5);
  msg::SunSensor bad = Sun(1.99);
  bad.valid = false;
  est_->OnSunSensor(bad);
  bad = Sun(1.99);
  bad.health = msg::SensorHealth::kFailed;
  est_->OnSunSensor(bad);
  EXPECT_TRUE(SunEvents().empty());
  // The odometry-only filter never sees the sun: its heading sigma only grows.
  EXPECT_GT(est_->odometry_only()->Estimate().covariance(5, 5),
            est_->ekf().Estimate().covariance(5, 5));

  // A sun below sun.min_elevation is ignored.
  PoseFusionOptions high;
  high.sun_min_elevation = 89.0 * kDegree;
  Make(high);
  Feed(0.0, 1.0);
  est_->OnSunSensor(Sun(0.99));
  EXPECT_TRUE(SunEvents().empty());
}

TEST_F(PoseEstimatorTest, RefusedRelativePosesBecomeRejectedEvents) {
  Feed(0.0, 3.0);
  (void)est_->TakeEvents();
  msg::RelativePose r;
  r.t_from = T(1.0);
  r.t_to = T(2.0);
  r.covariance = msg::Matrix6d::Identity() * 1e-4;
  r.delta.translation() = Eigen::Vector3d(std::nan(""), 0, 0);
  est_->OnRelativePose(r);
  est_->RejectRelativePose(MotionSource::kExternal, T(2.5), "unreadable");
  const auto events = est_->TakeEvents();
  ASSERT_EQ(events.size(), 2u);
  EXPECT_FALSE(events[0].accepted);
  EXPECT_TRUE(std::isnan(events[0].mahalanobis_sq));
  EXPECT_EQ(events[0].stamp, T(2.0));
  EXPECT_EQ(events[0].source, MotionSource::kVisualOdometry);
  EXPECT_EQ(events[1].source, MotionSource::kExternal);
  EXPECT_EQ(events[1].message, "relative pose rejected: unreadable");
  // A good one is gated and accepted: the rover did not move.
  r.delta = Eigen::Isometry3d::Identity();
  est_->OnRelativePose(r);
  const auto good = est_->TakeEvents();
  ASSERT_EQ(good.size(), 1u);
  EXPECT_TRUE(good[0].accepted) << good[0].message;
}

TEST_F(PoseEstimatorTest, WithoutTheOdometryOnlyFilter) {
  PoseFusionOptions o;
  o.odometry_only = false;
  Make(o);
  Feed(0.0, 1.0);
  EXPECT_TRUE(est_->started());
  EXPECT_EQ(est_->odometry_only(), nullptr);
}

TEST(PoseFusionOptions, ParametersKeepTheirKeysAndDefaults) {
  ParamSet ps("dl-pose");
  DeclareParams<PoseFusionOptions>(ps, "");
  EXPECT_EQ(ps.GetString("ephemeris.mode"), "season");
  EXPECT_DOUBLE_EQ(ps.GetDouble("sun.max_rate_deg_s"), 0.2);
  EXPECT_TRUE(ps.GetBool("odometry_only.enabled"));
  EXPECT_EQ(ps.GetInt("start.level_samples"), 1000);
  ASSERT_TRUE(
      ps.LoadYamlString("sun:\n  min_elevation_deg: 10\nephemeris:\n  run_start_s: 5\n", "p.yaml")
          .ok());
  auto o = ReadParams<PoseFusionOptions>(ps, "");
  ASSERT_TRUE(o.ok()) << o.status().ToString();
  EXPECT_NEAR(o->sun_min_elevation, 10.0 * kDegree, 1e-15);
  EXPECT_EQ(o->run_start_s, 5.0);
  EXPECT_NEAR(o->sun_max_rate, 0.2 * kDegree, 1e-15);
}

}  // namespace
}  // namespace rover::dl::pose
