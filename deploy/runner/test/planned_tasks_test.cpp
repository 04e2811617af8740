#include "rover/deploy/runner/tasks/planned_tasks.hpp"

#include <gtest/gtest.h>

#include "run_fixture.hpp"

namespace rover::deploy::runner {
namespace {

using testing::ScenarioWithTask;

TEST(PlannedTasks, ValidateTheirSection) {
  EXPECT_EQ(ValidateTask(ScenarioWithTask("task: {type: long_traverse}\n")).message(),
            "s.yaml:2: task: a 'long_traverse' task needs a 'goal'");
  EXPECT_EQ(
      ValidateTask(ScenarioWithTask("task: {type: long_traverse, goal: {x: 1, y: 1}, steps: []}\n"))
          .message(),
      "s.yaml:2: task: unknown key 'steps' (known: type, goal)");
  EXPECT_EQ(ValidateTask(ScenarioWithTask("task: {type: long_traverse, goal: {x: 1}}\n")).message(),
            "s.yaml:2: task.goal: needs both 'x' and 'y'");
}

TEST(PlannedTasks, ARunFailsSayingWhichServicesAreMissing) {
  auto t = TaskRegistry::Builtin().Make(
      ScenarioWithTask("task: {type: long_traverse, goal: {x: 5, y: 6}}\n"));
  ASSERT_TRUE(t.ok()) << t.status().message();
  EXPECT_EQ((*t)->PlannedPath(), (std::vector<Eigen::Vector2d>{{1, 2}, {5, 6}}));
  testing::RunFixture run;
  TaskContext ctx = run.Context();
  ASSERT_TRUE((*t)->Open(ctx).ok());
  EXPECT_TRUE((*t)->Ready());
  const TaskOutcome out = (*t)->Run(ctx);
  EXPECT_TRUE(out.steps.empty());
  EXPECT_EQ(out.failure,
            "task type 'long_traverse' needs the autonomous-navigation services, which this stack does "
            "not have yet");
}

}  // namespace
}  // namespace rover::deploy::runner
