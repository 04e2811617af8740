#include "rover/msg/motor.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rover::msg {
namespace {

TEST(MotorMessages, NamesAreTheIdlEnumerators) {
  EXPECT_EQ(std::string(GroupModeName(GroupMode::kVelocity)), "VELOCITY");
  EXPECT_EQ(std::string(GroupStateName(GroupState::kRejected)), "REJECTED");
  EXPECT_EQ(std::string(MotorFaultName(MotorFault::kNoTelemetry)), "NO_TELEMETRY");
  EXPECT_EQ(std::string(MotorFaultName(MotorFault::kOverCurrent)), "OVERCURRENT");
  EXPECT_EQ(std::string(GroupModeName(static_cast<GroupMode>(9))), "UNKNOWN");
  // The IDL enum order.
  EXPECT_EQ(static_cast<int>(MotorFault::kStopped), 7);
  EXPECT_EQ(static_cast<int>(GroupState::kRejected), 4);
  EXPECT_EQ(static_cast<int>(GroupMode::kStop), 2);
}

TEST(MotorMessages, KnownModes) {
  for (int m = 0; m <= 2; ++m) EXPECT_TRUE(IsKnownGroupMode(static_cast<GroupMode>(m)));
  EXPECT_FALSE(IsKnownGroupMode(static_cast<GroupMode>(3)));
  EXPECT_FALSE(IsKnownGroupMode(static_cast<GroupMode>(-1)));
}

}  // namespace
}  // namespace rover::msg
