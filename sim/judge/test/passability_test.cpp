#include "rover/sim/judge/passability.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::sim::judge {
namespace {

// A field from x = -2 to 8, y = -6 to 6; the rover at the origin facing north (+x), the goal
// 5 m ahead.
PassabilityQuery Query() {
  PassabilityQuery q;
  q.start = {0.0, 0.0};
  q.goal = {5.0, 0.0};
  q.tolerance = 0.3;
  q.area_min = {-2.0, -6.0};
  q.area_max = {8.0, 6.0};
  return q;
}

// A wall of rocks across the field at x = 2.5, every 0.25 m, leaving out |y| < gap / 2.
std::vector<JudgeRock> Wall(double gap, double height = 0.4, double diameter = 0.3) {
  std::vector<JudgeRock> rocks;
  int id = 0;
  for (double y = -6.0; y <= 6.0; y += 0.25) {
    if (std::abs(y) < gap / 2.0) continue;
    rocks.push_back({id++, {2.5, y}, diameter, height, {}});
  }
  return rocks;
}

TEST(Passability, AnOpenFieldIsCrossedStraight) {
  const auto len = ContactFreePathLength({}, RoverFootprint::MerDefault(), Query());
  ASSERT_TRUE(len.ok()) << len.status().message();
  ASSERT_TRUE(len->has_value());
  EXPECT_GT(**len, 4.6);
  EXPECT_LT(**len, 5.0);
}

TEST(Passability, AClosedWallHasNoContactFreePath) {
  const auto len = ContactFreePathLength(Wall(0.0), RoverFootprint::MerDefault(), Query());
  ASSERT_TRUE(len.ok());
  EXPECT_FALSE(len->has_value());
}

TEST(Passability, AGapTheRoverFitsThroughIsUsedAndTheMarginCanCloseIt) {
  // The rover is 1.16 m wide over its wheels: a 1.75 m opening less the two rocks' radii leaves
  // 1.45 m, 0.14 m a side.
  const auto fp = RoverFootprint::MerDefault();
  auto len = ContactFreePathLength(Wall(1.75), fp, Query());
  ASSERT_TRUE(len.ok());
  ASSERT_TRUE(len->has_value());
  EXPECT_LT(**len, 5.3);  // straight through the gap on the way
  PassabilityQuery q = Query();
  q.margin = 0.2;
  len = ContactFreePathLength(Wall(1.75), fp, q);
  ASSERT_TRUE(len.ok());
  EXPECT_FALSE(len->has_value());
}

TEST(Passability, LowRocksUnderTheBellyAreStraddledButNotUnderTheRectangle) {
  // One 0.25 m rock (taller than the traversable height, lower than the belly's 0.35 m less the
  // 0.05 m margin) straight ahead between the wheels.
  const std::vector<JudgeRock> rocks = {{1, {2.5, 0.0}, 0.3, 0.25, {}}};
  const auto fp = RoverFootprint::MerDefault();
  const auto parts = ContactFreePathLength(rocks, fp, Query());
  ASSERT_TRUE(parts.ok() && parts->has_value());
  PassabilityQuery q = Query();
  q.rectangle = true;
  const auto rect = ContactFreePathLength(rocks, fp, q);
  ASSERT_TRUE(rect.ok() && rect->has_value());
  EXPECT_LT(**parts, 5.0);
  EXPECT_GT(**rect, **parts + 0.1);  // around the rock
  // Rocks at or below the traversable height never block.
  q.traversable_height = 0.25;
  const auto low = ContactFreePathLength(rocks, fp, q);
  ASSERT_TRUE(low.ok() && low->has_value());
  EXPECT_NEAR(**low, **parts, 1e-6);
}

TEST(Passability, AStartOnARockOrOutsideTheAreaHasNoPath) {
  const auto fp = RoverFootprint::MerDefault();
  const std::vector<JudgeRock> rocks = {{1, {0.0, 0.5}, 0.4, 0.5, {}}};  // under the left wheels
  auto len = ContactFreePathLength(rocks, fp, Query());
  ASSERT_TRUE(len.ok());
  EXPECT_FALSE(len->has_value());
  PassabilityQuery q = Query();
  q.start = {-5.0, 0.0};
  len = ContactFreePathLength({}, fp, q);
  ASSERT_TRUE(len.ok());
  EXPECT_FALSE(len->has_value());
}

TEST(Passability, BadQueriesNameTheField) {
  const auto fp = RoverFootprint::MerDefault();
  PassabilityQuery q = Query();
  q.tolerance = -1.0;
  auto len = ContactFreePathLength({}, fp, q);
  ASSERT_FALSE(len.ok());
  EXPECT_NE(len.status().message().find("passability.tolerance"), std::string::npos);
  q = Query();
  q.goal = {NAN, 0.0};
  len = ContactFreePathLength({}, fp, q);
  ASSERT_FALSE(len.ok());
  EXPECT_NE(len.status().message().find("passability.goal"), std::string::npos);
  q = Query();
  q.area_max = {1000.0, 1000.0};
  q.cell = 0.02;
  len = ContactFreePathLength({}, fp, q);
  ASSERT_FALSE(len.ok());
  EXPECT_NE(len.status().message().find("lattice states"), std::string::npos);
}

}  // namespace
}  // namespace rover::sim::judge
