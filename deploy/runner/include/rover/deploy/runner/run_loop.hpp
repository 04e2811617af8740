#pragma once
/// @file
/// The run's clock and its one way of waiting. Everything the runner and a task wait for (the
/// services hearing us, a drive step's terminal status, the last samples) is a condition passed
/// to WaitUntil, which on every pass also pumps the recorder and runs the run's checks: a crashed
/// service, Ctrl-C, the simulated time budget and the wall budget. So no wait can outlive a
/// crashed set or a hung simulator.
///
/// Strict lock-step (LoopLimits::strict_lockstep; core/runtime lockstep.hpp): the runner is one
/// of the participants the simulator waits for. Each pass serves the latest tick T: this thread
/// reads only samples written before T and its writes carry T; once `done()` does not hold and
/// the checks pass, the runner acknowledges T (as kRunnerName) and waits for the next tick.
/// `done()` is asked once per tick (after tick 0), on the tick's first pass, never after the
/// acknowledgement. So the task's commands enter the run at the same simulated time however the
/// machine is loaded.
///
/// Time: `now()` is the latest sim/clock time heard [s since the start of the run]; budgets are
/// in simulated seconds except the wall budget, the safety net for a hung run (wall seconds since
/// LoopLimits::wall_start, monotonic).

#include <atomic>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rover/base/clock.hpp"
#include "rover/base/status.hpp"
#include "rover/runtime/dds.hpp"

namespace rover::deploy::runner {

struct LoopLimits {
  double time_budget_s = 300;  ///< [s] simulated; exceeding it fails the run
  double wall_budget_s = 600;  ///< [s] wall, counted from wall_start; exceeding it fails the run
  Time wall_start;             ///< MonotonicNow() when the run began
  const std::atomic<bool>* abort = nullptr;  ///< set (Ctrl-C) to stop: "interrupted"
  bool strict_lockstep = false;              ///< serve the simulator's ticks (see the file comment)
};

/// The name the runner acknowledges sim/clock under (the simulator's sim.lockstep_services
/// lists it).
inline constexpr const char* kRunnerName = "scenario-runner";

class RunLoop {
 public:
  /// Reads sim/clock on `participant` (which must outlive the loop).
  static Result<std::unique_ptr<RunLoop>> Create(const dds::Participant& participant,
                                                 LoopLimits limits);

  /// Latest simulated time heard on sim/clock [s]; 0 before the first tick.
  double now() const { return now_s_; }

  /// Adds work done on every pass, after reading the clock (the recorder's takes).
  void AddPump(std::function<void()> pump);
  /// Adds a check run on every pass that the condition does not hold: it returns "" while all is
  /// well, else the run's one-line failure. Checks run in the order added, then the built-in ones
  /// (interrupted, time budget, wall budget).
  void AddCheck(std::function<std::string()> check);

  /// Reads the clock and runs the pumps once.
  void Pump();
  /// The first failing check's line, or "".
  std::string Check() const;
  /// Pumps until `done()` holds (returns "") or a check fails (returns its line); between
  /// passes it waits up to 5 ms (wall) for a new tick.
  std::string WaitUntil(const std::function<bool()>& done);

  ~RunLoop();

 private:
  RunLoop(dds::Reader<rover_sim_Clock> clock, LoopLimits limits)
      : clock_(std::move(clock)), limits_(limits) {}
  // Strict lock-step: acknowledges the tick served when a clock sample came since the last one.
  void Acknowledge();

  dds::Reader<rover_sim_Clock> clock_;
  dds_entity_t participant_ = 0;
  dds::Writer<rover_sim_ClockAck> ack_;
  std::unique_ptr<dds::WaitSet> waitset_;
  std::int64_t tick_ns_ = 0;
  std::int64_t decided_tick_ns_ = -1;  // strict: the tick whose condition was last asked
  bool heard_ = false;
  std::uint64_t clock_samples_ = 0, acked_samples_ = 0;
  LoopLimits limits_;
  double now_s_ = 0;
  std::vector<std::function<void()>> pumps_;
  std::vector<std::function<std::string()>> checks_;
};

}  // namespace rover::deploy::runner
