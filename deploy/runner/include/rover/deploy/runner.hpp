#pragma once
/// @file
/// Runs one scenario end to end for one seed (`roverctl run` runs many, in parallel):
///
///  1. makes the run folder `<out>/<scenario>-seed<N>/` (result.json, map.png,
///     estimate_error.png, logs/<service>.log, params/);
///  2. starts the scenario's service set with the simulator's sections of the scenario
///     (terrain, lander, science targets, start pose, speed, seed) on a leased DDS domain, run
///     clock = sim/clock, everything validated first;
///  3. executes the task over topics as an operator would (directed: one dl/drive_command per
///     step, waiting for its terminal dl/drive_status), while recording sim/truth and dl/pose;
///  4. stops at the end of the task, at the time budget (simulated), at the wall budget (a hung
///     run), when a service crashes, or when `abort` is set; nothing is left running;
///  5. scores the run with the judge and writes the outputs.

#include <atomic>
#include <functional>
#include <string>

#include "rover/base/status.hpp"
#include "rover/deploy/run_report.hpp"
#include "rover/deploy/scenario.hpp"

namespace rover::deploy {

struct RunOptions {
  std::string out_dir;         ///< campaign folder
  std::string bin_dir;         ///< where the services are
  std::string dds_config_uri;  ///< CYCLONEDDS_URI for the services
  const std::atomic<bool>* abort = nullptr;
  /// Called with short progress notes ("starting", "step 2/5 arc", ...) and the simulated time.
  std::function<void(const std::string& note, double sim_time_s)> progress;
};

/// Validates the simulator's sections of a scenario (terrain, lander, science targets) with the
/// simulator's own parameter declarations, reporting the scenario file's lines.
Status ValidateSimulatorSections(const std::string& text, const std::string& file);

/// Everything RunScenario does before starting a process, for one seed: builds the world, checks
/// the service set and runs every service's parameter validation. An error here means no run of
/// the campaign could start; nothing is left behind but the run folder's params/.
Status PreflightScenario(const Scenario& scenario, std::uint32_t seed, const RunOptions& options);

/// Runs one seed. A failed run is a RunResult with pass == false; an error Status means the run
/// could not be made at all (bad scenario, unwritable folder).
Result<RunResult> RunScenario(const Scenario& scenario, std::uint32_t seed, const RunOptions& options);

}  // namespace rover::deploy
