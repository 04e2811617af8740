#pragma once
/// @file
/// Scenario files: one end-to-end test of the whole rover (docs/scenarios.md has the schema).
///
///   name: drive-flat                     # required
///   description: ...
///   compose: ../drive.compose.yaml       # required; the service set, relative to this file
///   simulator: rover-sim                 # the simulator's service name in that file
///   estimator: dl-pose                   # the pose estimator, told the start pose
///   seed: 1                              # default seed; `roverctl run --seeds` overrides
///   sim: {real_time_factor: 0, time_budget_s: 120, wall_budget_s: 300}
///   rover: {start: {x: 0, y: 0, yaw_deg: 0}}
///   terrain: {...}  lander: {...}  science_targets: [...]   # for the simulator (see sim/)
///   task:                              # what the rover is to do; `type` picks the task and
///     type: directed                     # the task parses the rest of the section itself
///     steps: [...]                       # (deploy/runner: task registry; docs/scenarios.md)
///   faults: [{kind: drop, topic: dl/pose, probability: 0.5, start_s: 20, duration_s: 10}]
///                                        # injected during the run (docs/faults.md; start_s
///                                        # in simulated seconds); listed in result.json
///   criteria:
///     target: {x: 5, y: 0, tolerance: 0.5}
///     heading: {deg: 90, tolerance_deg: 5}
///     max_tilt_deg: 30
///     traversable_height: 0.2
///     max_estimate_error: 0.5            # [m]
///     max_estimate_error_percent: 2      # of distance driven
///     min_distance: 4                    # [m]
///   params: {dl-pose: {key: value}}      # per-service parameter overrides
///   record: {topics: [...], exclude: [...], size_cap_mb: 500, compression: zstd}
///                                        # the run's run.mcap: on by default; `record:
///                                        # false` turns it off (rover/recording/record_options.hpp)
///
/// Errors are one line naming file, line and key. Sections meant for the simulator (terrain,
/// lander, science_targets) and the task section are validated by callbacks (the simulator's
/// parameter declarations, the runner's task registry), so they too report their lines.

#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/deploy/set_faults.hpp"
#include "rover/recording/record_options.hpp"
#include "rover/sim/judge/judge.hpp"

namespace rover::deploy {

/// Where the scenario's `task:` section is. Its keys belong to the task named by `type`: the
/// runner's task registry parses and validates them (deploy/runner/.../task.hpp).
struct TaskSection {
  std::string type;   ///< task.type as written
  int line = 0;       ///< line of the section
  int type_line = 0;  ///< line of task.type
};

/// What a scenario run records when the scenario says nothing: every topic but the camera
/// head's raw frames (hw/camera_frame; `record: {exclude: []}` keeps them), zstd, no cap, into
/// run.mcap.
recording::RecordOptions DefaultRunRecording();

struct Scenario {
  std::string file;               ///< path as given
  std::string name;
  std::string description;
  std::string compose_path;       ///< resolved relative to the scenario file
  std::string simulator = "rover-sim";
  /// The pose estimator's service name: the runner tells it the start pose (start.x, start.y,
  /// start.yaw_deg), as operators tell a rover where it is.
  std::string estimator = "dl-pose";
  std::uint32_t seed = 1;
  double real_time_factor = 0;    ///< 0 = as fast as possible
  /// [s] the simulator runs at most this far ahead of the slowest service (sim/clock_ack), so a
  /// loaded machine slows the run instead of making the stack late; 0 = free running.
  double lockstep_lead_s = 0.1;
  /// How the simulator keeps in step with the services: "strict" (the default: tick by tick,
  /// every service and the runner served; the same seed gives the same figures bit for bit,
  /// core/runtime lockstep.hpp), "lead" (at most lockstep_lead_s ahead; faster on a loaded
  /// machine, not reproducible) or "off" (free running).
  std::string lockstep = "strict";
  /// [s] strict lock-step's quantum: simulated time between two ticks (a whole number of the
  /// simulator's 10 ms periods). Each link between two services takes one quantum and a timer
  /// faster than the quantum fires once per tick (ddl-joints' 50 Hz at 25 Hz): 40 ms, a fifth
  /// of MER's 8 Hz mobility cycle, so that campaigns run at 10 simulated s per wall s on two
  /// cores (docs/scenarios.md "Reproducible runs").
  double lockstep_quantum_s = 0.04;
  double time_budget_s = 300;     ///< [s] simulated
  double wall_budget_s = 600;     ///< [s] wall-clock safety net
  double start_x = 0, start_y = 0, start_yaw = 0;  ///< [m], [rad]
  TaskSection task;
  /// `faults:`, validated when the file is read; the runner adds them to the set's
  /// x-rover.faults (renumbered after those) and lists what they did in the run's result.
  std::vector<SetFault> faults;
  sim::judge::JudgeCriteria criteria;
  /// service -> flattened key -> YAML scalar text
  std::map<std::string, std::map<std::string, std::string>> params;
  /// The run's recording: every catalog topic but hw/camera_frame into <run folder>/run.mcap
  /// unless the
  /// scenario's `record` says otherwise (a relative path is inside the run folder).
  recording::RecordOptions record = DefaultRunRecording();
  std::string text;               ///< the file's text (to hand sections to the simulator)
};

/// Validates the simulator's sections (terrain, lander, science_targets) of a scenario text;
/// returns the first error with the file's line.
using SimSectionValidator = std::function<Status(const std::string& text, const std::string& file)>;
/// Validates the task section of a parsed scenario (its type and its own keys); returns the first
/// error with the file's line.
using TaskValidator = std::function<Status(const Scenario& scenario)>;

/// The top-level keys that belong to the simulator.
const std::vector<std::string>& SimulatorSections();

/// Parses and validates a scenario. Without `validate_task` only the task section's `type` is
/// checked to be there; without `validate_sim` the simulator's sections are taken as they are.
Result<Scenario> ParseScenario(const std::string& text, const std::string& file,
                               const SimSectionValidator& validate_sim = nullptr,
                               const TaskValidator& validate_task = nullptr);
Result<Scenario> LoadScenarioFile(const std::string& path,
                                  const SimSectionValidator& validate_sim = nullptr,
                                  const TaskValidator& validate_task = nullptr);

/// Parses a seed range "A..B", a single "A", or a comma-separated list of both ("3,5..7");
/// A <= B, each seed once, at most 10000 seeds.
Result<std::vector<std::uint32_t>> ParseSeedRange(const std::string& text);

}  // namespace rover::deploy
