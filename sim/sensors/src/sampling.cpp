#include "rover/sim/sensors/sampling.hpp"

#include <algorithm>
#include <cmath>

#include "rover/base/check.hpp"

namespace rover::sim::sensors {

std::uint64_t SensorSeed(std::uint64_t seed, std::uint64_t stream) {
  std::uint64_t z = seed + 0x9E3779B97F4A7C15ULL * (stream + 1);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

double NoiseRng::Normal() {
  constexpr double kTwoPi = 6.28318530717958647692;
  const double u1 = static_cast<double>((engine_() >> 11) + 1) * 0x1.0p-53;  // (0, 1]
  const double u2 = Uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(kTwoPi * u2);
}

SampleClock::SampleClock(double rate_hz) {
  ROVER_DEMAND(std::isfinite(rate_hz) && rate_hz > 0.0);
  period_ = Duration{std::max<std::int64_t>(1, std::llround(1e9 / rate_hz))};
}

bool SampleClock::Due(Time now) {
  if (!started_) {
    started_ = true;
    next_ = now + period_;
    return true;
  }
  if (now < next_) return false;
  // Skip any periods the caller stepped over; keep the phase of the schedule.
  const std::int64_t missed = (now - next_).count() / period_.count();
  next_ = next_ + Duration{(missed + 1) * period_.count()};
  return true;
}

}  // namespace rover::sim::sensors
