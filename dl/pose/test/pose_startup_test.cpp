#include "rover/dl/pose/pose_startup.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <optional>
#include <random>

#include "pose_test_support.hpp"
#include "rover/base/units.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::dl::pose {
namespace {

EkfOptions Ekf() {
  EkfOptions o;
  o.gravity = kMarsGravity;
  return o;
}

using testing::T;

// The specific force at rest for a rover at roll, pitch (any yaw).
Eigen::Vector3d AtRest(double roll, double pitch) {
  return geometry::RotationFromRpy(roll, pitch, 1.0).transpose() *
         Eigen::Vector3d(0, 0, kMarsGravity);
}

TEST(PoseStartup, LevelFromSpecificForceInvertsTheModel) {
  const Eigen::Vector2d rp = LevelFromSpecificForce(AtRest(0.1, -0.2));
  EXPECT_NEAR(rp.x(), 0.1, 1e-12);
  EXPECT_NEAR(rp.y(), -0.2, 1e-12);
}

TEST(PoseStartup, LevelsOnAStationaryStretchWithTheMeanGyroAsTheBias) {
  PoseStartOptions start;
  start.level_samples = 200;
  start.x = 1.0;
  start.yaw = 30.0 * kDegree;
  Leveller l(start, Ekf());
  std::mt19937_64 rng(7);
  std::normal_distribution<double> noise(0.0, 1e-4);
  const Eigen::Vector3d bias(2e-4, -1e-4, 3e-4);
  const Eigen::Vector3d f = AtRest(3.0 * kDegree, -2.0 * kDegree);
  // A few moving samples first (|w| above the threshold): they break the stretch.
  for (int k = 0; k < 10; ++k) {
    EXPECT_FALSE(l.Add(T(0.01 * k), Eigen::Vector3d(0, 0, 0.1), f).has_value());
  }
  std::optional<StartDecision> d;
  int k = 10;
  for (; k < 10 + 200 && !d.has_value(); ++k) {
    const Eigen::Vector3d w = bias + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    d = l.Add(T(0.01 * k), w, f);
  }
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(k, 210);  // exactly level_samples still samples
  EXPECT_TRUE(d->at_rest);
  EXPECT_EQ(d->samples, 200);
  EXPECT_NEAR(d->roll_pitch.x(), 3.0 * kDegree, 1e-9);
  EXPECT_NEAR(d->roll_pitch.y(), -2.0 * kDegree, 1e-9);
  EXPECT_LT((d->init.gyro_bias - bias).norm(), 3e-5);
  EXPECT_EQ(d->init.stamp, T(0.01 * 209));
  EXPECT_EQ(d->init.position, Eigen::Vector3d(1, 0, 0));
  EXPECT_NEAR(geometry::RpyFromRotation(d->init.attitude.toRotationMatrix()).z(), 30.0 * kDegree,
              1e-12);
  // The bias sigma is the standard error of the mean over the 1.99 s stretch.
  const double span = ToSeconds(T(0.01 * 209) - T(0.01 * 10));
  EXPECT_NEAR(span, 1.99, 1e-8);
  EXPECT_DOUBLE_EQ(d->init.gyro_bias_sigma, Ekf().gyro_noise_density / std::sqrt(span));
  EXPECT_EQ(d->init.rpy_sigma.z(), start.yaw_sigma);
  // It starts over: the next sample begins a new levelling.
  EXPECT_FALSE(l.Add(T(2.1), bias, f).has_value());
}

TEST(PoseStartup, WithoutAStillStretchItStartsFromThePlausibleSamplesAtTheTimeout) {
  PoseStartOptions start;
  start.level_samples = 1000;
  start.level_timeout_s = 1.0;
  Leveller l(start, Ekf());
  const Eigen::Vector3d f = AtRest(0.0, 5.0 * kDegree);
  std::optional<StartDecision> d;
  for (int k = 0; k <= 100 && !d.has_value(); ++k) {
    // Always turning; every third sample has an implausible |f| (a bump) and is not averaged.
    const Eigen::Vector3d fk = k % 3 == 0 ? Eigen::Vector3d(2.0 * f) : f;
    d = l.Add(T(10.0 + 0.01 * k), Eigen::Vector3d(0, 0, 0.05), fk);
  }
  ASSERT_TRUE(d.has_value());
  EXPECT_FALSE(d->at_rest);
  EXPECT_NEAR(d->waited_s, 1.0, 1e-9);
  EXPECT_EQ(d->samples, 67);  // k = 1, 2, 4, 5, ... 100
  EXPECT_NEAR(d->roll_pitch.y(), 5.0 * kDegree, 1e-9);
  EXPECT_EQ(d->init.gyro_bias, Eigen::Vector3d::Zero());
  EXPECT_EQ(d->init.gyro_bias_sigma, start.gyro_bias_sigma);

  // No plausible sample at all: level.
  Leveller none(start, Ekf());
  std::optional<StartDecision> n;
  for (int k = 0; k <= 100 && !n.has_value(); ++k) {
    n = none.Add(T(0.01 * k), Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 9.81));
  }
  ASSERT_TRUE(n.has_value());
  EXPECT_EQ(n->samples, 0);
  EXPECT_NEAR(n->roll_pitch.norm(), 0.0, 1e-12);
}

TEST(PoseStartup, WithoutBiasEstimationTheBiasIsZero) {
  PoseStartOptions start;
  start.level_samples = 5;
  start.estimate_gyro_bias = false;
  Leveller l(start, Ekf());
  std::optional<StartDecision> d;
  for (int k = 0; k < 5; ++k) d = l.Add(T(k * 0.01), Eigen::Vector3d(0, 0, 0.005), AtRest(0, 0));
  ASSERT_TRUE(d.has_value());
  EXPECT_EQ(d->init.gyro_bias, Eigen::Vector3d::Zero());
  EXPECT_EQ(d->init.gyro_bias_sigma, start.gyro_bias_sigma);
}

TEST(PoseStartup, ParametersKeepTheirKeysAndDefaults) {
  ParamSet ps("dl-pose");
  DeclareParams<PoseStartOptions>(ps, "start.");
  EXPECT_DOUBLE_EQ(ps.GetDouble("start.tilt_sigma_deg"), 1.0);
  EXPECT_DOUBLE_EQ(ps.GetDouble("start.yaw_sigma_deg"), 5.0);
  EXPECT_EQ(ps.GetInt("start.level_samples"), 1000);
  ASSERT_TRUE(
      ps.LoadYamlString("start:\n  yaw_deg: 90\n  y: 2\n  level_samples: 10\n", "s.yaml").ok());
  auto o = ReadParams<PoseStartOptions>(ps, "start.");
  ASSERT_TRUE(o.ok()) << o.status().ToString();
  EXPECT_NEAR(o->yaw, 90.0 * kDegree, 1e-15);
  EXPECT_EQ(o->y, 2.0);
  EXPECT_EQ(o->level_samples, 10);
  EXPECT_DOUBLE_EQ(o->tilt_sigma, PoseStartOptions().tilt_sigma);
}

}  // namespace
}  // namespace rover::dl::pose
