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

}  // namespace
}  // namespace rover
