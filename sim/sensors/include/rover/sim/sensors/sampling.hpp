#pragma once
/// @file
/// Seeded noise and sample scheduling for the simulated sensors.
///
/// NoiseRng: std::mt19937_64 (whose output the C++ standard fixes) with our own transforms, so
/// that a seed gives the same noise with every standard library:
///   Uniform() = (bits >> 11) 2^-53 in [0, 1);  Normal() = Box-Muller on two fresh uniforms
///   (no cached second value), sqrt(-2 ln u1) cos(2 pi u2) with u1 in (0, 1].
/// SensorSeed(seed, stream) derives independent per-sensor seeds (SplitMix64 finaliser), so that
/// adding noise to one sensor does not change the noise of another.
///
/// SampleClock: a sensor sampling at rate_hz produces samples at t0 + k period, period =
/// round(1e9 / rate_hz) ns on the run clock. Due(now) returns true once per period (the first
/// call always samples); if the caller steps over several periods only one sample is produced
/// and the schedule skips ahead (a real sensor would have produced the missed ones, but nobody
/// could have read them).

#include <cstdint>
#include <random>

#include "rover/base/time.hpp"

namespace rover::sim::sensors {

/// SplitMix64 finaliser of seed and stream: an independent sub-seed.
std::uint64_t SensorSeed(std::uint64_t seed, std::uint64_t stream);

class NoiseRng {
 public:
  explicit NoiseRng(std::uint64_t seed) : engine_(seed) {}
  /// Uniform in [0, 1).
  double Uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Standard normal N(0, 1).
  double Normal();
  /// N(0, sigma^2); sigma == 0 returns 0 without drawing.
  double Normal(double sigma) { return sigma == 0.0 ? 0.0 : sigma * Normal(); }

 private:
  std::mt19937_64 engine_;
};

class SampleClock {
 public:
  /// Precondition: rate_hz > 0 and finite.
  explicit SampleClock(double rate_hz);
  /// True if a sample is due at `now` (and schedules the next one).
  bool Due(Time now);
  /// Forget the schedule: the next Due() samples.
  void Reset() { started_ = false; }
  Duration period() const { return period_; }

 private:
  Duration period_;
  Time next_{};
  bool started_ = false;
};

}  // namespace rover::sim::sensors
