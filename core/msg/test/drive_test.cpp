#include "rover/msg/drive.hpp"

#include <gtest/gtest.h>

namespace rover::msg {
namespace {

// The enumerators keep the IDL ordinals (idl/rover_dl.idl).
static_assert(static_cast<int>(DrivePrimitive::kSteer) == 4);
static_assert(static_cast<int>(DriveState::kRejected) == 6);
static_assert(static_cast<int>(DriveTermination::kStaleSensor) == 11);

TEST(DriveMessages, NamesMatchTheIdl) {
  EXPECT_STREQ(DrivePrimitiveName(DrivePrimitive::kTurnInPlace), "TURN_IN_PLACE");
  EXPECT_STREQ(DriveStateName(DriveState::kSteering), "STEERING");
  EXPECT_STREQ(DriveTerminationName(DriveTermination::kRejectedBusy), "REJECTED_BUSY");
  EXPECT_STREQ(DriveTerminationName(DriveTermination::kStaleSensor), "STALE_SENSOR");
  EXPECT_STREQ(DrivePrimitiveName(static_cast<DrivePrimitive>(42)), "UNKNOWN");
  EXPECT_STREQ(DriveTerminationName(static_cast<DriveTermination>(-1)), "UNKNOWN");
}

TEST(DriveMessages, KnownPrimitives) {
  for (int p = 0; p <= 4; ++p) EXPECT_TRUE(IsKnownPrimitive(static_cast<DrivePrimitive>(p)));
  EXPECT_FALSE(IsKnownPrimitive(static_cast<DrivePrimitive>(5)));
  EXPECT_FALSE(IsKnownPrimitive(static_cast<DrivePrimitive>(-1)));
}

}  // namespace
}  // namespace rover::msg
