#pragma once
/// @file
/// Rocker and bogie potentiometers read by a 12-bit ADC (hw/suspension_pots).
///
///   adc_i = clamp(round((o_i + e_o,i) + g_i (1 + e_g,i) angle_i + n), 0, 4095)
/// o, g: nominal offset [counts] and gain [counts/rad] (PotSpec, negative for a mirrored pot);
/// e: the simulator's true-vs-nominal errors (PotErrors); n ~ N(0, (noise_scale noise_counts)^2).
/// Angles beyond the electrical range saturate at the ADC rails (0 or 4095), as a real wiper at
/// the end of its track does. Angle order and signs: hw::PotIndex, + raises the front.

#include <array>
#include <cstdint>

#include "rover/base/time.hpp"
#include "rover/hwconfig/hardware_config.hpp"
#include "rover/sim/sensors/sampling.hpp"

namespace rover::sim::sensors {

struct PotErrors {
  std::array<double, hw::kNumPots> offset_error_counts{};  ///< [counts] true - nominal
  std::array<double, hw::kNumPots> gain_error{};           ///< relative (0.01 = 1 % steeper)
};

class SuspensionPotModel {
 public:
  /// Preconditions: spec valid, noise_scale >= 0.
  SuspensionPotModel(const PotSpec& spec, const PotErrors& errors, double noise_scale,
                     std::uint64_t seed);

  /// angles [rad]: left rocker, right rocker, left bogie, right bogie.
  hw::SuspensionPots Sample(const std::array<double, hw::kNumPots>& angles, Time stamp);

  /// Noise-free true ADC value (unclamped, unrounded) of pot i at `angle`.
  double TrueCounts(int pot, double angle) const;

 private:
  PotSpec spec_;
  PotErrors errors_;
  double sigma_ = 0.0;
  NoiseRng rng_;
};

}  // namespace rover::sim::sensors
