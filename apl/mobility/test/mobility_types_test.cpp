#include "rover/apl/mobility/mobility_types.hpp"

#include <gtest/gtest.h>

namespace rover::apl::mobility {
namespace {

TEST(MobilityTypes, FaultClassesFollowMerTable1) {
  EXPECT_EQ(FaultClassOf(Fault::kNone), FaultClass::kNone);
  for (Fault f : {Fault::kArb, Fault::kAcm, Fault::kPot, Fault::kTod, Fault::kStopped,
                  Fault::kWaypointTimeout, Fault::kNoPath, Fault::kNoProgress, Fault::kBusy,
                  Fault::kVisOdom, Fault::kKeepOut, Fault::kBadCommand}) {
    EXPECT_EQ(FaultClassOf(f), FaultClass::kGoalError) << FaultName(f);
  }
  for (Fault f : {Fault::kImg, Fault::kSapp, Fault::kMot, Fault::kDriveTimeout, Fault::kTilt,
                  Fault::kSuspension, Fault::kNorth}) {
    EXPECT_EQ(FaultClassOf(f), FaultClass::kMotionError) << FaultName(f);
  }
  EXPECT_EQ(FaultClassOf(static_cast<Fault>(99)), FaultClass::kNone);
}

TEST(MobilityTypes, NamesAsMer) {
  EXPECT_EQ(FaultName(Fault::kWaypointTimeout), "WAYPT_TIMEOUT");
  EXPECT_EQ(FaultName(Fault::kNorth), "NORTH");
  EXPECT_EQ(FaultName(static_cast<Fault>(-1)), "UNKNOWN");
  EXPECT_EQ(ModeName(Mode::kGuardedArc), "GUARDED_ARC");
  EXPECT_EQ(ModeName(Mode::kClearFault), "CLEAR_FAULT");
  EXPECT_EQ(ModeName(static_cast<Mode>(17)), "mode 17");
  EXPECT_EQ(CameraName(Camera::kRearHazcam), "rear_hazcam");
}

TEST(MobilityTypes, ModeGroups) {
  EXPECT_TRUE(ModeHasGoal(Mode::kAutoNav));
  EXPECT_TRUE(ModeHasGoal(Mode::kLongTraverse));
  EXPECT_FALSE(ModeHasGoal(Mode::kGuarded));
  EXPECT_TRUE(ModeHasPrimitives(Mode::kGuardedArc));
  EXPECT_FALSE(ModeHasPrimitives(Mode::kStop));
  EXPECT_TRUE(ModeUsesVisOdom(Mode::kAutoNavVisOdom));
  EXPECT_FALSE(ModeUsesVisOdom(Mode::kAutoNav));
}

}  // namespace
}  // namespace rover::apl::mobility
