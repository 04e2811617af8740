#include "rover/deploy/runner.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "scenario_files.hpp"

namespace rover::deploy {
namespace {
namespace fs = std::filesystem;

class RunnerTest : public runner::testing::ScenarioFiles {};

// The scenario format stays as it was: every shipped scenario loads with the full validation.
TEST(ShippedScenarios, AllLoad) {
  int n = 0;
  for (const char* dir : {"/deploy/scenarios", "/tests/e2e/scenarios"}) {
    for (const auto& e : fs::directory_iterator(rover::testing::SourceDir() + dir)) {
      if (e.path().extension() != ".yaml") continue;
      auto s = LoadScenario(e.path().string());
      EXPECT_TRUE(s.ok()) << s.status().message();
      ++n;
    }
  }
  EXPECT_GE(n, 10);
}

TEST_F(RunnerTest, LoadScenarioChecksTheTaskWithItsOwnKeysAndLines) {
  std::string text = runner::testing::kSmallScenario;
  text.replace(text.find("type: directed"), 14, "type: directd");
  EXPECT_EQ(Load(text).status().message(),
            dir_ +
                "/s.yaml:13: task.type: 'directd' is not one of: directed, autonav, "
                "goto_waypoint, guarded, guarded_arc, lander_return, long_traverse, "
                "science_target, sequence, autofocus (did you mean 'directed'?)");
  text = runner::testing::kSmallScenario;
  text.replace(text.find("distance: 2"), 11, "distance: 200");
  EXPECT_EQ(Load(text).status().message(),
            dir_ + "/s.yaml:15: task.steps[].distance: 200 is out of range [-100, 100]");
  // The simulator's sections too.
  text = runner::testing::kSmallScenario;
  text.replace(text.find("size_x: 6"), 9, "size_x: -6");
  EXPECT_EQ(Load(text).status().message().rfind(dir_ + "/s.yaml:6: ", 0), 0u)
      << Load(text).status().message();
}

TEST_F(RunnerTest, PreflightLeavesNothingBehind) {
  auto s = Load(runner::testing::kSmallScenario);
  ASSERT_TRUE(s.ok()) << s.status().message();
  ASSERT_TRUE(PreflightScenario(*s, 1, Options()).ok());
  EXPECT_FALSE(fs::exists(dir_ + "/out/tiny-seed1"));
}

TEST_F(RunnerTest, PreflightRejectsAnUnknownTaskBeforeAnythingIsMade) {
  auto s = Load(runner::testing::kSmallScenario);
  ASSERT_TRUE(s.ok()) << s.status().message();
  s->text.replace(s->text.find("type: directed"), 14, "type: teleport");
  s->task.type = "teleport";
  EXPECT_EQ(PreflightScenario(*s, 1, Options())
                .message()
                .rfind(dir_ + "/s.yaml:13: task.type: 'teleport'", 0),
            0u);
  EXPECT_FALSE(fs::exists(dir_ + "/out"));
  // RunScenario refuses it the same way: nothing is started.
  auto r = RunScenario(*s, 1, Options());
  ASSERT_FALSE(r.ok());
  EXPECT_FALSE(fs::exists(dir_ + "/out"));
}

TEST_F(RunnerTest, PreflightReportsABadServiceSet) {
  auto s = Load(runner::testing::kSmallScenario);
  ASSERT_TRUE(s.ok()) << s.status().message();
  Compose("services:\n  rover-sim: {command: \"true\"}\n  dl-pose: {command: no-such-rover-exe}\n");
  EXPECT_EQ(
      PreflightScenario(*s, 1, Options()).message(),
      dir_ + "/set.compose.yaml:3: services.dl-pose.command: no such command 'no-such-rover-exe'");
}

}  // namespace
}  // namespace rover::deploy
