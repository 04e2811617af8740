#include "rover/deploy/runner/tasks/autofocus_task.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "run_fixture.hpp"

namespace rover::deploy::runner {
namespace {

using ::testing::HasSubstr;
using testing::ScenarioWithTask;

TEST(AutofocusTask, ParsesAndChecksItsSection) {
  auto t = TaskRegistry::Builtin().Make(ScenarioWithTask(
      "task: {type: autofocus, soil: 4, rock: 1, height_error: 0.03, target_timeout_s: 200, "
      "time_budget_s: 1000}\n"));
  ASSERT_TRUE(t.ok()) << t.status().message();
  const AutofocusSpec& spec = dynamic_cast<const AutofocusTask&>(**t).spec();
  EXPECT_EQ(spec.soil, 4);
  EXPECT_EQ(spec.rock, 1);
  EXPECT_DOUBLE_EQ(spec.height_error, 0.03);
  EXPECT_DOUBLE_EQ(spec.target_timeout_s, 200.0);
  EXPECT_DOUBLE_EQ(spec.time_budget_s, 1000.0);
  EXPECT_EQ((*t)->PlannedPath(), (std::vector<Eigen::Vector2d>{{1, 2}}));
  // Defaults: three soil spots and two rocks, 2.5 cm of height error.
  auto d = TaskRegistry::Builtin().Make(ScenarioWithTask("task: {type: autofocus}\n"));
  ASSERT_TRUE(d.ok()) << d.status().message();
  EXPECT_EQ(dynamic_cast<const AutofocusTask&>(**d).spec().soil, 3);
  EXPECT_EQ(dynamic_cast<const AutofocusTask&>(**d).spec().rock, 2);

  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: autofocus, soil: 0, rock: 0}\n")).message(),
              HasSubstr("soil and rock are both 0"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: autofocus, soil: 2.5}\n")).message(),
              HasSubstr("task.soil: 2.5 is not a count"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: autofocus, rock: -1}\n")).message(),
              HasSubstr("rock"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: autofocus, height_error: 0.5}\n")).message(),
              HasSubstr("height_error"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: autofocus, targets: 3}\n")).message(),
              HasSubstr("targets"));
}

}  // namespace
}  // namespace rover::deploy::runner
