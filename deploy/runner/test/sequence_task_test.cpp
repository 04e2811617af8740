#include "rover/deploy/runner/tasks/sequence_task.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rover/testing/test_support.hpp"
#include "run_fixture.hpp"

namespace rover::deploy::runner {
namespace {

using ::testing::HasSubstr;
using testing::ScenarioWithTask;

std::string Template() { return rover::testing::SourceDir() + "/deploy/sequences/approach_template.seq"; }

TEST(SequenceTask, ParsesAndChecksItsSection) {
  auto t = TaskRegistry::Builtin().Make(ScenarioWithTask(
      "task: {type: sequence, file: " + Template() +
      ", set: {target: '(4, 0.3, 0)', fine_step: 5 cm}, time_budget_s: 900, expect: failed}\n"));
  ASSERT_TRUE(t.ok()) << t.status().message();
  const SequenceSpec& spec = dynamic_cast<const SequenceTask&>(**t).spec();
  EXPECT_THAT(spec.text, HasSubstr("TARGET target = (6.0, 0.0, 0.0)"));
  EXPECT_EQ(spec.overrides.at("target"), "(4, 0.3, 0)");
  EXPECT_EQ(spec.overrides.at("fine_step"), "5 cm");
  EXPECT_EQ(spec.expect, "failed");
  EXPECT_EQ(spec.time_budget_s, 900.0);
  EXPECT_EQ((*t)->PlannedPath(), (std::vector<Eigen::Vector2d>{{1, 2}}));

  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: sequence}\n")).message(),
              HasSubstr("missing 'file'"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: sequence, file: /no/such.seq}\n")).message(),
              HasSubstr("task.file: cannot read '/no/such.seq'"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: sequence, file: " + Template() +
                                            ", set: [1, 2]}\n"))
                  .message(),
              HasSubstr("task.set: is not a map"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: sequence, file: " + Template() +
                                            ", set: {target: {x: 1}}}\n"))
                  .message(),
              HasSubstr("task.set.target: is not a single value"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: sequence, file: " + Template() +
                                            ", set: {'two words': 1}}\n"))
                  .message(),
              HasSubstr("task.set:"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: sequence, file: " + Template() +
                                            ", expect: aborted}\n"))
                  .message(),
              HasSubstr("task.expect: 'aborted' is not one of: done, failed"));
  EXPECT_THAT(ValidateTask(ScenarioWithTask("task: {type: sequence, file: " + Template() +
                                            ", speed: 3}\n"))
                  .message(),
              HasSubstr("unknown key 'speed'"));
}

TEST(SequenceTask, WithoutASequencerItIsNotReady) {
  auto t = TaskRegistry::Builtin().Make(
      ScenarioWithTask("task: {type: sequence, file: " + Template() + "}\n"));
  ASSERT_TRUE(t.ok()) << t.status().message();
  testing::RunFixture run;
  TaskContext ctx = run.Context();
  ASSERT_TRUE((*t)->Open(ctx).ok());
  EXPECT_FALSE((*t)->Ready());
}

}  // namespace
}  // namespace rover::deploy::runner
