#include "rover/deploy/runner/service_set.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "scenario_files.hpp"

namespace rover::deploy::runner {
namespace {

class PrepareRunTest : public testing::ScenarioFiles {};

TEST_F(PrepareRunTest, WritesEachServicesParametersAndBuildsTheWorld) {
  auto s = Load(testing::kSmallScenario);
  ASSERT_TRUE(s.ok()) << s.status().message();
  auto p = PrepareRun(*s, 3, Options());
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_EQ(p->run_dir, dir_ + "/out/tiny-seed3");
  EXPECT_EQ(p->project.rover.clock, "sim");
  EXPECT_EQ(p->project.rover.project.rfind("tiny-seed3-", 0), 0u) << p->project.rover.project;
  EXPECT_FALSE(p->project.rover.domain.has_value());
  // The simulator gets the world sections with this seed and starts paused.
  const std::string sim = rover::testing::ReadFile(p->run_dir + "/params/rover-sim.yaml");
  EXPECT_NE(sim.find("seed: 3"), std::string::npos) << sim;
  EXPECT_NE(sim.find("start_paused: true"), std::string::npos) << sim;
  EXPECT_NE(sim.find("yaw_deg: 90"), std::string::npos) << sim;
  EXPECT_EQ(p->project.Find("rover-sim")->environment.at("ROVER_PARAMS"),
            p->run_dir + "/params/rover-sim.yaml");
  // The estimator is told the start pose, then gets the scenario's own overrides.
  const std::string pose = rover::testing::ReadFile(p->run_dir + "/params/dl-pose.overrides.yaml");
  EXPECT_EQ(pose, "ekf.gyro_noise: 0.001\nstart.x: 1.5\nstart.y: -0.5\nstart.yaw_deg: 90\n");
  EXPECT_EQ(p->project.Find("dl-pose")->environment.at("ROVER_PARAMS"),
            p->run_dir + "/params/dl-pose.overrides.yaml");
  EXPECT_NEAR(p->world.terrain.ground.heights().size(), 121 * 121, 500);
}

TEST_F(PrepareRunTest, SameSeedSameTerrainDigest) {
  auto s = Load(testing::kSmallScenario);
  ASSERT_TRUE(s.ok()) << s.status().message();
  auto a = PrepareRun(*s, 3, Options());
  auto b = PrepareRun(*s, 3, Options());
  auto c = PrepareRun(*s, 4, Options());
  ASSERT_TRUE(a.ok() && b.ok() && c.ok());
  EXPECT_EQ(TerrainDigest(a->world.terrain).size(), 16u);
  EXPECT_EQ(TerrainDigest(a->world.terrain), TerrainDigest(b->world.terrain));
  EXPECT_NE(TerrainDigest(a->world.terrain), TerrainDigest(c->world.terrain));
}

TEST_F(PrepareRunTest, ErrorsNameTheFileAndWhatIsWrong) {
  auto s = Load(testing::kSmallScenario);
  ASSERT_TRUE(s.ok()) << s.status().message();
  Compose("services:\n  sim: {command: \"true\"}\n  dl-pose: {command: \"true\"}\n");
  EXPECT_EQ(
      PrepareRun(*s, 1, Options()).status().message(),
      dir_ + "/s.yaml: simulator service 'rover-sim' is not in " + dir_ + "/set.compose.yaml");
  Compose("services:\n  rover-sim: {command: \"true\"}\n");
  EXPECT_EQ(PrepareRun(*s, 1, Options()).status().message(),
            dir_ + "/s.yaml: params.dl-pose: no such service in " + dir_ + "/set.compose.yaml");
  Compose("services:\n  rover-sim: {command: \"true\"}\n  dl-pose: {command: no-such-rover-exe}\n");
  EXPECT_EQ(
      PrepareRun(*s, 1, Options()).status().message(),
      dir_ + "/set.compose.yaml:3: services.dl-pose.command: no such command 'no-such-rover-exe'");
}

TEST_F(PrepareRunTest, AServiceSetLeasesItsOwnDomain) {
  auto s = Load(testing::kSmallScenario);
  ASSERT_TRUE(s.ok()) << s.status().message();
  auto p = PrepareRun(*s, 1, Options());
  ASSERT_TRUE(p.ok()) << p.status().message();
  auto a = ServiceSet::Create(*p);
  auto b = ServiceSet::Create(*p);
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_NE((*a)->domain(), (*b)->domain());
  EXPECT_FALSE((*a)->SimulatorHearsUs());  // no operator participant yet
}

// A fault campaign's kill -9: the killed service's exit and restart are not a crash; a second
// exit would be, and so is a kill of a service its restart policy does not bring back.
TEST_F(PrepareRunTest, AKilledServiceThatIsRestartedIsNotACrash) {
  auto s = Load(testing::kSmallScenario);
  ASSERT_TRUE(s.ok()) << s.status().message();
  Compose(
      "services:\n  rover-sim: {command: \"sleep 60\", restart: \"on-failure:3\"}\n"
      "  dl-pose: {command: \"sleep 60\", restart: \"no\"}\n");
  auto p = PrepareRun(*s, 1, Options());
  ASSERT_TRUE(p.ok()) << p.status().message();
  auto set = ServiceSet::Create(*p);
  ASSERT_TRUE(set.ok()) << set.status().message();
  ServiceSet& ss = **set;
  ASSERT_TRUE(ss.Start().ok());
  std::vector<std::string> crashes;
  EXPECT_FALSE(ss.Kill("no-such-service").ok());
  ASSERT_TRUE(ss.Kill("rover-sim").ok());
  bool again = false;
  for (int i = 0; i < 200 && !again; ++i) {
    EXPECT_EQ(ss.CheckServices(&crashes), "");
    again = ss.RunsAgain("rover-sim");
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  EXPECT_TRUE(again);
  EXPECT_TRUE(crashes.empty());
  ASSERT_TRUE(ss.Kill("dl-pose").ok());
  std::string crash;
  for (int i = 0; i < 200 && crash.empty(); ++i) {
    crash = ss.CheckServices(&crashes);
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  EXPECT_NE(crash.find("service 'dl-pose' crashed"), std::string::npos) << crash;
  ss.Stop();
}

}  // namespace
}  // namespace rover::deploy::runner
