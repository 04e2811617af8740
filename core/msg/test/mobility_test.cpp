#include "rover/msg/mobility.hpp"

#include <gtest/gtest.h>

namespace rover::msg {
namespace {

using F = MobilityFault;

TEST(MobilityMsg, FaultClassesFollowMerTable1) {
  EXPECT_EQ(FaultClassOf(F::kNone), FaultClass::kNone);
  for (F f : {F::kArb, F::kAcm, F::kPot, F::kTod, F::kStopped, F::kWaypointTimeout, F::kNoPath,
              F::kNoProgress, F::kBusy, F::kVisOdom, F::kKeepOut, F::kBadCommand, F::kRestart}) {
    EXPECT_EQ(FaultClassOf(f), FaultClass::kGoalError) << MobilityFaultName(f);
  }
  for (F f : {F::kImg, F::kSapp, F::kMot, F::kDriveTimeout, F::kTilt, F::kSuspension, F::kNorth}) {
    EXPECT_EQ(FaultClassOf(f), FaultClass::kMotionError) << MobilityFaultName(f);
  }
  EXPECT_EQ(FaultClassOf(static_cast<F>(99)), FaultClass::kNone);
  EXPECT_EQ(FaultClassOf(static_cast<F>(-3)), FaultClass::kNone);
}

TEST(MobilityMsg, NamesAsMer) {
  EXPECT_EQ(MobilityFaultName(F::kWaypointTimeout), "WAYPT_TIMEOUT");
  EXPECT_EQ(MobilityFaultName(F::kNone), "NONE");
  EXPECT_EQ(MobilityFaultName(F::kNorth), "NORTH");
  EXPECT_EQ(MobilityFaultName(F::kRestart), "RESTART");
  EXPECT_EQ(MobilityFaultName(static_cast<F>(-1)), "UNKNOWN");
  EXPECT_EQ(MobilityFaultName(static_cast<F>(kMobilityFaultCount)), "UNKNOWN");
  EXPECT_EQ(MobilityModeName(MobilityMode::kDirected), "DIRECTED");
  EXPECT_EQ(MobilityModeName(MobilityMode::kGuardedArc), "GUARDED_ARC");
  EXPECT_EQ(MobilityModeName(MobilityMode::kClearFault), "CLEAR_FAULT");
  EXPECT_EQ(MobilityModeName(static_cast<MobilityMode>(17)), "mode 17");
  EXPECT_STREQ(MobilityStateName(MobilityState::kIdle), "IDLE");
  EXPECT_STREQ(MobilityStateName(MobilityState::kSucceeded), "SUCCEEDED");
  EXPECT_STREQ(MobilityStateName(MobilityState::kRejected), "REJECTED");
  EXPECT_STREQ(MobilityStateName(static_cast<MobilityState>(5)), "UNKNOWN");
  EXPECT_STREQ(FaultClassName(FaultClass::kNone), "NONE");
  EXPECT_STREQ(FaultClassName(FaultClass::kGoalError), "GOAL_ERROR");
  EXPECT_STREQ(FaultClassName(FaultClass::kMotionError), "MOTION_ERROR");
  EXPECT_STREQ(FaultClassName(static_cast<FaultClass>(3)), "UNKNOWN");
}

}  // namespace
}  // namespace rover::msg
