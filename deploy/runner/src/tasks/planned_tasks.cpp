#include "rover/deploy/runner/tasks/planned_tasks.hpp"

namespace rover::deploy::runner {
namespace {

// A task whose services do not exist yet: nothing to open, nothing to wait for; its run fails.
class UnavailableTask : public Task {
 public:
  UnavailableTask(std::string type, Eigen::Vector2d start, std::optional<TaskGoal> goal)
      : type_(std::move(type)), start_(start), goal_(goal) {}

  Status Open(TaskContext&) override { return Status::Ok(); }
  bool Ready() const override { return true; }
  TaskOutcome Run(TaskContext&) override {
    return {{},
            "task type '" + type_ +
                "' needs the autonomous-navigation services, which this stack does not have "
                "yet"};
  }
  std::vector<Eigen::Vector2d> PlannedPath() const override {
    std::vector<Eigen::Vector2d> path{start_};
    if (goal_) path.push_back(goal_->xy);
    return path;
  }

 private:
  std::string type_;
  Eigen::Vector2d start_;
  std::optional<TaskGoal> goal_;
};

TaskFactory Factory(std::string type, bool needs_goal) {
  return [type, needs_goal](const TaskSource& source) -> Result<std::unique_ptr<Task>> {
    ROVER_RETURN_IF_ERROR(yaml::CheckKeys(source.section, "task", {"type", "goal"}, source.errors));
    ROVER_ASSIGN_OR_RETURN(std::optional<TaskGoal> goal, ParseTaskGoal(source));
    if (needs_goal && !goal) {
      return source.errors.At(source.section, "task: a '" + type + "' task needs a 'goal'");
    }
    const Scenario& s = source.scenario;
    return std::unique_ptr<Task>(
        std::make_unique<UnavailableTask>(type, Eigen::Vector2d(s.start_x, s.start_y), goal));
  };
}

}  // namespace

void RegisterPlannedTasks(TaskRegistry& registry) {
  registry.Register("long_traverse", "a long autonomous traverse to `goal` (planned)",
                    Factory("long_traverse", true));
}

}  // namespace rover::deploy::runner
