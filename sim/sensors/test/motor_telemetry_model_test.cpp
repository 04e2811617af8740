#include "rover/sim/sensors/motor_telemetry_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rover::sim::sensors {
namespace {

std::array<MotorPhysical, hw::kNumMotors> Motors(double current, double temperature) {
  std::array<MotorPhysical, hw::kNumMotors> m{};
  for (int i = 0; i < hw::kNumMotors; ++i) {
    auto& x = m[static_cast<std::size_t>(i)];
    x.position_rad = 0.1 * i;
    x.velocity_rad_s = 0.05 * i;
    x.current_a = current;
    x.temperature_c = temperature;
  }
  return m;
}

TEST(MotorTelemetryModel, IdealPackingMatchesTheNominalCalibration) {
  const HardwareConfig config;
  MotorTelemetryModel model(config, {}, 0.0, 1);
  auto motors = Motors(0.75, -40.0);
  motors[3].enabled = true;
  motors[3].at_goal = true;
  motors[5].stall = true;
  motors[7].over_current = true;
  motors[11].over_temp = true;
  const hw::MotorTelemetry t = model.Pack(motors, 77, Time{123});
  EXPECT_EQ(t.stamp_ns, 123);
  EXPECT_EQ(t.command_id, 77u);
  for (int i = 0; i < hw::kNumMotors; ++i) {
    const auto k = static_cast<std::size_t>(i);
    const hw::MotorReading& r = t.motors[k];
    const double cpr = config.motors[k].CountsPerRad();
    EXPECT_EQ(r.position, std::llround(0.1 * i * cpr));
    EXPECT_EQ(r.velocity, std::llround(0.05 * i * cpr));
    // Driver-side inverse recovers the value within half an ADC count.
    EXPECT_NEAR(config.telemetry.CurrentFromCounts(r.current_adc), 0.75,
                0.5 / config.telemetry.current_counts_per_amp);
    EXPECT_NEAR(config.telemetry.TemperatureFromCounts(r.temperature_adc), -40.0,
                0.5 / config.telemetry.temperature_counts_per_degc);
  }
  EXPECT_EQ(t.motors[3].flags, hw::kMotorFlagEnabled | hw::kMotorFlagAtGoal);
  EXPECT_EQ(t.motors[5].flags, hw::kMotorFlagStall);
  EXPECT_EQ(t.motors[7].flags, hw::kMotorFlagOverCurrent);
  EXPECT_EQ(t.motors[11].flags, hw::kMotorFlagOverTemp);
  EXPECT_EQ(t.motors[0].flags, 0);
}

TEST(MotorTelemetryModel, AdcValuesStayWithin12Bits) {
  const HardwareConfig config;
  MotorTelemetryModel model(config, {}, 10.0, 5);
  for (double current : {-5.0, 0.0, 1e9, std::nan("")}) {
    for (double temp : {-300.0, 400.0, std::numeric_limits<double>::infinity()}) {
      const hw::MotorTelemetry t = model.Pack(Motors(current, temp), 0, Time{});
      for (const auto& r : t.motors) {
        EXPECT_LE(r.current_adc, hw::kAdcMax);
        EXPECT_LE(r.temperature_adc, hw::kAdcMax);
      }
    }
  }
}

TEST(MotorTelemetryModel, AdcNoiseMatchesTheConfiguredSigma) {
  HardwareConfig config;
  config.telemetry.adc_noise_counts = 4.0;
  MotorTelemetryModel model(config, {}, 1.0, 99);
  const double mean_counts = config.telemetry.CountsFromCurrent(1.0);
  double sum = 0.0, sum2 = 0.0;
  int n = 0;
  for (int k = 0; k < 2000; ++k) {
    const hw::MotorTelemetry t = model.Pack(Motors(1.0, 20.0), 0, Time{});
    for (const auto& r : t.motors) {
      const double e = r.current_adc - mean_counts;
      sum += e;
      sum2 += e * e;
      ++n;
    }
  }
  const double mean = sum / n;
  const double var = sum2 / n - mean * mean;
  // Rounding adds 1/12 count^2 of uniform quantisation noise.
  EXPECT_NEAR(std::sqrt(var), std::sqrt(16.0 + 1.0 / 12.0), 0.03 * 4.0);
  EXPECT_NEAR(mean, 0.0, 0.05);
}

TEST(MotorTelemetryModel, TrueErrorsShiftTheReadings) {
  const HardwareConfig config;
  MotorTelemetryErrors errors;
  errors.current_gain_error = 0.05;
  errors.temperature_offset_error_c = 3.0;
  MotorTelemetryModel model(config, errors, 0.0, 1);
  const hw::MotorTelemetry t = model.Pack(Motors(1.0, 20.0), 0, Time{});
  EXPECT_NEAR(config.telemetry.CurrentFromCounts(t.motors[0].current_adc), 1.05, 1e-3);
  EXPECT_NEAR(config.telemetry.TemperatureFromCounts(t.motors[0].temperature_adc), 23.0, 0.04);
}

TEST(MotorTelemetryModel, SameSeedSameTelemetry) {
  const HardwareConfig config;
  MotorTelemetryModel a(config, {}, 1.0, 11), b(config, {}, 1.0, 11);
  for (int k = 0; k < 10; ++k) {
    const auto ta = a.Pack(Motors(0.5, 10.0), 1, Time{k});
    const auto tb = b.Pack(Motors(0.5, 10.0), 1, Time{k});
    for (std::size_t i = 0; i < ta.motors.size(); ++i) {
      EXPECT_EQ(ta.motors[i].current_adc, tb.motors[i].current_adc);
      EXPECT_EQ(ta.motors[i].temperature_adc, tb.motors[i].temperature_adc);
    }
  }
}

}  // namespace
}  // namespace rover::sim::sensors
