#pragma once
/// @file
/// Pacing of the simulator against the wall clock, without DDS or clock reads: the rover-sim
/// service asks UntilNextStep(wall_now, sim_time) before each engine step and sleeps for what it
/// returns.
///
/// Real time: with real-time factor r > 0 the step that starts at simulated time s is due at
/// wall time  w0 + (s - s0) / r,  where (w0, s0) is the anchor taken at start, on resume and on
/// every speed change (so a change never makes the simulator race to catch up). r = 0 runs as
/// fast as the machine allows.
///
/// Lock-step (lockstep_lead_s = L > 0): every service that acknowledges sim/clock
/// (sim/clock_ack) is waited on until it has acknowledged a time >= s - L, so a slow service
/// (rendering, stereo) stops the simulated world instead of falling behind it. A service whose
/// acknowledgement has not moved for lockstep_stall_s of wall time is no longer waited on (it
/// died or hung; the supervisor restarts it) until it acknowledges a new time.
///
/// Strict lock-step (lockstep_strict, core/runtime lockstep.hpp): the simulator publishes
/// sim/clock only at the end of each quantum (a barrier, SetBarrier) and starts the next quantum
/// only when every service named in lockstep_services has acknowledged the barrier; it waits for
/// them from the first step on (the set is known, not learned from acknowledgements, so a slow
/// starter cannot miss the start). A named service that has not acknowledged a barrier within
/// lockstep_stall_s of wall time stalls the run: stalled() names it, and the simulator stops
/// stepping (a clear failure instead of a hang or a run that is no longer reproducible).
///
/// Pipelined (lockstep_pipelined, off by default): the quantum (B, B + Q] is stepped at once, while
/// the services serve tick B, and sim/clock of its end, B + Q, goes out only when every named
/// service has served B (so everything they wrote at B has arrived before anyone serves B + Q).
/// What the services write at tick B is applied from B + Q on (the simulator reads only inputs
/// written before the quantum it starts): one quantum more actuation latency. Known limit: on
/// drive runs dl-pose's estimate then differs between runs in the 12th digit (the physics and
/// every sample count do not); until that is found it is not the default. Without pipelining a
/// quantum starts only once B has been served, and runs are identical bit for bit.
///
/// Times: wall times are rover::Time on the monotonic clock, simulated times are seconds.

#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/base/time.hpp"

namespace rover::sim::rover_sim {

struct PacerOptions {
  double real_time_factor = 1.0;  ///< simulated seconds per wall second; 0 = unpaced
  bool start_paused = false;      ///< wait for SIM_RESUME before the first step
  double lockstep_lead_s = 0.0;   ///< [s] simulated lead over the slowest service; 0 = free running
  /// [s] wall time a service may go without a new acknowledgement before it is not waited on.
  /// Generous by default: at a load of 10+ on two cores ddl-camera and dl-pose went silent for
  /// over 2 s, and a simulator that ran on left dl-locomotion with a stale attitude (SAPP).
  double lockstep_stall_s = 30.0;
  /// Strict lock-step (see the file comment); lockstep_lead_s is then not used.
  bool lockstep_strict = false;
  /// [s] simulated time between two barriers under strict lock-step (a whole number of
  /// simulator periods; the service checks that).
  double lockstep_quantum_s = 0.04;
  /// The services strict lock-step waits for, comma-separated (their --name).
  std::string lockstep_services;
  /// Strict: step a quantum while the services serve the tick that began it (see above).
  bool lockstep_pipelined = false;

  /// real_time_factor in [0, 1000]; lockstep_lead_s 0 or in [kMinLockstepLeadS, 10];
  /// lockstep_stall_s in [0.1, 3600]; lockstep_quantum_s in [0.001, 1]; strict needs at least
  /// one service, names without spaces. Messages start with the field.
  Status Validate() const;
  static void BindParams(ParamBinder<PacerOptions>& b);
};

/// Smallest lock-step lead: the services acknowledge every 25 ms of simulated time.
inline constexpr double kMinLockstepLeadS = 0.05;

class Pacer {
 public:
  /// How long to wait while paused before asking again (the service republishes sim/clock).
  static constexpr Duration kPausedPoll = std::chrono::milliseconds(50);
  /// How long to wait before asking again while lock-step waits on a service.
  static constexpr Duration kLockstepPoll = std::chrono::microseconds(200);
  /// The same under strict lock-step: the simulator's executor wakes at once when an
  /// acknowledgement arrives, so this only bounds the wait (no polling).
  static constexpr Duration kStrictWait = std::chrono::milliseconds(20);

  /// Preconditions: options.Validate() is Ok.
  explicit Pacer(const PacerOptions& options);

  /// Takes the real-time anchor (wall_now, sim_s).
  void Anchor(Time wall_now, double sim_s);
  void Pause() { paused_ = true; }
  /// Unpauses and re-anchors.
  void Resume(Time wall_now, double sim_s);
  /// InvalidArgument (the field and value) when rtf is outside [0, 1000]; then nothing changes.
  Status SetRealTimeFactor(double rtf, Time wall_now, double sim_s);

