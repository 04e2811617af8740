#include "rover/apl/enav/cost_to_go.hpp"

#include <gtest/gtest.h>

#include "scene.hpp"

namespace rover::apl::enav {
namespace {

using testing::Block;
using testing::Blocks;
using testing::ScanOf;
using testing::TestOptions;

TEST(CostToGoField, OpenKnownGroundCostIsAboutTheDistance) {
  auto t = HeightTerrain::Create(TestOptions());
  ASSERT_TRUE(t.ok());
  ASSERT_TRUE(t->Update(ScanOf(Blocks({}), -4, 4, -4, 4)).ok());
  CostToGoField f;
  EXPECT_TRUE(f.Update(*t, {3.0, 0.0}));
  EXPECT_FALSE(f.Update(*t, {3.0, 0.0}));  // nothing changed: no new search
  EXPECT_EQ(f.searches(), 1);
  EXPECT_NEAR(f.Cost({0.0, 0.0}), 3.0, 0.25);
  // 8-connected metric: within 8 % of Euclidean on the diagonal-ish.
  EXPECT_NEAR(f.Cost({0.0, 2.0}), std::hypot(3.0, 2.0), 0.3);
  EXPECT_DOUBLE_EQ(f.Factor({0.0, 0.0}), 1.0);
  // Unknown ground is priced, not forbidden.
  EXPECT_TRUE(std::isfinite(f.Cost({-6.0, 0.0})));
  EXPECT_DOUBLE_EQ(f.Factor({-6.0, 0.0}), TestOptions().unknown_cost_factor);
}

TEST(CostToGoField, TallRocksBlockAndTheWayGoesAround) {
  auto t = HeightTerrain::Create(TestOptions());
  ASSERT_TRUE(t.ok());
  // A wall of 0.5 m rocks across x = 1.5 from y = -2 to 2.
  std::vector<Block> wall;
  for (double y = -2.0; y <= 2.0; y += 0.2) wall.push_back({1.5, y, 0.1, 0.5});
  ASSERT_TRUE(t->Update(ScanOf(Blocks(wall), -4, 4, -4, 4)).ok());
  CostToGoField f;
  f.Update(*t, {3.0, 0.0});
  EXPECT_TRUE(std::isinf(f.Cost({1.5, 0.0})));
  EXPECT_TRUE(std::isinf(f.Factor({1.5, 0.0})));
  const double around = f.Cost({0.0, 0.0});
  EXPECT_GT(around, 3.0 + 2.0);  // at least around the end of the wall
  EXPECT_TRUE(std::isfinite(around));
}

TEST(CostToGoField, ARockOnTheGoalPointLeavesTheRestOfItsToleranceOpen) {
  auto t = HeightTerrain::Create(TestOptions());
  ASSERT_TRUE(t.ok());
  // A 0.5 m rock 0.3 m across on the goal point (3, 0).
  ASSERT_TRUE(t->Update(ScanOf(Blocks({{3.0, 0.0, 0.15, 0.5}}), -4, 4, -4, 4)).ok());
  CostToGoField point;
  point.Update(*t, {3.0, 0.0});
  CostToGoField region;
  region.Update(*t, {3.0, 0.0}, 1.5);  // the rover fits no nearer the rock than about 1 m
  EXPECT_TRUE(std::isinf(region.Cost({3.0, 0.0})));  // the rock itself stays blocked
  // With a tolerance the open ground about the rock is the goal; without, the goal is cut off
  // and the field leads to the map's border instead.
  EXPECT_GT(region.Cost({0.0, 0.0}), 3.0 - 1.5 - 0.1);
  EXPECT_LT(region.Cost({0.0, 0.0}), 3.0);
  EXPECT_GT(point.Cost({0.0, 0.0}), 3.0 + 2.0);
  EXPECT_TRUE(region.Update(*t, {3.0, 0.0}, 0.5));  // a new tolerance: a new search
}

TEST(CostToGoField, GoalOffTheMapSeedsTheBorder) {
  auto t = HeightTerrain::Create(TestOptions());
  ASSERT_TRUE(t.ok());
  ASSERT_TRUE(t->Update(ScanOf(Blocks({}), -4, 4, -4, 4)).ok());
  CostToGoField f;
  f.Update(*t, {30.0, 0.0});
  EXPECT_LT(f.Cost({2.0, 0.0}), f.Cost({0.0, 0.0}));
  EXPECT_GT(f.Cost({0.0, 0.0}), 30.0 - 0.5);
}

}  // namespace
}  // namespace rover::apl::enav
