#pragma once
/// @file
/// A single-threaded event loop: reader callbacks and timers, driven by the run clock.
///
/// Run-clock timers fire on the service's Clock (wall or sim/clock): under a simulator they
/// follow simulated time, so a 8 Hz control loop runs 8 times per simulated second at any
/// real-time factor. Wall timers are only for liveness (the heartbeat). Callbacks run on the
/// thread that calls Spin(); an exception thrown by a callback is logged and counted, and the
/// loop goes on (a bad sample must never take a service down).
///
/// Fault seams (seam.hpp): on every pass the executor runs the process's seam pump and drains
/// the readers whose seams hold samples that are now due, and it does not sleep past the
/// pump's next due time (under a simulated clock it still wakes at least every 200 ms).
///
/// Strict lock-step (SetStrictTicks, lockstep.hpp): samples that arrive are only stashed in
/// their readers; each new run-clock time T (a tick of the simulator) is served in one go —
/// the fault seams' due work, then every subscription in the order subscribed, each handing
/// out the samples written before T, then the run-clock timers due by T — with this thread's
/// writes stamped T. The service context acknowledges T after that (SetAfterSpin), with what
/// the simulator needs to leave it out of ticks on which nothing would happen (next_due_ns,
/// reads; lockstep.hpp "idle"). Gated readers are not in the wait set under strict ticks:
/// samples wait in DDS until the tick that hands them out, so they do not wake the thread.

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/clock.hpp"
#include "rover/base/time.hpp"
#include "rover/runtime/dds.hpp"

namespace rover {

class Executor {
 public:
  using TimerId = int;
  enum class TimerBase { kRunClock, kWall };

  /// `clock` must outlive the executor.
  static Result<std::unique_ptr<Executor>> Create(const dds::Participant& participant,
                                                  const Clock& clock);

  /// Calls `callback` every `period` of the chosen clock. Timers that are not `always` run only
  /// while the executor is active. Precondition: period > 0.
  TimerId AddTimer(Duration period, std::function<void()> callback,
                   TimerBase base = TimerBase::kRunClock, bool always = false);
  void CancelTimer(TimerId id);

  /// Calls `callback` for each sample the reader receives. The reader must outlive the
  /// executor. Subscriptions that are not `always` are only served while active; samples that
  /// arrive meanwhile wait in the reader's history.
  template <class T>
  Status Subscribe(dds::Reader<T>& reader, std::function<void(const dds::Sample<T>&)> callback,
                   bool always = false) {
    auto drain = [&reader, cb = std::move(callback), this]() {
      reader.TakeEach([&](const dds::Sample<T>& s) { Invoke(reader.topic_name(), [&] { cb(s); }); });
    };
    return AddSubscription(
        reader.handle(), reader.topic_name(), std::move(drain), [&reader] { reader.Stash(); },
        always, reader.seam());
  }

  /// Drains every attached subscription now (the ones served while inactive too), whether or
  /// not new samples woke it: for a loop that moves its own read gate (the simulator's
  /// pipelined lock-step) and must hand out what the gate held back. Callbacks run inline.
  void DrainAll();

  /// Strict lock-step ticks (see the file comment). Precondition: the run clock is simulated.
  void SetStrictTicks(bool strict);
  bool strict_ticks() const { return strict_; }
  /// The last tick served (strict lock-step), or nullopt before the first.
  std::optional<Time> last_tick() const { return last_tick_; }
  /// Strict lock-step, after a tick was served: the run-clock time [ns] of the earliest timer,
  /// fault-seam release or held sample due (0: the next tick, whatever it brings), and the
  /// catalog topics the served subscriptions read. What the acknowledgement carries.
  std::int64_t next_due_ns() const { return next_due_ns_; }
  dds::lockstep::TopicMask reads() const { return reads_; }

  /// Active: every subscription and timer runs. Inactive: only `always` ones.
  Status SetActive(bool active);
  bool active() const { return active_; }

  /// Sets a function Spin() calls between polls while active, for a loop that produces time
  /// itself (the simulator). It returns how long (wall time) until it wants to run again;
  /// zero means at once, after incoming samples and due timers have been served.
  void SetWork(std::function<Duration()> work) { work_ = std::move(work); }
  /// Sets a function SpinOnce() calls last, after the samples and timers it served (the
  /// service context acknowledges the simulated time there).
  void SetAfterSpin(std::function<void()> after) { after_spin_ = std::move(after); }

  /// Waits at most `max_wait` (wall time) for work, then does all that is due.
  void SpinOnce(Duration max_wait);
  /// Spins until Stop().
  void Spin();
  /// Thread-safe; makes Spin() return.
  void Stop();
  bool stopped() const { return stop_.load(); }

  /// Exceptions thrown by callbacks so far.
  std::uint64_t callback_errors() const { return callback_errors_; }
  const Clock& clock() const { return clock_; }

  ~Executor();

 private:
  struct Timer {
    TimerId id;
    Duration period;
    std::function<void()> callback;
    TimerBase base;
    bool always;
    Time next{0};
    bool armed = false;
  };
  struct Subscription {
    dds_entity_t handle;
    std::string topic;
    std::function<void()> drain;
    std::function<void()> stash;  // strict lock-step: take into the reader's queue only
    bool always;
    dds::TopicSeam* seam;  // the reader's fault seam (held-back samples), or nullptr
    int topic_index = -1;  // lockstep::CatalogIndex(topic)
    bool attached = false;  // served (always, or while active)
    bool in_waitset = false;  // wakes the thread (attached, and not gated under strict ticks)
  };

  Executor(const Clock& clock, dds::WaitSet ws, dds::GuardCondition guard);
  Status AddSubscription(dds_entity_t handle, const std::string& topic, std::function<void()> drain,
                         std::function<void()> stash, bool always, dds::TopicSeam* seam);
  // Strict lock-step: serves the tick `now` (see the file comment).
  void ServeTick(Time now);
  // The fault seams' deferred work: writes delayed samples, drains readers whose seams hold
  // samples that are due now.
  void RunSeams();
  void Invoke(const std::string& what, const std::function<void()>& fn);
  void RunDueTimers();
  Time TimerNow(const Timer& t) const;
  // Puts subscription i in the wait set or takes it out, as its state demands.
  Status SyncWaitset(std::size_t i);
  // Strict lock-step: next_due_ns_ and reads_ from the timers and subscriptions.
  void NoteServed();

  const Clock& clock_;
  WallClock wall_;
  dds::WaitSet waitset_;
  dds::GuardCondition guard_;
  std::vector<Subscription> subscriptions_;
  std::vector<Timer> timers_;
  TimerId next_timer_id_ = 1;
  bool active_ = false;
  std::atomic<bool> stop_{false};
  std::uint64_t callback_errors_ = 0;
  Time last_run_clock_{0};
  std::function<Duration()> work_;
  std::function<void()> after_spin_;
  bool strict_ = false;
  std::optional<Time> last_tick_;
  // Strict lock-step: what the acknowledgement says of the executor (NoteServed).
  std::int64_t next_due_ns_ = 0;
  dds::lockstep::TopicMask reads_ = 0;
};

}  // namespace rover