  /// sim/clock_ack from `service` at wall time `wall_now`: it has processed sim time `acked_ns`.
  /// Acknowledgements from `self` (the simulator's own name) are ignored. Returns the name of a
  /// service that was not waited on and now is again, or an empty string.
  std::string OnAck(const std::string& service, std::int64_t acked_ns, Time wall_now);

  /// Zero when the step at simulated time sim_s may run now; otherwise how long to wait before
  /// asking again. Services that stall past lockstep_stall_s are dropped here; their names are
  /// added to `dropped` when given.
  Duration UntilNextStep(Time wall_now, double sim_s, std::vector<std::string>* dropped = nullptr);

  /// Simulated seconds per wall second since the anchor (0 before any wall time has passed).
  double MeasuredRealTimeFactor(Time wall_now, double sim_s) const;

  bool paused() const { return paused_; }
  double real_time_factor() const { return rtf_; }
  bool lockstep() const { return options_.lockstep_lead_s > 0.0; }
  /// Names of the services lock-step currently waits on.
  std::vector<std::string> services_waited_on() const;
  void set_self(std::string name) { self_ = std::move(name); }

  bool strict() const { return options_.lockstep_strict; }
  /// Strict: the simulator published sim/clock at `sim_ns` (wall `wall_now`): the barrier.
  /// Without pipelining the next step waits until every named service has acknowledged it.
  void SetBarrier(std::int64_t sim_ns, Time wall_now);
  std::int64_t barrier_ns() const { return barrier_ns_; }
  /// Strict: zero once every named service has acknowledged the barrier, else how long to wait
  /// (kStrictWait; kPausedPoll once one has stalled, see stalled()). Pipelined, the simulator
  /// asks this before publishing the clock at the end of a quantum.
  Duration UntilBarrierServed(Time wall_now);
  /// Strict: the named services that have not acknowledged the barrier yet.
  std::vector<std::string> Missing() const;
  /// Strict: the service that stalled the run (empty while none has).
  const std::string& stalled() const { return stalled_; }
  /// The names in lockstep_services.
  static std::vector<std::string> ParseServices(const std::string& list);

  /// Strict: the samples `service` has written per catalog topic, from its latest
  /// acknowledgement (sim/clock_ack.written).
  void OnWritten(const std::string& service, std::vector<std::uint64_t> counts);
  /// Strict: every participant's latest counts (sim/clock_ack.written) and `own`, summed per
  /// catalog topic: what has been written so far, as far as the simulator knows.
  std::vector<std::uint64_t> CurrentCounts(const std::vector<std::uint64_t>& own) const;
  /// Strict: what `service` said of itself in its acknowledgement of tick `acked_ns`
  /// (sim/clock_ack next_due_ns, reads): with the frontier of that tick, whether it must serve
  /// a later tick (lockstep::MustServe). An acknowledgement of a tick whose frontier is no longer
  /// known leaves the service due every tick until its next one.
  void OnIdleState(const std::string& service, std::int64_t acked_ns, std::int64_t next_due_ns,
                   std::uint64_t reads);
  /// Strict: services of lockstep_services that the tick whose frontier was last computed does
  /// not wait for (nothing is due for them: lockstep::MustServe).
  const std::vector<std::string>& idle() const { return idle_; }
  /// Strict: whether `service` is sent the tick whose frontier was last computed on its own
  /// sim/clock partition: unless it is idle at that tick; a repeat (the simulator waits) goes to
  /// every service.
  bool SendsTickTo(const std::string& service, bool repeat) const;
  /// Strict: the frontier sim/clock carries for the tick at `tick_ns`: the sum of every
  /// participant's latest counts and `own` (the simulator's), computed when the tick is first
  /// asked for and repeated unchanged after (acknowledgements that came since may count samples
  /// written while serving this very tick). Returns true in `*fresh` when it was just computed.
  const std::vector<std::uint64_t>& FrontierFor(std::int64_t tick_ns,
                                                const std::vector<std::uint64_t>& own,
                                                bool* fresh = nullptr);

 private:
  struct AckState {
    std::int64_t sim_time_ns = 0;
    Time changed;           ///< wall time the acknowledgement last moved
    bool waited_on = true;  ///< false while the service is considered gone
    bool seen = false;
    // Strict idle ticks: the frontier of the tick it last served, its next deadline, its topics.
    bool idle_known = false;
    std::vector<std::uint64_t> served;
    std::int64_t next_due_ns = 0;
    std::uint64_t reads = 0;
  };

  PacerOptions options_;
  double rtf_;
  bool paused_;
  Time wall_anchor_{0};
  double sim_anchor_ = 0.0;
  std::string self_;
  std::map<std::string, AckState> acks_;
  std::vector<std::string> expected_;  // strict: lockstep_services
  std::int64_t barrier_ns_ = 0;
  Time barrier_wall_{0};
  std::string stalled_;
  std::map<std::string, std::vector<std::uint64_t>> written_;
  std::vector<std::uint64_t> frontier_;  // of the tick last asked for
  std::int64_t frontier_ns_ = -1;
  // The last few ticks' frontiers (an acknowledgement may come after the next tick went out).
  std::deque<std::pair<std::int64_t, std::vector<std::uint64_t>>> recent_frontiers_;
  std::vector<std::string> idle_;  // of frontier_ns_
};

}  // namespace rover::sim::rover_sim
