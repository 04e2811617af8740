#include "rover/sim/sensors/encoder_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace rover::sim::sensors {

std::int64_t EncoderModel::Counts(double angle_rad) const {
  const double c = angle_rad * counts_per_rad_;
  if (!std::isfinite(c)) return 0;
  constexpr double kMax = 9.0e18;
  return std::llround(std::clamp(c, -kMax, kMax));
}

std::int32_t EncoderModel::RegisterCounts(double angle_rad) const {
  return hw::WrapCounter(Counts(angle_rad));
}

std::int32_t EncoderModel::RateCounts(double rate_rad_s) const {
  const double c = rate_rad_s * counts_per_rad_;
  if (!std::isfinite(c)) return 0;
  constexpr double kLo = std::numeric_limits<std::int32_t>::min();
  constexpr double kHi = std::numeric_limits<std::int32_t>::max();
  return static_cast<std::int32_t>(std::llround(std::clamp(c, kLo, kHi)));
}

}  // namespace rover::sim::sensors
