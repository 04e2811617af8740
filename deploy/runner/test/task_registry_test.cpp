#include <gtest/gtest.h>

#include "rover/deploy/runner/task.hpp"
#include "run_fixture.hpp"

namespace rover::deploy::runner {
namespace {

using testing::ScenarioWithTask;

class NullTask : public Task {
 public:
  explicit NullTask(std::string label) : label_(std::move(label)) {}
  Status Open(TaskContext&) override { return Status::Ok(); }
  bool Ready() const override { return true; }
  TaskOutcome Run(TaskContext&) override { return {{}, label_}; }
  std::vector<Eigen::Vector2d> PlannedPath() const override { return {}; }
  std::string label_;
};

TEST(TaskRegistry, BuiltinTypesInOrder) {
  EXPECT_EQ(TaskRegistry::Builtin().Types(),
            (std::vector<std::string>{"directed", "autonav", "goto_waypoint", "guarded",
                                      "guarded_arc", "lander_return", "long_traverse",
                                      "science_target", "sequence", "autofocus"}));
  EXPECT_NE(TaskRegistry::Builtin().Describe().find("directed "), std::string::npos);
}

TEST(TaskRegistry, UnknownTypeNamesFileLineAndTheKnownTypes) {
  const Scenario s = ScenarioWithTask("task:\n  type: directd\n");
  auto t = TaskRegistry::Builtin().Make(s);
  ASSERT_FALSE(t.ok());
  EXPECT_EQ(t.status().message(),
            "s.yaml:3: task.type: 'directd' is not one of: directed, autonav, goto_waypoint, "
            "guarded, guarded_arc, lander_return, long_traverse, science_target, sequence, "
            "autofocus (did you mean 'directed'?)");
  EXPECT_EQ(ValidateTask(ScenarioWithTask("task: {type: fly}\n")).message(),
            "s.yaml:2: task.type: 'fly' is not one of: directed, autonav, goto_waypoint, guarded, "
            "guarded_arc, lander_return, long_traverse, science_target, sequence, autofocus");
}

TEST(TaskRegistry, AFactoryGetsItsSectionAndOwnsItsKeys) {
  TaskRegistry r;
  r.Register("probe", "a test task", [](const TaskSource& src) -> Result<std::unique_ptr<Task>> {
    ROVER_RETURN_IF_ERROR(yaml::CheckKeys(src.section, "task", {"type", "label"}, src.errors));
    return std::unique_ptr<Task>(
        std::make_unique<NullTask>(yaml::ScalarText(src.section["label"])));
  });
  EXPECT_EQ(r.Types(), std::vector<std::string>{"probe"});
  auto ok = r.Make(ScenarioWithTask("task: {type: probe, label: hello}\n"));
  ASSERT_TRUE(ok.ok()) << ok.status().message();
  EXPECT_EQ(static_cast<NullTask&>(**ok).label_, "hello");
  // A key of another task type is the task's own error, with its line.
  auto bad = r.Make(ScenarioWithTask("task:\n  type: probe\n  steps: []\n"));
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "s.yaml:4: task: unknown key 'steps' (known: type, label)");
  // The built-in registry does not know it.
  EXPECT_FALSE(TaskRegistry::Builtin().Make(ScenarioWithTask("task: {type: probe}\n")).ok());
}

TEST(TaskRegistryDeathTest, RegisteringATypeTwiceIsABug) {
  TaskRegistry r;
  auto factory = [](const TaskSource&) -> Result<std::unique_ptr<Task>> {
    return std::unique_ptr<Task>(std::make_unique<NullTask>(""));
  };
  r.Register("a", "", factory);
  EXPECT_DEATH(r.Register("a", "", factory), "");
}

TEST(TaskGoal, ParsedWithItsChecks) {
  const yaml::FileErrors err("s.yaml");
  auto goal_of = [&](const std::string& text) {
    const Scenario s = ScenarioWithTask(text);
    const YAML::Node root = YAML::Load(s.text);
    const YAML::Node section = root["task"];
    return ParseTaskGoal(TaskSource{s, section, err});
  };
  auto none = goal_of("task: {type: autonav}\n");
  ASSERT_TRUE(none.ok());
  EXPECT_FALSE(none->has_value());
  auto g = goal_of("task: {type: autonav, goal: {x: 20, y: -5, tolerance: 2}}\n");
  ASSERT_TRUE(g.ok()) << g.status().message();
  EXPECT_EQ((*g)->xy, Eigen::Vector2d(20, -5));
  EXPECT_EQ((*g)->tolerance, 2);
  EXPECT_EQ(goal_of("task: {type: autonav, goal: {x: 20}}\n").status().message(),
            "s.yaml:2: task.goal: needs both 'x' and 'y'");
  EXPECT_EQ(goal_of("task: {type: autonav, goal: {x: 1, y: 1, tolerance: 0}}\n").status().message(),
            "s.yaml:2: task.goal.tolerance: 0 is out of range [0.01, 100]");
  EXPECT_EQ(goal_of("task: {type: autonav, goal: {x: 1, y: 1, z: 0}}\n").status().message(),
            "s.yaml:2: task.goal: unknown key 'z' (did you mean 'x'?) (known: x, y, tolerance)");
}

}  // namespace
}  // namespace rover::deploy::runner
