// The shipped autonomous-driving scenarios: each loads with the full validation, runs a mobility
// task that expects the outcome its comment argues for, and its world has the feature the
// outcome depends on (the wall, the zone, the rock across the line to the goal). Running them end
// to end needs apl-mobility (tests/e2e).
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "rover/deploy/runner.hpp"
#include "rover/deploy/runner/autonav_judging.hpp"
#include "rover/deploy/runner/task.hpp"
#include "rover/deploy/runner/tasks/mobility_task.hpp"
#include "rover/sim/world/world.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::deploy::runner {
namespace {

struct Loaded {
  Scenario scenario;
  MobilityTaskSpec spec;
  sim::world::World world;
};

Loaded Load(const std::string& name) {
  const std::string path = rover::testing::SourceDir() + "/deploy/scenarios/" + name;
  auto s = LoadScenario(path);
  EXPECT_TRUE(s.ok()) << s.status().message();
  Loaded out{*s, {}, {}};
  auto task = TaskRegistry::Builtin().Make(*s);
  EXPECT_TRUE(task.ok()) << task.status().message();
  const auto* mobility = dynamic_cast<const MobilityTask*>(task->get());
  EXPECT_NE(mobility, nullptr) << name << " is not a mobility task";
  if (mobility) out.spec = mobility->spec();
  ParamSet p("rover-sim");
  sim::world::DeclareWorldParams(p);
  EXPECT_TRUE(p.LoadYamlSections(s->text, path, sim::world::WorldSections()).ok());
  auto w = sim::world::BuildWorld(p);
  EXPECT_TRUE(w.ok()) << w.status().message();
  out.world = std::move(*w);
  return out;
}

// Where the rover would drive in a straight line: start to goal (or along the primitive).
Track StraightLine(const Loaded& l, double length) {
  Track t;
  Eigen::Vector2d a(l.world.start_x, l.world.start_y);
  Eigen::Vector2d dir(std::cos(l.world.start_yaw), std::sin(l.world.start_yaw));
  if (l.spec.goal) {
    length = (l.spec.goal->xy - a).norm();
    dir = (l.spec.goal->xy - a).normalized();
  }
  for (double s = 0; s <= length + 1e-9; s += 0.1) {
    const Eigen::Vector2d p = a + s * dir;
    t.push_back({s, p.x(), p.y()});
  }
  return t;
}

// Placed rocks taller than the traversable height that a 1.2 m wide rover on the line would hit.
int BlockingRocks(const Loaded& l, const Track& line) {
  int n = 0;
  for (const auto& r : l.world.terrain.rocks) {
    if (!r.placed || r.height <= l.scenario.criteria.traversable_height) continue;
    for (const auto& q : line) {
      if ((r.position.head<2>() - Eigen::Vector2d(q[1], q[2])).norm() < 0.6 + r.diameter / 2) {
        ++n;
        break;
      }
    }
  }
  return n;
}

TEST(AutonavScenarios, RockFieldsReachTheirGoal) {
  for (const auto& [file, preset, distance] :
       std::vector<std::tuple<std::string, sim::terrain::RockPreset, double>>{
           {"autonav_vl1.yaml", sim::terrain::RockPreset::kVl1, 25},
           {"autonav_vl2.yaml", sim::terrain::RockPreset::kVl2, 30}}) {
    const Loaded l = Load(file);
    EXPECT_EQ(l.spec.type, MobilityTaskType::kAutonav) << file;
    EXPECT_EQ(l.spec.expect, "reached") << file;
    EXPECT_EQ(l.spec.think, msg::ThinkMode::kDriveWhileThinking) << file;
    ASSERT_TRUE(l.spec.goal.has_value());
    EXPECT_NEAR(l.spec.goal->xy.norm(), distance, 1e-9) << file;
    EXPECT_EQ(l.world.terrain.params.rocks.preset, preset) << file;
    EXPECT_EQ(l.scenario.criteria.max_hazard_contacts, 0) << file;
    ASSERT_TRUE(l.scenario.criteria.target_xy.has_value());
    // The rock field covers the whole way.
    EXPECT_GT(l.world.terrain.natural.max_x(), distance + 2) << file;
  }
}

TEST(AutonavScenarios, TheWallBlocksTheLineAndADetourIsExpected) {
  const Loaded l = Load("autonav_wall.yaml");
  EXPECT_EQ(l.spec.expect, "reached");
  EXPECT_GE(BlockingRocks(l, StraightLine(l, 0)), 3);
  // Room to go round either end: the wall ends 4 m from the line, the map 15 m.
  double min_y = 1e9, max_y = -1e9;
  for (const auto& r : l.world.terrain.rocks) {
    if (!r.placed) continue;
    min_y = std::min(min_y, r.position.y());
    max_y = std::max(max_y, r.position.y());
  }
  EXPECT_NEAR(min_y, -4, 0.01);
  EXPECT_NEAR(max_y, 4, 0.01);
  EXPECT_GT(l.world.terrain.natural.max_y() - max_y, 5);
  EXPECT_GT(min_y - l.world.terrain.natural.min_y(), 5);
  // A detour is longer than the straight line.
  EXPECT_GT(*l.scenario.criteria.min_distance, l.spec.goal->xy.norm());
}

TEST(AutonavScenarios, TheKeepOutZoneCrossesTheLineAndKeepoutIsExpected) {
  const Loaded l = Load("autonav_keepout.yaml");
  EXPECT_EQ(l.spec.expect, "KEEPOUT");
  ASSERT_EQ(l.spec.keep_out.size(), 1u);
  std::vector<std::vector<Eigen::Vector2d>> zones = {l.spec.keep_out[0].vertices};
  EXPECT_GT(KeepOutEntries(StraightLine(l, 0), zones, 0.0), 0);
  EXPECT_EQ(KeepOutEntries(StraightLine(l, 0), {}, 0.0), 0);
}

TEST(AutonavScenarios, GuardedDriveHeadsStraightAtABigRockAndExpectsAVeto) {
  const Loaded l = Load("guarded_rock.yaml");
  EXPECT_EQ(l.spec.type, MobilityTaskType::kGuarded);
  EXPECT_EQ(l.spec.expect, "vetoed");
  ASSERT_EQ(l.spec.primitives.size(), 1u);
  EXPECT_EQ(l.spec.primitives[0].primitive, Primitive::kStraight);
  EXPECT_EQ(BlockingRocks(l, StraightLine(l, l.spec.primitives[0].distance)), 1);
}

TEST(AutonavScenarios, TheCulDeSacClosesThreeSidesAndNoprogressIsExpected) {
  const Loaded l = Load("autonav_cul_de_sac.yaml");
  EXPECT_EQ(l.spec.expect, "NOPROGRESS");
  EXPECT_GE(BlockingRocks(l, StraightLine(l, 0)), 3);
  // Walls left, right and ahead of the way in: rocks at y = +-4 and at x = 12.
  int left = 0, right = 0, back = 0;
  for (const auto& r : l.world.terrain.rocks) {
    if (!r.placed) continue;
    left += std::abs(r.position.y() - 4) < 0.01;
    right += std::abs(r.position.y() + 4) < 0.01;
    back += std::abs(r.position.x() - 12) < 0.01;
  }
  EXPECT_GT(left, 10);
  EXPECT_GT(right, 10);
  EXPECT_GT(back, 10);
}

TEST(AutonavScenarios, TheirServiceSetRunsTheMobilityManager) {
  std::ifstream in(rover::testing::SourceDir() + "/deploy/autonav.compose.yaml");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string text = ss.str();
  for (const char* service : {"rover-sim", "ddl-motor", "ddl-joints", "ddl-imu", "ddl-sun-sensor",
                              "ddl-camera", "dl-locomotion", "dl-pose", "dl-stereo", "dl-vo",
                              "apl-mobility"}) {
    EXPECT_NE(text.find(std::string("\n  ") + service + ":"), std::string::npos) << service;
  }
  for (const char* file : {"autonav_vl1.yaml", "autonav_vl2.yaml", "autonav_wall.yaml",
                           "autonav_keepout.yaml", "guarded_rock.yaml",
                           "autonav_cul_de_sac.yaml"}) {
    EXPECT_EQ(Load(file).scenario.compose_path,
              rover::testing::SourceDir() + "/deploy/autonav.compose.yaml")
        << file;
  }
}

}  // namespace
}  // namespace rover::deploy::runner
