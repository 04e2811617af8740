#pragma once
/// @file
/// Runs one scenario end to end for one seed (`roverctl run` runs many, in parallel). The run is
/// made of four pieces with their own headers under rover/deploy/runner/:
///
///  - launching (service_set.hpp): the run folder `<out>/<scenario>-seed<N>/` (result.json,
///    map.png, estimate_error.png, logs/<service>.log, params/), the world, the service set with
///    the simulator's sections of the scenario on a leased DDS domain (run clock = sim/clock),
///    everything validated first, and the operator's participant;
///  - recording (recorder.hpp, run_loop.hpp): sim/truth, dl/pose and dl/pose_odometry into the
///    judge and the tracks, and the one wait primitive, which stops at the time budget
///    (simulated), at the wall budget (a hung run), when a service crashes, or when `abort` is
///    set;
///  - the task (task.hpp, tasks/): what the scenario asks, executed over topics as an operator
///    would (directed: one dl/drive_command per step, waiting for its terminal dl/drive_status),
///    chosen by `task.type` from the task registry;
///  - judging (judging.hpp): the judge's verdict and the outputs.
///
/// Nothing is left running when a run ends.

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/deploy/run_report.hpp"
#include "rover/deploy/scenario.hpp"

namespace rover::deploy {

/// kill -9 of a service at a run-clock time (a fault campaign's `kill:`).
struct ServiceKill {
  std::string service;
  double at_s = 0;  ///< [s] run clock
};

struct RunOptions {
  std::string out_dir;         ///< campaign folder
  std::string bin_dir;         ///< where the services are
  std::string dds_config_uri;  ///< CYCLONEDDS_URI for the services
  const std::atomic<bool>* abort = nullptr;
  /// Called with short progress notes ("starting", "step 2/5 arc", ...) and the simulated time.
  std::function<void(const std::string& note, double sim_time_s)> progress;
  /// Services to kill -9 during the run (RunResult::kills says what happened).
  std::vector<ServiceKill> kills;
  /// Run the set with DDS Security (as if its compose file said x-rover.security: enabled),
  /// keys from `security_dir` (empty: the default under the state root). The runner itself
  /// then takes part as the "scenario-runner" role.
  bool security = false;
  std::string security_dir;
};

/// Validates the simulator's sections of a scenario (terrain, lander, science targets) with the
/// simulator's own parameter declarations, reporting the scenario file's lines.
Status ValidateSimulatorSections(const std::string& text, const std::string& file);

/// Loads a scenario file and validates all of it: its own keys, the task section (with the task
/// registered for its type) and the simulator's sections.
Result<Scenario> LoadScenario(const std::string& path);

/// Everything RunScenario does before starting a process, for one seed: makes the task, builds
/// the world, checks the service set and runs every service's parameter validation. An error
/// here means no run of the campaign could start; nothing is left behind.
Status PreflightScenario(const Scenario& scenario, std::uint32_t seed, const RunOptions& options);

/// Runs one seed. A failed run is a RunResult with pass == false; an error Status means the run
/// could not be made at all (bad scenario, unwritable folder).
Result<RunResult> RunScenario(const Scenario& scenario, std::uint32_t seed, const RunOptions& options);

}  // namespace rover::deploy
