#include "truth_check.hpp"

#include <gtest/gtest.h>

#include "rover/testing/fakes/range_synth.hpp"
#include "test_maps.hpp"

namespace rover::apl::gestalt::testing {
namespace {

using rover::testing::AddRock;
using rover::testing::FlatWorld;

TEST(TruthCheck, CountsMarkedHazardsAndUnexplainedObstacles) {
  sim::terrain::Terrain world = FlatWorld(14.0);
  AddRock(&world, 2.0, 1.0, 0.6, 0.3);    // a hazard
  AddRock(&world, -3.0, 0.0, 0.3, 0.12);  // small: excuses obstacles next to it, is no hazard
  const GestaltOptions o;
  nav_core::GoodnessMap m = KnownMap(255);
  const Eigen::Vector2d rover(0.0, 0.0);
  HazardQuality q = CompareWithTruth(m, world, rover, o);
  EXPECT_EQ(q.hazards_seen, 1);
  EXPECT_EQ(q.hazards_marked, 0);
  EXPECT_EQ(q.obstacle_cells, 0);
  EXPECT_DOUBLE_EQ(q.recall(), 0.0);
  // Mark the hazard's cell, a cell 1 m from the small rock, and a cell with no rock near.
  auto set = [&m](double x, double y, int g) {
    int i, j;
    m.CellOf(x, y, &i, &j);
    m.goodness[m.Index(i, j)] = static_cast<std::uint8_t>(g);
  };
  set(2.0, 1.0, 0);
  set(-3.0, 1.0, 5);
  set(0.0, -3.0, 0);
  q = CompareWithTruth(m, world, rover, o);
  EXPECT_EQ(q.hazards_marked, 1);
  EXPECT_EQ(q.obstacle_cells, 3);
  EXPECT_EQ(q.false_obstacles, 1);
  EXPECT_NEAR(q.false_rate(), 1.0 / 3.0, 1e-12);
  // Unknown hazards are not counted as seen; cells beyond the radius are not counted.
  m.flags[m.Index(35, 30)] = 0;
  TruthCheckOptions near;
  near.radius = 2.0;
  q = CompareWithTruth(m, world, rover, o, near);
  EXPECT_EQ(q.hazards_seen, 0);
  EXPECT_EQ(q.obstacle_cells, 0);
}

}  // namespace
}  // namespace rover::apl::gestalt::testing
