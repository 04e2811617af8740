#include "rover/sim/sensors/imu_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "rover/geometry/transforms.hpp"

namespace rover::sim::sensors {
namespace {

Eigen::Vector3d Decode(const std::array<std::int32_t, 3>& raw, const InertialSensorSpec& s,
                       const Eigen::Matrix3d& rover_from_case) {
  const Eigen::Vector3d y(raw[0] * s.lsb, raw[1] * s.lsb, raw[2] * s.lsb);
  return rover_from_case * s.ScaleMisalignment().inverse() * (y - s.bias);
}

Time At(int k, double rate_hz) { return Time{std::llround(k * 1e9 / rate_hz)}; }

TEST(ImuModel, IdealSampleRoundTripsThroughTheNominalCalibration) {
  const ImuSpec spec;
  ImuModel imu(spec, {}, 0.0, 1);
  ImuTruth truth;
  truth.angular_velocity_rover = Eigen::Vector3d(0.01, -0.2, 0.35);
  truth.specific_force_rover = Eigen::Vector3d(0.3, -0.1, 3.71);
  truth.temperature_c = 25.37;
  const hw::ImuRaw raw = imu.Sample(truth, Time{5});
  EXPECT_EQ(raw.stamp_ns, 5);
  EXPECT_EQ(raw.status, 0);
  EXPECT_EQ(raw.temperature, 2537);
  const Eigen::Vector3d w = Decode(raw.gyro, spec.gyro, spec.rover_from_case);
  const Eigen::Vector3d f = Decode(raw.accel, spec.accel, spec.rover_from_case);
  EXPECT_LT((w - truth.angular_velocity_rover).cwiseAbs().maxCoeff(), 1.0 * spec.gyro.lsb);
  EXPECT_LT((f - truth.specific_force_rover).cwiseAbs().maxCoeff(), 1.0 * spec.accel.lsb);
  // The case frame is rotated 90 deg about z: rover y rate is (mostly) on case -x.
  EXPECT_NEAR(raw.gyro[0] * spec.gyro.lsb, -0.2, 1e-3);
}

TEST(ImuModel, WhiteNoiseMatchesNoiseDensityTimesSqrtRate) {
  ImuSpec spec;
  spec.gyro.bias_random_walk = 0.0;
  spec.accel.bias_random_walk = 0.0;
  ImuModel imu(spec, {}, 1.0, 2024);
  const int n = 20000;
  Eigen::Vector3d sum_g = Eigen::Vector3d::Zero(), sum2_g = Eigen::Vector3d::Zero();
  Eigen::Vector3d sum_a = Eigen::Vector3d::Zero(), sum2_a = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) {
    const hw::ImuRaw raw = imu.Sample(ImuTruth{}, At(k, spec.rate_hz));
    for (int i = 0; i < 3; ++i) {
      const double g = raw.gyro[static_cast<std::size_t>(i)] * spec.gyro.lsb - spec.gyro.bias[i];
      const double a = raw.accel[static_cast<std::size_t>(i)] * spec.accel.lsb - spec.accel.bias[i];
      sum_g[i] += g;
      sum2_g[i] += g * g;
      sum_a[i] += a;
      sum2_a[i] += a * a;
    }
  }
  const double sg = spec.gyro.SampleSigma(spec.rate_hz);
  const double sa = spec.accel.SampleSigma(spec.rate_hz);
  for (int i = 0; i < 3; ++i) {
    const double mg = sum_g[i] / n, ma = sum_a[i] / n;
    EXPECT_NEAR(std::sqrt(sum2_g[i] / n - mg * mg), sg, 0.03 * sg) << i;
    EXPECT_NEAR(std::sqrt(sum2_a[i] / n - ma * ma), sa, 0.03 * sa) << i;
    EXPECT_NEAR(mg, 0.0, 4.0 * sg / std::sqrt(double{n})) << i;
  }
}

TEST(ImuModel, BiasRandomWalkVarianceGrowsLinearlyInTime) {
  ImuSpec spec;
  spec.gyro.noise_density = 0.0;
  spec.accel.noise_density = 0.0;
  spec.gyro.bias_random_walk = 1.0e-4;  // [rad/s/sqrt(s)], large enough to dwarf the LSB
  spec.accel.bias_random_walk = 2.0e-3;
  const int runs = 300;
  const int k1 = 1000, k2 = 4000;  // t = 10 s and 40 s at 100 Hz
  std::vector<double> g1, g2, a2;
  for (int r = 0; r < runs; ++r) {
    ImuModel imu(spec, {}, 1.0, SensorSeed(77, static_cast<std::uint64_t>(r)));
    for (int k = 0; k <= k2; ++k) {
      const hw::ImuRaw raw = imu.Sample(ImuTruth{}, At(k, spec.rate_hz));
      if (k == k1 || k == k2) {
        for (int i = 0; i < 3; ++i) {
          const double g =
              raw.gyro[static_cast<std::size_t>(i)] * spec.gyro.lsb - spec.gyro.bias[i];
          (k == k1 ? g1 : g2).push_back(g);
          if (k == k2) {
            a2.push_back(raw.accel[static_cast<std::size_t>(i)] * spec.accel.lsb -
                         spec.accel.bias[i]);
          }
        }
      }
    }
  }
  auto var = [](const std::vector<double>& v) {
    double s = 0.0, s2 = 0.0;
    for (double x : v) {
      s += x;
      s2 += x * x;
    }
    const double m = s / static_cast<double>(v.size());
    return s2 / static_cast<double>(v.size()) - m * m;
  };
  const double v1 = var(g1), v2 = var(g2);
  const double k_rw = spec.gyro.bias_random_walk;
  // 900 samples per estimate: relative standard error of a variance ~ sqrt(2/900) = 4.7 %.
  EXPECT_NEAR(v1, k_rw * k_rw * 10.0, 0.15 * k_rw * k_rw * 10.0);
  EXPECT_NEAR(v2, k_rw * k_rw * 40.0, 0.15 * k_rw * k_rw * 40.0);
  EXPECT_NEAR(v2 / v1, 4.0, 0.8);
  const double ka = spec.accel.bias_random_walk;
  EXPECT_NEAR(var(a2), ka * ka * 40.0, 0.15 * ka * ka * 40.0);
}

TEST(ImuModel, SaturationClipsAndFlags) {
  const ImuSpec spec;
  ImuModel imu(spec, {}, 0.0, 1);
  ImuTruth truth;
  truth.angular_velocity_rover = Eigen::Vector3d(0.0, 25.0, 0.0);  // beyond 17.45 rad/s
  truth.specific_force_rover = Eigen::Vector3d(0.0, 0.0, 9.81);
  hw::ImuRaw raw = imu.Sample(truth, Time{});
  EXPECT_EQ(raw.status, hw::kImuGyroSaturated);
  const auto max_lsb = static_cast<std::int32_t>(std::floor(spec.gyro.range / spec.gyro.lsb));
  for (auto g : raw.gyro) EXPECT_LE(std::abs(g), max_lsb);
  truth.angular_velocity_rover.setZero();
  truth.specific_force_rover = Eigen::Vector3d(500.0, 0.0, 0.0);
  truth.self_test_fail = true;
  raw = imu.Sample(truth, Time{10'000'000});
  EXPECT_EQ(raw.status, hw::kImuAccelSaturated | hw::kImuSelfTestFail);
  // Non-finite input does not produce garbage.
  truth.specific_force_rover = Eigen::Vector3d(std::nan(""), 0.0, 0.0);
  truth.temperature_c = std::nan("");
  raw = imu.Sample(truth, Time{20'000'000});
  EXPECT_EQ(raw.temperature, 0);
}

TEST(ImuModel, TrueErrorsBiasTheNominalDecoding) {
  const ImuSpec spec;
  ImuErrors errors;
  errors.gyro_bias_error = Eigen::Vector3d(1e-4, 0.0, 0.0);
  errors.mounting_error_rpy = Eigen::Vector3d(0.0, 0.0, 0.01);
  ImuModel imu(spec, errors, 0.0, 1);
  ImuTruth truth;
  truth.specific_force_rover = Eigen::Vector3d(0.0, 9.81, 0.0);
  const hw::ImuRaw raw = imu.Sample(truth, Time{});
  const Eigen::Vector3d w = Decode(raw.gyro, spec.gyro, spec.rover_from_case);
  const Eigen::Vector3d f = Decode(raw.accel, spec.accel, spec.rover_from_case);
  // Bias error on case x = rover y.
  EXPECT_NEAR(w.y(), 1e-4, 2e-6);
  // The case is yawed +0.01 rad beyond its nominal mounting, so the nominally decoded specific
  // force appears yawed by -0.01 rad.
  EXPECT_NEAR(std::atan2(-f.x(), f.y()), -0.01, 1e-4);
  EXPECT_LT((imu.TrueGyroBias() - spec.gyro.bias - errors.gyro_bias_error).norm(), 1e-15);
}

TEST(ImuModel, TurnOnBiasIsDrawnFromTheSeed) {
  const ImuSpec spec;
  ImuErrors errors;
  errors.gyro_bias_sigma = 1e-5;
  const ImuModel a(spec, errors, 1.0, 5), b(spec, errors, 1.0, 5), c(spec, errors, 1.0, 6);
  EXPECT_EQ(a.TrueGyroBias(), b.TrueGyroBias());
  EXPECT_NE(a.TrueGyroBias(), c.TrueGyroBias());
  EXPECT_LT((a.TrueGyroBias() - spec.gyro.bias).norm(), 6e-5);
}

}  // namespace
}  // namespace rover::sim::sensors
