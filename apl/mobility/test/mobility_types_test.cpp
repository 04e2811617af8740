#include "rover/apl/mobility/mobility_types.hpp"

#include <gtest/gtest.h>

namespace rover::apl::mobility {
namespace {

// The names, classes and conversions of the message types are core/msg's (core/msg/test).

TEST(MobilityTypes, ModeGroups) {
  EXPECT_TRUE(ModeHasGoal(Mode::kAutoNav));
  EXPECT_TRUE(ModeHasGoal(Mode::kLongTraverse));
  EXPECT_TRUE(ModeHasGoal(Mode::kVisOdomGoToWaypoint));
  EXPECT_FALSE(ModeHasGoal(Mode::kGuarded));
  EXPECT_FALSE(ModeHasGoal(Mode::kStop));
  EXPECT_TRUE(ModeHasPrimitives(Mode::kGuardedArc));
  EXPECT_TRUE(ModeHasPrimitives(Mode::kDirected));
  EXPECT_FALSE(ModeHasPrimitives(Mode::kStop));
  EXPECT_FALSE(ModeHasPrimitives(Mode::kAutoNav));
  EXPECT_TRUE(ModeUsesVisOdom(Mode::kAutoNavVisOdom));
  EXPECT_TRUE(ModeUsesVisOdom(Mode::kGuardedVisOdom));
  EXPECT_FALSE(ModeUsesVisOdom(Mode::kAutoNav));
  EXPECT_FALSE(ModeHasGoal(static_cast<Mode>(kModeCount)));
}

}  // namespace
}  // namespace rover::apl::mobility
