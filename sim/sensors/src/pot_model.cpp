#include "rover/sim/sensors/pot_model.hpp"

#include "rover/base/check.hpp"
#include "rover/sim/sensors/motor_telemetry_model.hpp"

namespace rover::sim::sensors {

SuspensionPotModel::SuspensionPotModel(const PotSpec& spec, const PotErrors& errors,
                                       double noise_scale, std::uint64_t seed)
    : spec_(spec), errors_(errors), rng_(seed) {
  ROVER_DEMAND(noise_scale >= 0.0);
  sigma_ = noise_scale * spec_.noise_counts;
}

double SuspensionPotModel::TrueCounts(int pot, double angle) const {
  ROVER_DEMAND(pot >= 0 && pot < hw::kNumPots);
  const auto i = static_cast<std::size_t>(pot);
  return spec_.offset_counts[i] + errors_.offset_error_counts[i] +
         spec_.gain_counts_per_rad[i] * (1.0 + errors_.gain_error[i]) * angle;
}

hw::SuspensionPots SuspensionPotModel::Sample(const std::array<double, hw::kNumPots>& angles,
                                              Time stamp) {
  hw::SuspensionPots p;
  p.stamp_ns = stamp.ns;
  for (int i = 0; i < hw::kNumPots; ++i) {
    const auto k = static_cast<std::size_t>(i);
    p.adc[k] = ToAdc12(TrueCounts(i, angles[k]) + rng_.Normal(sigma_));
  }
  return p;
}

}  // namespace rover::sim::sensors
