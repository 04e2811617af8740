#include "rover/ddl/imu/imu_driver.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>

#ifdef ROVER_HAVE_SIM_SENSORS
#include "rover/sim/sensors/imu_model.hpp"
#include "rover/sim/sensors/sim_sensor_options.hpp"
#endif

namespace rover::ddl::imu {
namespace {

// Exact nominal encoding (the measurement model without noise).
hw::ImuRaw Encode(const ImuSpec& s, const Eigen::Vector3d& w, const Eigen::Vector3d& f) {
  hw::ImuRaw raw;
  const Eigen::Vector3d yg =
      s.gyro.ScaleMisalignment() * s.rover_from_case.transpose() * w + s.gyro.bias;
  const Eigen::Vector3d ya =
      s.accel.ScaleMisalignment() * s.rover_from_case.transpose() * f + s.accel.bias;
  for (int i = 0; i < 3; ++i) {
    raw.gyro[static_cast<std::size_t>(i)] =
        static_cast<std::int32_t>(std::lround(yg[i] / s.gyro.lsb));
    raw.accel[static_cast<std::size_t>(i)] =
        static_cast<std::int32_t>(std::lround(ya[i] / s.accel.lsb));
  }
  raw.temperature = 1234;
  return raw;
}

TEST(ImuDriver, InvertsTheNominalCalibration) {
  const ImuSpec spec;
  auto driver = ImuDriver::Create(spec);
  ASSERT_TRUE(driver.ok());
  const Eigen::Vector3d w(0.02, -0.5, 1.1), f(0.4, -0.2, 3.711);
  hw::ImuRaw raw = Encode(spec, w, f);
  raw.stamp_ns = 77;
  const Imu imu = driver->Convert(raw);
  EXPECT_EQ(imu.stamp.ns, 77);
  EXPECT_EQ(imu.health, msg::SensorHealth::kOk);
  EXPECT_LT((imu.angular_velocity - w).cwiseAbs().maxCoeff(), spec.gyro.lsb);
  EXPECT_LT((imu.linear_acceleration - f).cwiseAbs().maxCoeff(), spec.accel.lsb);
  EXPECT_NEAR(imu.temperature, 12.34, 1e-12);
}

TEST(ImuDriver, HealthFromStatusBitsAndRanges) {
  const ImuSpec spec;
  auto driver = ImuDriver::Create(spec);
  ASSERT_TRUE(driver.ok());
  hw::ImuRaw raw = Encode(spec, Eigen::Vector3d::Zero(), Eigen::Vector3d(0, 0, 3.71));
  raw.status = hw::kImuGyroSaturated;
  EXPECT_EQ(driver->Convert(raw).health, msg::SensorHealth::kDegraded);
  EXPECT_EQ(driver->Convert(raw).health_reason, "gyro saturated");
  raw.status = hw::kImuAccelSaturated;
  EXPECT_EQ(driver->Convert(raw).health, msg::SensorHealth::kDegraded);
  raw.status = hw::kImuSelfTestFail | hw::kImuGyroSaturated;
  EXPECT_EQ(driver->Convert(raw).health, msg::SensorHealth::kFailed);
  raw.status = 0;
  raw.gyro[1] = 2'000'000'000;  // corrupt: 2000 rad/s, beyond the 17.45 rad/s full scale
  const Imu bad = driver->Convert(raw);
  EXPECT_EQ(bad.health, msg::SensorHealth::kFailed);
  EXPECT_NE(bad.health_reason.find("gyro y"), std::string::npos);
}

TEST(ImuDriver, RejectsASingularCalibration) {
  ImuSpec spec;
  spec.accel.scale = Eigen::Vector3d(1.0, 1.0, 0.6);
  spec.accel.misalignment.setZero();
  spec.accel.misalignment(0, 1) = 0.1;
  spec.accel.misalignment(1, 0) = 0.1;
  EXPECT_TRUE(ImuDriver::Create(spec).ok());  // still well conditioned (det K = 0.59)
  spec.accel.scale = Eigen::Vector3d(1.0, 1.0, 0.5);
  EXPECT_FALSE(ImuDriver::Create(spec).ok());  // det K = 0.495: nearly singular
  spec.accel.scale = Eigen::Vector3d::Ones();
  spec.rover_from_case(0, 0) = 2.0;  // not a rotation
  EXPECT_FALSE(ImuDriver::Create(spec).ok());
}

#ifdef ROVER_HAVE_SIM_SENSORS
TEST(ImuDriver, RoundTripThroughTheSimulatedImu) {
  const ImuSpec spec;
  auto driver = ImuDriver::Create(spec);
  ASSERT_TRUE(driver.ok());
  sim::sensors::ImuModel ideal(spec, sim::sensors::ImuErrors{}, 0.0, 1);
  sim::sensors::ImuTruth truth;
  truth.angular_velocity_rover = Eigen::Vector3d(0.1, 0.2, -0.3);
  truth.specific_force_rover = Eigen::Vector3d(-0.5, 0.25, 3.71);
  truth.temperature_c = -33.21;
  const Imu imu = driver->Convert(ideal.Sample(truth, Time{}));
  EXPECT_EQ(imu.health, msg::SensorHealth::kOk);
  EXPECT_LT((imu.angular_velocity - truth.angular_velocity_rover).cwiseAbs().maxCoeff(),
            spec.gyro.lsb);
  EXPECT_LT((imu.linear_acceleration - truth.specific_force_rover).cwiseAbs().maxCoeff(),
            spec.accel.lsb);
  EXPECT_NEAR(imu.temperature, -33.21, 0.005 + 1e-12);

  // Saturation in the simulator -> DEGRADED from the driver.
  truth.angular_velocity_rover = Eigen::Vector3d(0.0, 0.0, 30.0);
  EXPECT_EQ(driver->Convert(ideal.Sample(truth, Time{10'000'000})).health,
            msg::SensorHealth::kDegraded);
}

TEST(ImuDriver, SimulatorCalibrationErrorsShowUpInTheOutput) {
  // The simulator's TRUE calibration differs from the nominal one the driver uses. Averaged
  // over 10 s at rest the driver's output is off by exactly the modelled error.
  const ImuSpec spec;
  auto driver = ImuDriver::Create(spec);
  ASSERT_TRUE(driver.ok());
  sim::sensors::ImuErrors errors =
      sim::sensors::SimSensorOptions().imu;                     // defaults: bias, scale, mounting
  errors.gyro_bias_error = Eigen::Vector3d(1e-4, -5e-5, 2e-5);  // 20 deg/h: visible in 10 s
  sim::sensors::ImuModel imu(spec, errors, 1.0, 42);
  sim::sensors::ImuTruth truth;
  truth.specific_force_rover = Eigen::Vector3d(0.0, 0.0, 3.71);
  Eigen::Vector3d mean_w = Eigen::Vector3d::Zero(), mean_f = Eigen::Vector3d::Zero();
  const int n = 1000;
  for (int k = 0; k < n; ++k) {
    const Imu out = driver->Convert(imu.Sample(truth, Time{k * 10'000'000LL}));
    mean_w += out.angular_velocity / n;
    mean_f += out.linear_acceleration / n;
  }
  const Eigen::Matrix3d decode_g = spec.rover_from_case * spec.gyro.ScaleMisalignment().inverse();
  const Eigen::Matrix3d decode_a = spec.rover_from_case * spec.accel.ScaleMisalignment().inverse();
  const Eigen::Vector3d expect_w = decode_g * errors.gyro_bias_error;
  const Eigen::Matrix3d k_true_a =
      (Eigen::Vector3d::Ones() + errors.accel_scale_error).asDiagonal() *
      spec.accel.ScaleMisalignment();
  const Eigen::Vector3d expect_f =
      decode_a * (k_true_a * imu.TrueRoverFromCase().transpose() * truth.specific_force_rover +
                  errors.accel_bias_error);
  const double sw = spec.gyro.SampleSigma(spec.rate_hz) / std::sqrt(double{n});
  const double sa = spec.accel.SampleSigma(spec.rate_hz) / std::sqrt(double{n});
  EXPECT_LT((mean_w - expect_w).cwiseAbs().maxCoeff(), 4.0 * sw + 2e-7);
  EXPECT_LT((mean_f - expect_f).cwiseAbs().maxCoeff(), 4.0 * sa + 1e-4);
  // ... and the errors are well above the averaged noise: calibration matters.
  EXPECT_GT(expect_w.norm(), 10.0 * sw);
  EXPECT_GT((expect_f - truth.specific_force_rover).norm(), 10.0 * sa);
}
#else
TEST(ImuDriver, RoundTripThroughTheSimulatedImu) {
  GTEST_SKIP() << "sim/sensors is not part of this build (ROVER_MODULE_FILTER)";
}
#endif

}  // namespace
}  // namespace rover::ddl::imu
