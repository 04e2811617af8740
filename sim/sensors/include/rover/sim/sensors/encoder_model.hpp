#pragma once
/// @file
/// Motor-shaft encoder behind a gearhead: joint angle [rad] -> hw encoder counts.
///
///   counts = round(angle * c),  c = MotorSpec::CountsPerRad() = counts_per_rev * gear_ratio / 2 pi
///   rate   = round(rate_rad_s * c)  [counts/s]  (the controller's velocity estimate)
/// The angle is cumulative (a wheel that turned 3 times is at 6 pi), so the count is unbounded;
/// the hw/ field is a free-running int32 register that wraps modulo 2^32
/// (hw::WrapCounter). Drivers accumulate hw::CounterDelta between samples and never see a wrap.
/// Quantisation: the count is the nearest integer, so the angle is known to +-0.5 / c rad.

#include <cstdint>

#include "rover/hwconfig/hardware_config.hpp"

namespace rover::sim::sensors {

class EncoderModel {
 public:
  EncoderModel() = default;
  explicit EncoderModel(const MotorSpec& spec) : counts_per_rad_(spec.CountsPerRad()) {}

  /// Unbounded count of a joint angle [rad]. Non-finite angles give 0.
  std::int64_t Counts(double angle_rad) const;
  /// The int32 register value (wraps modulo 2^32).
  std::int32_t RegisterCounts(double angle_rad) const;
  /// Rate [rad/s] -> counts/s, saturated to the int32 range; non-finite gives 0.
  std::int32_t RateCounts(double rate_rad_s) const;
  double counts_per_rad() const { return counts_per_rad_; }

 private:
  double counts_per_rad_ = 1.0;
};

}  // namespace rover::sim::sensors
