#include "rover/deploy/runner/tasks/science_target_task.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "run_fixture.hpp"

namespace rover::deploy::runner {
namespace {

using ::testing::HasSubstr;
using testing::ScenarioWithTask;

TEST(ScienceTargetTask, ParsesAndChecksItsSection) {
  EXPECT_TRUE(ValidateTask(ScenarioWithTask(
                  "task: {type: science_target, target: 1, standoff: 1.1, pixel_offset: {x: 2, "
                  "y: -1}, time_budget_s: 900, expect: TARGET_LOST}\n"))
                  .ok());
  EXPECT_TRUE(ValidateTask(ScenarioWithTask("task: {type: science_target}\n")).ok());
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: science_target, target: 0.5}\n")).message(),
              HasSubstr("task.target: 0.5 is not an index"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: science_target, standoff: 9}\n")).message(),
              HasSubstr("task.standoff"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: science_target, pixel: 3}\n")).message(),
              HasSubstr("unknown key 'pixel'"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask(
                  "task: {type: science_target, pixel_offset: {x: 1, z: 2}}\n"))
                  .message(),
              HasSubstr("task.pixel_offset: unknown key 'z'"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: science_target, expect: touched}\n")).message(),
              HasSubstr("task.expect: 'touched' is not one of: at_target, BAD_COMMAND"));
  EXPECT_TRUE(ValidateTask(ScenarioWithTask(
                  "task: {type: science_target, place: true, autofocus: true}\n"))
                  .ok());
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: science_target, autofocus: yes}\n"))
                  .message(),
              HasSubstr("task.autofocus: yes is not true or false"));
}

TEST(ScienceTargetTask, WithoutTheWorldItSaysItNeedsTheTruthAndSendsNothing) {
  auto t = TaskRegistry::Builtin().Make(ScenarioWithTask("task: {type: science_target}\n"));
  ASSERT_TRUE(t.ok()) << t.status().message();
  EXPECT_EQ((*t)->PlannedPath(), (std::vector<Eigen::Vector2d>{{1, 2}}));
  testing::RunFixture run;
  TaskContext ctx = run.Context();
  ASSERT_TRUE((*t)->Open(ctx).ok());
  const TaskOutcome out = (*t)->Run(ctx);
  EXPECT_TRUE(out.steps.empty());
  EXPECT_THAT(out.failure, HasSubstr("needs the simulated world"));
}

}  // namespace
}  // namespace rover::deploy::runner
