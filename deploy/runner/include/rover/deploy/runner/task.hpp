#pragma once
/// @file
/// The task interface: what the rover is asked to do in a scenario run, executed over topics as
/// an operator would. The runner launches the set, records and judges; a task only commands and
/// watches. A new task type is one class and one registration; nothing else in the runner
/// changes (docs/howto/write-a-scenario.md, "Adding a task type", has a worked example).
///
/// Life of a task in a run:
///  1. Preflight: the registry parses the scenario's `task:` section with the factory registered
///     for its `type` (each task owns its keys); an error names the file, line and key, and
///     nothing starts.
///  2. Open(): the task creates its writers and readers on the run's participant.
///  3. Simulated time starts once the simulator and Ready() say the services the task commands
///     hear it; the runner then waits for the first pose estimate (and half a simulated second).
///  4. Run(): the task commands and waits with ctx.WaitUntil, which also ends the wait on a
///     crashed service, Ctrl-C or a budget; it returns its outcome.
///  5. The runner lets the last samples arrive, judges the run against the scenario's criteria
///     and writes the outputs; PlannedPath() is drawn on the map.

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <string_view>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/base/yaml_check.hpp"
#include "rover/deploy/run_report.hpp"
#include "rover/deploy/runner/recorder.hpp"
#include "rover/deploy/runner/run_loop.hpp"
#include "rover/deploy/scenario.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/sim/world/world.hpp"

namespace rover::deploy::runner {

/// What a task is given while it runs. The references outlive the task's Run().
struct TaskContext {
  const Scenario& scenario;
  /// The runner's participant on the run's DDS domain: make writers and readers with
  /// MakeWriter / MakeReader (or dds::Writer<T>::Create on it).
  const dds::Participant& participant;
  RunLoop& loop;
  Recorder& recorder;
  /// Progress notes for the campaign's live line ("step 2/5 arc"); may be empty.
  std::function<void(const std::string& note)> progress;
  /// The simulated world (truth: only the runner's tasks and the judge read it, never the
  /// stack); null where a task runs without one (unit tests).
  const sim::world::World* world = nullptr;
  /// The run's seed (seeded randomness of a task, e.g. an operator's measurement error).
  std::uint32_t seed = 0;

  /// Simulated time [s] (sim/clock).
  double Now() const { return loop.now(); }
  /// Waits until `done()` holds: "" then, else the run's failure line (crash, budget, Ctrl-C).
  std::string WaitUntil(const std::function<bool()>& done) { return loop.WaitUntil(done); }
  void Note(const std::string& note) const {
    if (progress) progress(note);
  }
  template <class T>
  Result<dds::Writer<T>> MakeWriter(const std::string& topic) const {
    return dds::Writer<T>::Create(participant, topic);
  }
  template <class T>
  Result<dds::Reader<T>> MakeReader(const std::string& topic) const {
    return dds::Reader<T>::Create(participant, topic);
  }
};

/// How a task ended.
struct TaskOutcome {
  /// One entry per command sent (result.json "steps"), in order; a step cut short by the run's
  /// end has state "interrupted".
  std::vector<StepResult> steps;
  /// "" when everything went as the scenario expects; else one line saying what happened and
  /// what was expected ("step 2 (arc) ended failed (tilt), expected timeout: ..."), or the run's
  /// failure line when a wait was cut short ("time budget of 60 simulated s exceeded").
  std::string failure;
};

class Task {
 public:
  virtual ~Task() = default;
  /// Creates the task's writers and readers (before simulated time starts).
  virtual Status Open(TaskContext& ctx) = 0;
  /// True once the services the task commands hear its writers; simulated time starts, and the
  /// task runs, only then.
  virtual bool Ready() const = 0;
  /// Executes the task: sends its commands and waits for their outcomes with ctx.WaitUntil.
  virtual TaskOutcome Run(TaskContext& ctx) = 0;
  /// The path the task means to drive (site frame [m], from the start pose), for the map; may be
  /// empty.
  virtual std::vector<Eigen::Vector2d> PlannedPath() const = 0;
};

/// What a task factory gets: the scenario and its `task:` section (a map holding `type`).
struct TaskSource {
  const Scenario& scenario;
  const YAML::Node& section;
  const yaml::FileErrors& errors;  ///< for "<file>:<line>: task.<key>: ..." messages
};

/// Parses and validates the section, and makes the task; an error names file, line and key.
using TaskFactory = std::function<Result<std::unique_ptr<Task>>(const TaskSource& source)>;

/// Maps `task.type` to a factory.
class TaskRegistry {
 public:
  /// The task types this stack has (the directed task and the planned ones).
  static const TaskRegistry& Builtin();

  /// Adds a type. Preconditions: `type` is not registered yet, `factory` is set.
  void Register(const std::string& type, std::string summary, TaskFactory factory);
  /// The registered types, in registration order.
  std::vector<std::string> Types() const;
  /// One line per type: "directed  one dl/drive_command per step ...".
  std::string Describe() const;
  /// Makes the scenario's task. An unknown type is
  /// "<file>:<line>: task.type: 'fly' is not one of: directed, ... (did you mean ...)".
  Result<std::unique_ptr<Task>> Make(const Scenario& scenario) const;

 private:
  struct Entry {
    std::string type, summary;
    TaskFactory factory;
  };
  std::vector<Entry> entries_;
};

/// Builtin().Make(scenario) without keeping the task: the TaskValidator for ParseScenario.
Status ValidateTask(const Scenario& scenario);

/// A task's destination, `goal: {x, y, tolerance}` [m] in the site frame.
struct TaskGoal {
  Eigen::Vector2d xy = Eigen::Vector2d::Zero();
  double tolerance = 1.0;
};
/// Reads the optional `goal` of a task section (x and y required, |x|, |y| <= 1e4, tolerance in
/// [0.01, 100]); nullopt when there is none.
Result<std::optional<TaskGoal>> ParseTaskGoal(const TaskSource& source);

/// An outcome or `expect:` name in core/msg's spelling: the hyphens MER's papers write
/// (WAYPT-TIMEOUT, NOT-FOUND) become '_'; "reached" and "vetoed" stay.
std::string CanonicalOutcome(std::string name);
/// A task's `expect:` (at `node`, a scalar): one of `choices`, a hyphenated fault name read as
/// core/msg's; errors name file, line, key and the choices.
Result<std::string> ParseTaskExpect(const YAML::Node& node, const std::vector<std::string>& choices,
                                    const yaml::FileErrors& err);

/// A core/msg enumerator name as scenarios and result.json write it: lower case, "GOAL_ERROR" ->
/// "goal error" with `space` (fault classes), "MOTOR_STALL" -> "motor_stall" without.
std::string ScenarioSpelling(std::string_view msg_name, bool space = false);

}  // namespace rover::deploy::runner
