#include "rover/ddl/motor/motor_types.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rover::ddl::motor {
namespace {

TEST(MotorTypes, NamesAreStable) {
  // GroupMode, GroupState and MotorFault names: core/msg/test/motor_test.cpp.
  EXPECT_EQ(std::string(CommandErrorName(CommandError::kTimeoutTooShort)), "timeout_too_short");
}

TEST(MotorTypes, DecodeTelemetryUsesTheCalibration) {
  const HardwareConfig config;
  hw::MotorTelemetry t;
  t.stamp_ns = 42;
  t.command_id = 5;
  const double cpr = config.motors[hw::kSteerRF].CountsPerRad();
  t.motors[hw::kSteerRF].position = static_cast<std::int32_t>(std::lround(0.3 * cpr));
  t.motors[hw::kSteerRF].velocity = static_cast<std::int32_t>(std::lround(-0.1 * cpr));
  t.motors[hw::kSteerRF].current_adc =
      static_cast<std::uint16_t>(config.telemetry.CountsFromCurrent(0.5));
  t.motors[hw::kSteerRF].temperature_adc =
      static_cast<std::uint16_t>(config.telemetry.CountsFromTemperature(-25.0));
  t.motors[hw::kSteerRF].flags = hw::kMotorFlagStall;
  const MotorReadings r = DecodeMotorTelemetry(config, t);
  EXPECT_EQ(r.stamp_ns, 42);
  EXPECT_EQ(r.command_id, 5u);
  EXPECT_NEAR(r.position[hw::kSteerRF], 0.3, 0.5 / cpr);
  EXPECT_NEAR(r.velocity[hw::kSteerRF], -0.1, 0.5 / cpr);
  EXPECT_NEAR(r.current[hw::kSteerRF], 0.5, 1e-3);
  EXPECT_NEAR(r.temperature[hw::kSteerRF], -25.0, 0.1);
  EXPECT_EQ(r.flags[hw::kSteerRF], hw::kMotorFlagStall);
}

TEST(MotorTypes, OptionsValidateAndLoad) {
  EXPECT_TRUE(MotorManagerOptions().Validate().ok());
  MotorManagerOptions o;
  o.stall_fraction = 2.0;
  EXPECT_FALSE(o.Validate().ok());
  o = MotorManagerOptions();
  o.timeout_factor = 0.5;
  EXPECT_FALSE(o.Validate().ok());

  ParamSet ps("ddl_motor");
  DeclareMotorManagerParams(ps);
  ASSERT_TRUE(ps.LoadYamlString("motor_manager:\n  stall_window_s: 2.0\n  brake_when_done: false\n",
                                "m.yaml")
                  .ok());
  auto loaded = MotorManagerOptionsFromParams(ps);
  ASSERT_TRUE(loaded.ok()) << loaded.status().ToString();
  EXPECT_EQ(loaded->stall_window_s, 2.0);
  EXPECT_FALSE(loaded->brake_when_done);
  ParamSet bad("ddl_motor");
  DeclareMotorManagerParams(bad);
  ASSERT_TRUE(bad.LoadYamlString("motor_manager:\n  stall_fraction: 0\n", "m.yaml").ok());
  auto r = MotorManagerOptionsFromParams(bad);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(),
            "m.yaml:2: key 'motor_manager.stall_fraction': 0 is out of range [0.01, 1]");
}

}  // namespace
}  // namespace rover::ddl::motor
