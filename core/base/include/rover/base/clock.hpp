#pragma once
/// @file
/// The one clock every timer, timeout, rate and timestamp goes through.
///
/// A service never reads std::chrono::system_clock for logic: it asks its Clock. In deployment
/// that is WallClock; in simulation it is the simulator's sim/clock (rover/runtime/sim_clock.hpp),
/// which may run faster or slower than real time, pause, or restart at zero on a reset.

#include <atomic>
#include <mutex>

#include "rover/base/time.hpp"

namespace rover {

class Clock {
 public:
  virtual ~Clock() = default;
  /// Current run-clock time. Before a simulated clock has received its first sample, returns
  /// Time{0} and valid() is false.
  virtual Time Now() const = 0;
  /// False while a simulated clock has not heard from the simulator yet.
  virtual bool valid() const { return true; }
  /// True when time comes from a simulator (may differ from wall time in rate and epoch).
  virtual bool simulated() const { return false; }
};

/// CLOCK_REALTIME, in nanoseconds since the Unix epoch.
class WallClock final : public Clock {
 public:
  Time Now() const override;
};

/// A clock that is set by its owner: the simulated clock's storage and a test fixture's clock.
/// Thread-safe.
class ManualClock : public Clock {
 public:
  explicit ManualClock(Time start = Time{0}, bool valid = true) : now_(start.ns), valid_(valid) {}
  Time Now() const override { return Time{now_.load()}; }
  bool valid() const override { return valid_.load(); }
  bool simulated() const override { return true; }
  void Set(Time t) {
    now_.store(t.ns);
    valid_.store(true);
  }
  void Advance(Duration d) { now_.fetch_add(d.count()); }

 private:
  std::atomic<std::int64_t> now_;
  std::atomic<bool> valid_;
};

/// Wall time read directly; only for liveness (heartbeats, supervisor timeouts) and for
/// measuring performance, never for logic.
Time WallNow();
/// CLOCK_MONOTONIC; for measuring elapsed wall time.
Time MonotonicNow();

}  // namespace rover
