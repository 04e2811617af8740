#pragma once
/// @file
/// Packs the physics engine's per-motor values into hw/motor_telemetry: encoder counts
/// (EncoderModel), 12-bit current and temperature ADC counts with noise, and the controller's
/// latched flags.
///
///   current_adc     = clamp(round(o_i + e_o + g_i (1 + e_g) I + n), 0, 4095)
///   temperature_adc = clamp(round(o_T + g_T (T + e_T) + n), 0, 4095)
/// with the nominal gains/offsets of MotorTelemetrySpec, the simulator's true-vs-nominal errors
/// e (MotorTelemetryErrors) and n ~ N(0, (noise_scale adc_noise_counts)^2).

#include <array>
#include <cstdint>

#include "rover/base/time.hpp"
#include "rover/hwconfig/hardware_config.hpp"
#include "rover/sim/sensors/encoder_model.hpp"
#include "rover/sim/sensors/sampling.hpp"

namespace rover::sim::sensors {

/// Ideal physical state of one motor (from the physics engine / motor controller).
struct MotorPhysical {
  double position_rad = 0.0;    ///< joint angle (cumulative for wheels)
  double velocity_rad_s = 0.0;  ///< joint rate
  double current_a = 0.0;       ///< winding current magnitude [A]
  double temperature_c = 0.0;   ///< winding temperature [deg C]
  bool enabled = false;         ///< powered (not braked / off)
  bool at_goal = false;         ///< position goal reached
  bool stall = false;           ///< latched faults
  bool over_current = false;
  bool over_temp = false;
};

/// True-vs-nominal errors of the telemetry ADCs (the driver only knows the nominal values).
struct MotorTelemetryErrors {
  double current_gain_error = 0.0;           ///< relative (0.01 = reads 1 % high)
  double current_offset_error_counts = 0.0;  ///< [counts]
  double temperature_offset_error_c = 0.0;   ///< [deg C]
};

/// hw flag bits of a MotorPhysical.
std::uint16_t MotorFlags(const MotorPhysical& m);

class MotorTelemetryModel {
 public:
  /// Preconditions: config.Validate() ok, noise_scale >= 0.
  MotorTelemetryModel(const HardwareConfig& config, const MotorTelemetryErrors& errors,
                      double noise_scale, std::uint64_t seed);

  /// One telemetry sample; `command_id` is the last applied MotorGoals::command_id.
  hw::MotorTelemetry Pack(const std::array<MotorPhysical, hw::kNumMotors>& motors,
                          std::uint32_t command_id, Time stamp);

  const EncoderModel& encoder(int motor) const;

 private:
  MotorTelemetrySpec spec_;
  MotorTelemetryErrors errors_;
  double sigma_ = 0.0;
  std::array<EncoderModel, hw::kNumMotors> encoders_;
  NoiseRng rng_;
};

/// round + clamp to the 12-bit ADC range; NaN gives 0.
std::uint16_t ToAdc12(double counts);

}  // namespace rover::sim::sensors
