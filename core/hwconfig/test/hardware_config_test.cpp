#include "rover/hwconfig/hardware_config.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace rover {
namespace {

const std::string kDefaultFile =
    std::string(ROVER_SOURCE_DIR) + "/deploy/config/rover_hardware.yaml";

TEST(HardwareConfig, DefaultsAreValid) {
  const HardwareConfig c;
  ASSERT_TRUE(c.Validate().ok()) << c.Validate().ToString();
  EXPECT_NEAR(c.motors[hw::kDriveLF].CountsPerRad(), 64.0 * 1500.0 / (2.0 * M_PI), 1e-9);
  EXPECT_FALSE(c.motors[hw::kDriveRR].HasLimits());
  EXPECT_TRUE(c.motors[hw::kSteerLF].HasLimits());
  EXPECT_EQ(MotorKindOf(hw::kMastPan), MotorKind::kMastPan);
  EXPECT_EQ(MotorKindOf(hw::kSteerRR), MotorKind::kSteer);
}

TEST(HardwareConfig, DeployFileLoadsAndMatchesTheCodeDefaults) {
  auto loaded = LoadHardwareConfig(kDefaultFile);
  ASSERT_TRUE(loaded.ok()) << loaded.status().ToString();
  const HardwareConfig d;
  for (int i = 0; i < hw::kNumMotors; ++i) {
    const auto k = static_cast<std::size_t>(i);
    EXPECT_DOUBLE_EQ(loaded->motors[k].CountsPerRad(), d.motors[k].CountsPerRad()) << i;
    EXPECT_DOUBLE_EQ(loaded->motors[k].max_rate, d.motors[k].max_rate) << i;
    EXPECT_DOUBLE_EQ(loaded->motors[k].current_limit, d.motors[k].current_limit) << i;
    EXPECT_EQ(loaded->motors[k].HasLimits(), d.motors[k].HasLimits()) << i;
  }
  EXPECT_EQ(loaded->pots.offset_counts, d.pots.offset_counts);
  EXPECT_EQ(loaded->pots.gain_counts_per_rad, d.pots.gain_counts_per_rad);
  EXPECT_LT((loaded->imu.rover_from_case - d.imu.rover_from_case).norm(), 1e-12);
  EXPECT_LT((loaded->imu.gyro.ScaleMisalignment() - d.imu.gyro.ScaleMisalignment()).norm(), 1e-15);
  EXPECT_LT((loaded->imu.accel.bias - d.imu.accel.bias).norm(), 1e-15);
  EXPECT_LT((loaded->sun_sensor.rover_from_sensor - d.sun_sensor.rover_from_sensor).norm(), 1e-12);
  EXPECT_NEAR(loaded->sun_sensor.fov, d.sun_sensor.fov, 1e-12);
}

TEST(HardwareConfig, ConversionsInvertEachOther) {
  const HardwareConfig c;
  EXPECT_NEAR(c.telemetry.CurrentFromCounts(c.telemetry.CountsFromCurrent(0.73)), 0.73, 1e-12);
  EXPECT_NEAR(c.telemetry.TemperatureFromCounts(c.telemetry.CountsFromTemperature(-55.5)), -55.5,
              1e-12);
  for (int p = 0; p < hw::kNumPots; ++p) {
    EXPECT_NEAR(c.pots.AngleFromCounts(p, c.pots.CountsFromAngle(p, 0.31)), 0.31, 1e-12);
  }
  // Mirrored right-side pots read the opposite way.
  EXPECT_LT(c.pots.CountsFromAngle(hw::kRightRocker, 0.2), c.pots.offset_counts[1]);
  // The IMU's default mounting: case x along rover y.
  EXPECT_LT((c.imu.rover_from_case * Eigen::Vector3d::UnitX() - Eigen::Vector3d::UnitY()).norm(),
            1e-12);
  // Sun sensor boresight up, columns to the right.
  EXPECT_LT(
      (c.sun_sensor.rover_from_sensor * Eigen::Vector3d::UnitZ() - Eigen::Vector3d::UnitZ()).norm(),
      1e-12);
  EXPECT_LT(
      (c.sun_sensor.rover_from_sensor * Eigen::Vector3d::UnitX() + Eigen::Vector3d::UnitY()).norm(),
      1e-12);
  EXPECT_TRUE(c.sun_sensor.SpotInFieldOfView(0.0, 0.0));
  EXPECT_TRUE(c.sun_sensor.SpotInFieldOfView(2000.0 * std::tan(1.04), 0.0));
  EXPECT_FALSE(c.sun_sensor.SpotInFieldOfView(2000.0 * std::tan(1.06), 0.0));
}

TEST(HardwareConfig, RangeErrorsNameFileLineAndKey) {
  ParamSet ps("hardware");
  DeclareHardwareParams(ps);
  ASSERT_TRUE(ps.LoadYamlString("motors:\n  drive:\n    gear_ratio: 0.5\n", "hw.yaml").ok());
  auto c = HardwareConfigFromParams(ps);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.status().message(),
            "hw.yaml:3: key 'motors.drive.gear_ratio': 0.5 is out of range [1, 1e+06]");
}

