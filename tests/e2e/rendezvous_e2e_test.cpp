// `roverctl run tests/e2e/scenarios/short_lander_return.yaml` end to end with the rendezvous
// service set (deploy/rendezvous.compose.yaml: the autonav set without dl-vo, plus dl-mast and
// apl-rendezvous): the rover must find the lander, stop at the base of ramp 0 within a few
// centimetres (the judge measures it against the simulator's lander), climb onto the deck, and
// leave drawn sightings in the run folder.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "rover/testing/roverctl_runner.hpp"
#include "rover/testing/test_support.hpp"

namespace rover {
namespace {
namespace fs = std::filesystem;

// The entry `name` of result.json's `list` ("criteria" or "figures"), or null.
nlohmann::json Entry(const nlohmann::json& result, const char* list, const std::string& name) {
  for (const auto& c : result[list]) {
    if (c.value("name", "") == name) return c;
  }
  return nullptr;
}

TEST(RendezvousE2e, ShortLanderReturnEndsOnTheDeckAfterAPlacementAtTheRampBase) {
  testing::UseLoopbackDds();
  const std::string dir = testing::MakeTempDir("rendezvous-e2e");
  testing::RoverctlRunner roverctl(dir);
  const auto [e, out] = roverctl.Run(
      {"run", testing::SourceDir() + "/tests/e2e/scenarios/short_lander_return.yaml", "--out",
       dir + "/out"},
      std::chrono::minutes(12));
  roverctl.KillLeftovers();

  const std::string run = dir + "/out/short-lander-return-seed1";
  ASSERT_TRUE(fs::exists(run + "/result.json")) << out;
  std::ifstream in(run + "/result.json");
  const nlohmann::json result = nlohmann::json::parse(in);

  const nlohmann::json on_deck = Entry(result, "criteria", "on_deck");
  ASSERT_FALSE(on_deck.is_null()) << result.dump(2);
  EXPECT_EQ(on_deck["measured"].get<double>(), 1.0);
  for (const char* name : {"placement_lateral", "placement_longitudinal"}) {
    const nlohmann::json f = Entry(result, "figures", name);
    ASSERT_FALSE(f.is_null()) << name;
    EXPECT_LT(f["measured"].get<double>(), 3.0) << name << " [cm]";
  }
  const nlohmann::json heading = Entry(result, "figures", "placement_heading");
  ASSERT_FALSE(heading.is_null());
  EXPECT_LT(heading["measured"].get<double>(), 2.5) << "[deg]";
  bool drawn = false;
  for (const auto& f : fs::directory_iterator(run + "/detections")) {
    drawn |= f.path().extension() == ".png";
  }
  EXPECT_TRUE(drawn) << "no drawn sighting in " << run << "/detections";
  EXPECT_TRUE(result["pass"].get<bool>()) << result.value("failure", "") << "\n" << out;
  EXPECT_EQ(e.code, 0) << out;

  std::error_code ec;
  if (!::testing::Test::HasFailure()) fs::remove_all(dir, ec);
}

// FIDO's single-command science-target approach (TARGET_SCIENCE), short: the target picked in
// a NAVCAM image, tracked to the standoff, the arm's instrument put on it within 2 cm of the
// picked point and touching; then a target
// that leaves the view ends in its typed goal error with nothing driven after the lost pair.
TEST(RendezvousE2e, ShortScienceTargetApproachAndALostTarget) {
  testing::UseLoopbackDds();
  const std::string dir = testing::MakeTempDir("science-e2e");
  testing::RoverctlRunner roverctl(dir);
  const auto [e, out] = roverctl.Run(
      {"run", testing::SourceDir() + "/tests/e2e/scenarios/short_science_target.yaml", "--out",
       dir + "/out"},
      std::chrono::minutes(8));
  roverctl.KillLeftovers();
  const std::string run = dir + "/out/short-science-target-seed1";
  ASSERT_TRUE(fs::exists(run + "/result.json")) << out;
  std::ifstream in(run + "/result.json");
  const nlohmann::json result = nlohmann::json::parse(in);
  EXPECT_TRUE(result["pass"].get<bool>()) << result.value("failure", "") << "\n" << out;
  const nlohmann::json placement = Entry(result, "figures", "placement_error");
  ASSERT_FALSE(placement.is_null()) << result.dump(2);
  EXPECT_LT(placement["measured"].get<double>(), 2.0) << "[cm]";
  const nlohmann::json contact = Entry(result, "figures", "instrument_contact");
  ASSERT_FALSE(contact.is_null()) << result.dump(2);
  EXPECT_EQ(contact["measured"].get<double>(), 1.0);
  EXPECT_FALSE(Entry(result, "figures", "aim_error").is_null());
  // FIDO's single command ends with the microscopic imager focused on the target. The
  // target is on the rock's flank, whose relief across the 20 mm field moves the whole frame's
  // best focus off the centre's: within twice the depth of field (+-2.31 mm) is asked here; the
  // share in focus is a campaign figure (docs/status.md).
  EXPECT_FALSE(Entry(result, "figures", "in_focus").is_null()) << result.dump(2);
  const nlohmann::json focus = Entry(result, "figures", "focus_error");
  ASSERT_FALSE(focus.is_null()) << result.dump(2);
  EXPECT_LT(focus["measured"].get<double>(), 4.6) << "[mm]";
  const nlohmann::json odometry = Entry(result, "figures", "odometry_placement_error");
  ASSERT_FALSE(odometry.is_null());
  EXPECT_TRUE(fs::exists(run + "/detections/target_00.png"));
  EXPECT_EQ(e.code, 0) << out;

  const auto [e2, out2] = roverctl.Run(
      {"run", testing::SourceDir() + "/deploy/scenarios/science_target_lost.yaml", "--out",
       dir + "/lost"},
      std::chrono::minutes(6));
  roverctl.KillLeftovers();
  const std::string lost = dir + "/lost/science-target-lost-seed1";
  ASSERT_TRUE(fs::exists(lost + "/result.json")) << out2;
  std::ifstream in2(lost + "/result.json");
  const nlohmann::json r2 = nlohmann::json::parse(in2);
  EXPECT_TRUE(r2["pass"].get<bool>()) << r2.value("failure", "") << "\n" << out2;
  ASSERT_EQ(r2["steps"].size(), 2u) << r2.dump(2);
  EXPECT_EQ(r2["steps"][1].value("termination", ""), "TARGET_LOST");
  EXPECT_NE(r2["steps"][1].value("message", "").find("OUT_OF_VIEW"), std::string::npos);
  EXPECT_LT(r2["distance_driven_m"].get<double>(), 1.2) << "nothing driven after the lost pair";
  EXPECT_EQ(e2.code, 0) << out2;

  std::error_code ec;
  if (!::testing::Test::HasFailure()) fs::remove_all(dir, ec);
}

// FIDO's auto-focus through the whole set: the runner designates one rock top and one soil spot
// with a height error, dl-arm sweeps the microscopic imager (frames rendered by rover-sim with
// the lens's depth of field, through ddl-camera) and ends FOCUSED within the depth of field.
TEST(RendezvousE2e, ShortAutofocusOnRockAndSoil) {
  testing::UseLoopbackDds();
  const std::string dir = testing::MakeTempDir("autofocus-e2e");
  testing::RoverctlRunner roverctl(dir);
  const auto [e, out] = roverctl.Run(
      {"run", testing::SourceDir() + "/tests/e2e/scenarios/short_autofocus.yaml", "--out",
       dir + "/out"},
      std::chrono::minutes(6));
  roverctl.KillLeftovers();
  const std::string run = dir + "/out/short-autofocus-seed1";
  ASSERT_TRUE(fs::exists(run + "/result.json")) << out;
  std::ifstream in(run + "/result.json");
  const nlohmann::json result = nlohmann::json::parse(in);
  EXPECT_TRUE(result["pass"].get<bool>()) << result.value("failure", "") << "\n" << out;
  ASSERT_EQ(result["steps"].size(), 2u) << result.dump(2);
  for (const auto& step : result["steps"]) {
    EXPECT_EQ(step.value("state", ""), "succeeded") << step.dump();
    EXPECT_EQ(step.value("termination", ""), "in_focus") << step.dump();
  }
  const nlohmann::json worst = Entry(result, "figures", "focus_error_worst");
  ASSERT_FALSE(worst.is_null()) << result.dump(2);
  EXPECT_LT(worst["measured"].get<double>(), 2.31) << "[mm] the depth of field";
  EXPECT_EQ(Entry(result, "figures", "focus_failed")["measured"].get<double>(), 0.0);
  EXPECT_EQ(e.code, 0) << out;

  std::error_code ec;
  if (!::testing::Test::HasFailure()) fs::remove_all(dir, ec);
}

}  // namespace
}  // namespace rover
