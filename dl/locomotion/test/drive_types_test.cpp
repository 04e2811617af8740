#include "rover/dl/locomotion/drive_types.hpp"

#include <gtest/gtest.h>

namespace rover::dl::locomotion {
namespace {

// The message enums' ordinals and names are core/msg's (core/msg/test/drive_test.cpp,
// motor_test.cpp); these are the library's own.
static_assert(kMobilityMotorMask == 0x3FF);
static_assert(SteerMotor(3) == 9);
static_assert(kSteeredWheel[1] == 2);

TEST(DriveTypes, InvalidReasonNames) {
  EXPECT_STREQ(InvalidReasonName(InvalidReason::kCurvatureOutOfRange), "curvature_out_of_range");
  EXPECT_STREQ(InvalidReasonName(InvalidReason::kNone), "none");
  EXPECT_STREQ(InvalidReasonName(static_cast<InvalidReason>(99)), "unknown");
}

TEST(DriveTypes, StatusCarriesTheMessageAndTheTypedReason) {
  DriveStatus s;
  s.command_id = 7;
  s.state = DriveState::kRejected;
  s.invalid_reason = InvalidReason::kSpeedOutOfRange;
  const msg::DriveStatus& wire = s;  // what goes on dl/drive_status
  EXPECT_EQ(wire.command_id, 7u);
  EXPECT_EQ(wire.state, DriveState::kRejected);
}

}  // namespace
}  // namespace rover::dl::locomotion
