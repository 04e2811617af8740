#include <algorithm>
#include <cctype>
#include <cstdio>

#include "rover/base/check.hpp"
#include "rover/deploy/runner/task.hpp"
#include "rover/deploy/runner/tasks/autofocus_task.hpp"
#include "rover/deploy/runner/tasks/directed_task.hpp"
#include "rover/deploy/runner/tasks/lander_return_task.hpp"
#include "rover/deploy/runner/tasks/mobility_task.hpp"
#include "rover/deploy/runner/tasks/planned_tasks.hpp"
#include "rover/deploy/runner/tasks/science_target_task.hpp"
#include "rover/deploy/runner/tasks/sequence_task.hpp"

namespace rover::deploy::runner {

const TaskRegistry& TaskRegistry::Builtin() {
  // A new task type: its own tasks/<name>_task.{hpp,cpp} with a Register function, called here.
  static const TaskRegistry registry = [] {
    TaskRegistry r;
    RegisterDirectedTask(r);
    RegisterMobilityTasks(r);
    RegisterLanderReturnTask(r);
    RegisterPlannedTasks(r);
    RegisterScienceTargetTask(r);
    RegisterSequenceTask(r);
    RegisterAutofocusTask(r);
    return r;
  }();
  return registry;
}

void TaskRegistry::Register(const std::string& type, std::string summary, TaskFactory factory) {
  ROVER_DEMAND(factory != nullptr);
  ROVER_DEMAND(std::none_of(entries_.begin(), entries_.end(),
                            [&](const Entry& e) { return e.type == type; }));
  entries_.push_back({type, std::move(summary), std::move(factory)});
}

std::vector<std::string> TaskRegistry::Types() const {
  std::vector<std::string> out;
  for (const auto& e : entries_) out.push_back(e.type);
  return out;
}

std::string TaskRegistry::Describe() const {
  std::string out;
  for (const auto& e : entries_) {
    char b[64];
    std::snprintf(b, sizeof b, "%-16s ", e.type.c_str());
    out += b + e.summary + "\n";
  }
  return out;
}

Result<std::unique_ptr<Task>> TaskRegistry::Make(const Scenario& scenario) const {
  const yaml::FileErrors err(scenario.file);
  ROVER_ASSIGN_OR_RETURN(const YAML::Node root, yaml::Load(scenario.text, err));
  const YAML::Node section = root["task"];
  if (!section || !section.IsMap()) {
    return err.At(scenario.task.line, "task: expected a map with a 'type'");
  }
  const YAML::Node type = section["type"];
  ROVER_ASSIGN_OR_RETURN(const std::string name, yaml::OneOf(type, "task.type", Types(), err));
  const auto it = std::find_if(entries_.begin(), entries_.end(),
                               [&](const Entry& e) { return e.type == name; });
  return it->factory(TaskSource{scenario, section, err});
}

Status ValidateTask(const Scenario& scenario) {
  auto task = TaskRegistry::Builtin().Make(scenario);
  return task.ok() ? Status::Ok() : task.status();
}

Result<std::optional<TaskGoal>> ParseTaskGoal(const TaskSource& source) {
  const YAML::Node g = source.section["goal"];
  if (!g) return std::optional<TaskGoal>();
  const yaml::FileErrors& err = source.errors;
  ROVER_RETURN_IF_ERROR(yaml::CheckKeys(g, "task.goal", {"x", "y", "tolerance"}, err));
  TaskGoal goal;
  bool hx = false, hy = false;
  ROVER_RETURN_IF_ERROR(
      yaml::OptionalNumber(g, "x", "task.goal", -1e4, 1e4, err, &goal.xy.x(), &hx));
  ROVER_RETURN_IF_ERROR(
      yaml::OptionalNumber(g, "y", "task.goal", -1e4, 1e4, err, &goal.xy.y(), &hy));
  if (!hx || !hy) return err.At(g, "task.goal: needs both 'x' and 'y'");
  ROVER_RETURN_IF_ERROR(
      yaml::OptionalNumber(g, "tolerance", "task.goal", 0.01, 100, err, &goal.tolerance));
  return std::optional<TaskGoal>(goal);
}

std::string CanonicalOutcome(std::string name) {
  if (name != "reached" && name != "vetoed") std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

Result<std::string> ParseTaskExpect(const YAML::Node& node, const std::vector<std::string>& choices,
                                    const yaml::FileErrors& err) {
  const std::string given = node.IsScalar() ? node.Scalar() : "";
  const std::string canonical = CanonicalOutcome(given);
  if (canonical != given && std::find(choices.begin(), choices.end(), canonical) != choices.end()) {
    return canonical;
  }
  return yaml::OneOf(node, "task.expect", choices, err);
}

std::string ScenarioSpelling(std::string_view msg_name, bool space) {
  std::string out(msg_name);
  for (char& c : out) {
    c = c == '_' && space ? ' ' : static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return out;
}

}  // namespace rover::deploy::runner
