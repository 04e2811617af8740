#pragma once
/// @file
/// Time points and durations of the run clock, in integer nanoseconds. The run clock is wall time
/// (CLOCK_REALTIME) in deployment and sim/clock when a simulator drives the run (clock.hpp).

#include <chrono>
#include <cstdint>

namespace rover {

/// A duration in nanoseconds.
using Duration = std::chrono::nanoseconds;

/// A point on the run clock: nanoseconds since the clock's epoch (Unix epoch for wall time,
/// start of the run for simulated time).
struct Time {
  std::int64_t ns = 0;

  static constexpr Time FromSeconds(double s) {
    return Time{static_cast<std::int64_t>(s * 1e9)};
  }
  constexpr double seconds() const { return static_cast<double>(ns) * 1e-9; }

  friend constexpr Time operator+(Time t, Duration d) { return Time{t.ns + d.count()}; }
  friend constexpr Time operator-(Time t, Duration d) { return Time{t.ns - d.count()}; }
  friend constexpr Duration operator-(Time a, Time b) { return Duration{a.ns - b.ns}; }
  friend constexpr auto operator<=>(Time a, Time b) = default;
};

/// Seconds as a Duration.
constexpr Duration Seconds(double s) { return Duration{static_cast<std::int64_t>(s * 1e9)}; }
/// Duration as seconds.
constexpr double ToSeconds(Duration d) { return static_cast<double>(d.count()) * 1e-9; }

}  // namespace rover
