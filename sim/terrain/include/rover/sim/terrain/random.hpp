#pragma once
/// @file
/// Portable, seeded random numbers for the terrain generator (and anything else in the simulator
/// that must be reproducible bit for bit).
///
/// The engine is std::mt19937_64, whose output sequence the C++ standard fixes exactly. The
/// std::*_distribution classes are *not* fixed by the standard (libstdc++ and libc++ give
/// different numbers), so the transforms below are our own:
///   Uniform()  = (bits >> 11) * 2^-53                 in [0, 1), 53 random bits
///   Normal()   = Box-Muller on two uniforms, no caching (each call draws two words)
///   UniformInt = Lemire-free modulo with rejection    unbiased, in [0, n)
/// Results are identical on every platform that has the same libm (std::log, std::cos); across
/// different libm implementations Normal() may differ in the last bit.

#include <cstdint>
#include <random>

namespace rover::sim::terrain {

/// SplitMix64 finaliser of (seed, stream): derives independent sub-seeds, so that e.g. the rock
/// stream does not change when the hill parameters change.
std::uint64_t MixSeed(std::uint64_t seed, std::uint64_t stream);

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}

  /// 64 raw bits.
  std::uint64_t Bits() { return engine_(); }
  /// Uniform in [0, 1).
  double Uniform() { return static_cast<double>(engine_() >> 11) * 0x1.0p-53; }
  /// Uniform in [lo, hi).
  double Uniform(double lo, double hi) { return lo + (hi - lo) * Uniform(); }
  /// Uniform in (0, 1]: safe for log().
  double UniformPositive() { return static_cast<double>((engine_() >> 11) + 1) * 0x1.0p-53; }
  /// Uniform integer in [0, n). Precondition: n >= 1.
  std::uint64_t UniformInt(std::uint64_t n);
  /// Standard normal N(0, 1) (Box-Muller).
  double Normal();

 private:
  std::mt19937_64 engine_;
};

}  // namespace rover::sim::terrain
