#pragma once
/// @file
/// Where a service's time goes: wall time summed per named activity (physics, render, stereo,
/// vo, planning, lockstep_wait, ...), plus the process's CPU time. Every service's heartbeat
/// carries both (sys/health), and the scenario runner reports them per run (result.json
/// "timing") and per campaign (summary.txt), so a slowdown shows the day it lands.
///
/// Times are wall time on the monotonic clock: what an activity costs the run, including time
/// the machine gave to other processes meanwhile (on a loaded machine that is part of the cost).

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rover/base/time.hpp"

namespace rover::runtime {

class ActivityLog {
 public:
  /// Activities kept per service; a heartbeat carries at most this many.
  static constexpr std::size_t kMaxActivities = 16;
  /// Longest activity name (the heartbeat's bounded string).
  static constexpr std::size_t kMaxNameLength = 31;

  struct Entry {
    std::string name;
    double wall_s = 0.0;  ///< [s] summed
    std::uint32_t count = 0;
  };

  /// Adds one occurrence of `name` lasting `wall`. Names beyond kMaxActivities are counted
  /// under "other"; names longer than kMaxNameLength are cut. Negative durations count as 0.
  void Add(std::string_view name, Duration wall);
  /// In the order first added.
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  std::vector<Entry> entries_;
};

/// Adds the wall time from construction to destruction to `log` under `name`.
class ScopedActivity {
 public:
  ScopedActivity(ActivityLog& log, std::string_view name);
  ~ScopedActivity();
  ScopedActivity(const ScopedActivity&) = delete;
  ScopedActivity& operator=(const ScopedActivity&) = delete;

 private:
  ActivityLog& log_;
  std::string_view name_;
  Time start_;
};

/// CPU time of this process so far, every thread [s] (CLOCK_PROCESS_CPUTIME_ID).
double ProcessCpuSeconds();
/// CPU time of the calling thread so far [s] (CLOCK_THREAD_CPUTIME_ID).
double ThreadCpuSeconds();

}  // namespace rover::runtime
