// `roverctl run tests/e2e/scenarios/short_autonav.yaml` end to end with the autonav service set
// (simulator, DDL drivers, dl-locomotion, dl-pose, ddl-camera, dl-stereo, dl-vo, apl-mobility):
// the mobility manager must end the way the scenario's `expect:` says (reached), with no motion
// error (the MOT stall of the first autonav run) and no hazard contact, and the run must pass.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "rover/base/process.hpp"
#include "rover/testing/roverctl_runner.hpp"
#include "rover/testing/test_support.hpp"

namespace rover {
namespace {
namespace fs = std::filesystem;

// The criterion `name` of result.json's "criteria", or null.
nlohmann::json Criterion(const nlohmann::json& result, const std::string& name) {
  for (const auto& c : result["criteria"]) {
    if (c.value("name", "") == name) return c;
  }
  return nullptr;
}

TEST(AutonavE2e, ShortAutonavReachesItsGoalWithoutFaultOrHazardContact) {
  testing::UseLoopbackDds();
  const std::string dir = testing::MakeTempDir("autonav-e2e");
  testing::RoverctlRunner roverctl(dir);
  const auto [e, out] =
      roverctl.Run({"run", testing::SourceDir() + "/tests/e2e/scenarios/short_autonav.yaml",
                    "--out", dir + "/out"},
                   std::chrono::minutes(8));
  roverctl.KillLeftovers();

  const std::string result_path = dir + "/out/short-autonav-seed1/result.json";
  ASSERT_TRUE(fs::exists(result_path)) << out;
  std::ifstream in(result_path);
  const nlohmann::json result = nlohmann::json::parse(in);
  ASSERT_TRUE(result.contains("mobility")) << result.dump(2);
  const nlohmann::json& mob = result["mobility"];

  // The outcome the scenario expects, and no fault of either class on the way.
  EXPECT_EQ(mob.value("expect", ""), "reached");
  EXPECT_EQ(mob.value("outcome", ""), mob.value("expect", "?")) << mob.dump(2);
  EXPECT_NE(mob.value("fault", ""), "MOT") << mob.value("message", "");
  EXPECT_NE(mob.value("fault_class", ""), "motion error") << mob.value("message", "");
  EXPECT_GE(mob.value("steps", 0), 2) << "autonav must have taken steps of its own";

  // No hazard contact (a truth rock above the traversable height touched by the rover).
  const nlohmann::json contacts = Criterion(result, "hazard_contacts");
  ASSERT_FALSE(contacts.is_null()) << result.dump(2);
  EXPECT_EQ(contacts["measured"].get<double>(), 0.0);
  EXPECT_TRUE(contacts["pass"].get<bool>());

  EXPECT_TRUE(result["pass"].get<bool>()) << result.value("failure", "") << "\n" << out;
  EXPECT_EQ(e.code, 0) << out;

  std::error_code ec;
  if (!::testing::Test::HasFailure()) fs::remove_all(dir, ec);
}

}  // namespace
}  // namespace rover
