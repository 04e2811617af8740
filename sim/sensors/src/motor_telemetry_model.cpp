#include "rover/sim/sensors/motor_telemetry_model.hpp"

#include <algorithm>
#include <cmath>

#include "rover/base/check.hpp"

namespace rover::sim::sensors {

std::uint16_t ToAdc12(double counts) {
  if (std::isnan(counts)) return 0;
  return static_cast<std::uint16_t>(std::llround(std::clamp(counts, 0.0, double{hw::kAdcMax})));
}

std::uint16_t MotorFlags(const MotorPhysical& m) {
  std::uint16_t f = 0;
  if (m.enabled) f |= hw::kMotorFlagEnabled;
  if (m.at_goal) f |= hw::kMotorFlagAtGoal;
  if (m.stall) f |= hw::kMotorFlagStall;
  if (m.over_current) f |= hw::kMotorFlagOverCurrent;
  if (m.over_temp) f |= hw::kMotorFlagOverTemp;
  return f;
}

MotorTelemetryModel::MotorTelemetryModel(const HardwareConfig& config,
                                         const MotorTelemetryErrors& errors, double noise_scale,
                                         std::uint64_t seed)
    : spec_(config.telemetry), errors_(errors), rng_(seed) {
  ROVER_DEMAND(noise_scale >= 0.0);
  sigma_ = noise_scale * spec_.adc_noise_counts;
  for (int i = 0; i < hw::kNumMotors; ++i) {
    encoders_[static_cast<std::size_t>(i)] =
        EncoderModel(config.motors[static_cast<std::size_t>(i)]);
  }
}

const EncoderModel& MotorTelemetryModel::encoder(int motor) const {
  ROVER_DEMAND(motor >= 0 && motor < hw::kNumMotors);
  return encoders_[static_cast<std::size_t>(motor)];
}

hw::MotorTelemetry MotorTelemetryModel::Pack(
    const std::array<MotorPhysical, hw::kNumMotors>& motors, std::uint32_t command_id, Time stamp) {
  hw::MotorTelemetry t;
  t.stamp_ns = stamp.ns;
  t.command_id = command_id;
  for (std::size_t i = 0; i < motors.size(); ++i) {
    const MotorPhysical& m = motors[i];
    hw::MotorReading& r = t.motors[i];
    r.position = encoders_[i].RegisterCounts(m.position_rad);
    r.velocity = encoders_[i].RateCounts(m.velocity_rad_s);
    const double i_counts =
        spec_.current_offset_counts + errors_.current_offset_error_counts +
        spec_.current_counts_per_amp * (1.0 + errors_.current_gain_error) * m.current_a;
    r.current_adc = ToAdc12(i_counts + rng_.Normal(sigma_));
    const double t_counts =
        spec_.CountsFromTemperature(m.temperature_c + errors_.temperature_offset_error_c);
    r.temperature_adc = ToAdc12(t_counts + rng_.Normal(sigma_));
    r.flags = MotorFlags(m);
  }
  return t;
}

}  // namespace rover::sim::sensors
