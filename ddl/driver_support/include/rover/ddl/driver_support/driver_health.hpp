#pragma once
/// @file
/// Input freshness and health bookkeeping of a driver service.
///
/// InputMonitor judges one input stream on the run clock by ARRIVAL time (the run-clock time at
/// which a sample was accepted), not by the sample's own stamp, so that a wrong stamp cannot
/// make a dead stream look alive. It also rejects samples stamped implausibly far in the future
/// (more than `max_future_s` after the run clock): libraries that ignore samples older than the
/// newest seen would otherwise be frozen by one corrupt stamp. Negative stamps are rejected too.
/// The future check is skipped while the run clock is not valid (sim/clock not heard yet).
///
/// ClockJumpDetector notices the run clock moving backwards (a simulator reset): services then
/// reset their libraries' per-stream state.
///
/// HealthSummary keeps the worst SensorHealth seen (FAILED > STALE > DEGRADED > OK) and the
/// reason of the first contribution of that severity.

#include <cstdint>
#include <optional>
#include <string>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/msg/health.hpp"

namespace rover::ddl::driver_support {

class InputMonitor {
 public:
  /// `name` is the topic (used in messages). Preconditions: stale_after_s > 0, max_future_s > 0.
  InputMonitor(std::string name, double stale_after_s, double max_future_s);

  /// Checks a sample's stamp and records its arrival at `now`. OutOfRange (naming the topic,
  /// the stamp and the clock) for a negative stamp or one more than max_future_s after `now`
  /// (only when `clock_valid`); the arrival is then not recorded.
  Status Accept(std::int64_t stamp_ns, Time now, bool clock_valid = true);

  /// No sample accepted yet, or the last one arrived more than stale_after_s before `now`.
  bool Stale(Time now) const;
  /// Why Stale(now) holds ("hw/imu: no sample yet", "hw/imu: no sample for more than 0.1 s"),
  /// "" when fresh. The text does not change while the condition lasts (no live numbers), so it
  /// can go into a heartbeat without causing one per call.
  std::string StaleReason(Time now) const;

  /// Forgets the last arrival (e.g. after the run clock went back).
  void Reset() { last_arrival_.reset(); }

  const std::string& name() const { return name_; }
  double stale_after_s() const { return stale_after_s_; }
  std::uint64_t accepted() const { return accepted_; }
  std::uint64_t rejected() const { return rejected_; }

 private:
  std::string name_;
  double stale_after_s_;
  double max_future_s_;
  std::optional<Time> last_arrival_;
  std::uint64_t accepted_ = 0;
  std::uint64_t rejected_ = 0;
};

/// Detects the run clock going backwards.
class ClockJumpDetector {
 public:
  /// True if `now` is earlier than the latest valid time seen. Invalid clocks are ignored.
  bool WentBack(Time now, bool clock_valid = true);

 private:
  std::optional<Time> last_;
};

/// True for the 1st, 10th, 100th, ... occurrence: for logging a repeated problem (a bad sample
/// at 100 Hz) without flooding the log and sys/event.
inline bool IsLogWorthy(std::uint64_t count) {
  while (count >= 10 && count % 10 == 0) count /= 10;
  return count == 1;
}

/// The worst health seen and the first reason of that severity.
struct HealthSummary {
  msg::SensorHealth health = msg::SensorHealth::kOk;
  std::string reason;  ///< empty while kOk

  /// Keeps `h` and `why` if `h` is worse than the current health.
  void Worsen(msg::SensorHealth h, const std::string& why);
};

}  // namespace rover::ddl::driver_support