TEST(HardwareConfig, CrossFieldErrorsNameFileLineAndKeyWithPrefix) {
  ParamSet ps("ddl_motor");
  DeclareHardwareParams(ps, "hardware");
  ASSERT_TRUE(
      ps.LoadYamlString("hardware:\n  motors:\n    steer:\n      min_angle: 2.0\n", "x.yaml").ok());
  auto c = HardwareConfigFromParams(ps, "hardware");
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.status().message(),
            "x.yaml:4: key 'hardware.motors.steer.min_angle': 2 must be below max_angle 1.6");

  ParamSet ps2("hardware");
  DeclareHardwareParams(ps2);
  ASSERT_TRUE(ps2.LoadYamlString(
                     "imu:\n  gyro:\n    misalignment: [0.01, 0, 0, 0, 0, 0, 0, 0, 0]\n", "m.yaml")
                  .ok());
  auto c2 = HardwareConfigFromParams(ps2);
  ASSERT_FALSE(c2.ok());
  EXPECT_NE(c2.status().message().find("m.yaml:3: key 'imu.gyro.misalignment'"), std::string::npos)
      << c2.status().message();

  ParamSet ps3("hardware");
  DeclareHardwareParams(ps3);
  ASSERT_TRUE(ps3.LoadYamlString("sun_sensor:\n  min_intensity: 4000\n", "s.yaml").ok());
  auto c3 = HardwareConfigFromParams(ps3);
  ASSERT_FALSE(c3.ok());
  EXPECT_EQ(c3.status().message(),
            "s.yaml:2: key 'sun_sensor.min_intensity': 4000 must be below full_scale_intensity "
            "3500");
}

TEST(HardwareConfig, UnknownKeysAndWrongSizesAreRejected) {
  ParamSet ps("hardware");
  DeclareHardwareParams(ps);
  const Status s = ps.LoadYamlString("pots:\n  ofset_counts: [1, 2, 3, 4]\n", "p.yaml");
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("did you mean 'pots.offset_counts'"), std::string::npos)
      << s.message();
  ParamSet ps2("hardware");
  DeclareHardwareParams(ps2);
  ASSERT_TRUE(ps2.LoadYamlString("pots:\n  offset_counts: [1, 2, 3]\n", "p.yaml").ok());
  auto c = HardwareConfigFromParams(ps2);
  ASSERT_FALSE(c.ok());
  EXPECT_NE(c.status().message().find("p.yaml:2: key 'pots.offset_counts': expected 4 numbers"),
            std::string::npos)
      << c.status().message();
}

TEST(HardwareConfig, MissingFileIsNotFound) {
  auto c = LoadHardwareConfig("/nonexistent/rover_hardware.yaml");
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.status().code(), StatusCode::kNotFound);
}

}  // namespace
}  // namespace rover
