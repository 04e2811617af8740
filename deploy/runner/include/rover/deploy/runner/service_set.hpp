#pragma once
/// @file
/// Launching a run's service set: the run folder and the world (PrepareRun, which also runs every
/// service's parameter validation), the supervised processes on a leased DDS domain, the
/// operator's participant on that domain, and the simulator's start switch (simulated time starts
/// paused and runs once the runner says so).

#include <map>
#include <memory>
#include <string>
#include <vector>

#include "rover/base/clock.hpp"
#include "rover/base/status.hpp"
#include "rover/deploy/compose.hpp"
#include "rover/deploy/runner.hpp"
#include "rover/deploy/scenario.hpp"
#include "rover/deploy/supervisor.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/sim/world/world.hpp"

namespace rover::deploy::runner {

/// Everything a run needs before a process starts.
struct PreparedRun {
  std::string run_dir;     ///< <out>/<scenario>-seed<N>
  sim::world::World world;        ///< exactly as the simulator will build it
  ComposeProject project;  ///< the set, each service given its parameter files
  SupervisorOptions supervisor;
};

/// Makes the run folder (emptied first) with params/: the simulator's world sections for this
/// seed (terrain.seed = the seed unless the scenario fixes it, the start pose, sim.start_paused)
/// and each service's overrides (the estimator is told the start pose; then the scenario's
/// params.<service>); builds the world; loads the set and runs the supervisor's preflight (every
/// command exists, every rover service accepts its parameters). Errors name the scenario or
/// compose file.
Result<PreparedRun> PrepareRun(const Scenario& scenario, std::uint32_t seed,
                               const RunOptions& options);

/// The simulator's parameter file of a run: the scenario's world sections with this seed
/// (terrain.seed = the seed unless the scenario fixes it), the start pose and sim.start_paused.
std::string SimParamsYaml(const Scenario& scenario, std::uint32_t seed,
                          const std::vector<std::string>& lockstep_services = {});
/// The world of a run, exactly as the simulator builds it from SimParamsYaml (errors name
/// `source`, the file that text is or would be in).
Result<sim::world::World> BuildRunWorld(const Scenario& scenario, std::uint32_t seed,
                                        const std::string& source);

/// FNV-1a digest of a terrain's heights and rock list, 16 hex digits (same seed, same digest).
std::string TerrainDigest(const sim::terrain::Terrain& terrain);

/// The running set of one run.
class ServiceSet {
 public:
  /// Leases the run's DDS domain (nothing starts yet).
  static Result<std::unique_ptr<ServiceSet>> Create(const PreparedRun& prepared);
  ~ServiceSet();

  int domain() const { return supervisor_->domain(); }
  /// Starts every service (all or nothing, see supervisor.hpp).
  Status Start();
  /// Creates the operator's participant on the run's domain and its sim/control writer.
  Status OpenOperator();
  /// The operator's participant. Precondition: OpenOperator() succeeded.
  const dds::Participant& participant() const { return participant_; }
  /// The simulator hears sim/control.
  bool SimulatorHearsUs() const;
  /// Starts simulated time (sim/control RESUME).
  Status ResumeSimulator();
  /// One supervision step; "" while every service runs, else "service 'x' crashed (how it
  /// ended)", and "x: how it ended; its last log line" is appended to `*crashes`. The heartbeats
  /// (readiness) are read on every call; the processes are polled and the state file written
  /// at most every kProcessPollS of wall time (the runner calls this every simulated tick).
  std::string CheckServices(std::vector<std::string>* crashes);
  static constexpr double kProcessPollS = 0.05;
  /// Every service is ready by its rule (supervisor.hpp: a rover service's heartbeat says ACTIVE
  /// and health OK), as of the last CheckServices().
  bool Ready() const { return supervisor_->readiness().ready; }
  /// Why it is not ready: "dl-pose: health degraded: levelling: ...; ...".
  std::string NotReady() const { return supervisor_->readiness().Summary(); }
  /// Wall seconds from the start of Start() to the set first being ready (< 0: not yet).
  double ready_after_s() const { return supervisor_->ready_after_s(); }
  /// Stops every service; nothing is left running.
  void Stop();
  /// kill -9 of one service (a fault campaign's `kill:`). From then on its exit is expected:
  /// CheckServices does not call it a crash while its restart policy brings it back (it still
  /// does if the service is not restarted, or fails again later).
  Status Kill(const std::string& service);
  /// The service was killed by Kill() and runs again (restarted by the supervisor).
  bool RunsAgain(const std::string& service) const;

 private:
  explicit ServiceSet(std::unique_ptr<Supervisor> supervisor)
      : supervisor_(std::move(supervisor)) {}

  std::unique_ptr<Supervisor> supervisor_;
  std::map<std::string, int> killed_;  // service -> its restart count when it was killed
  Time last_process_poll_{0};
  dds::Participant participant_;
  dds::Writer<rover_sim_Control> control_;
};

}  // namespace rover::deploy::runner
