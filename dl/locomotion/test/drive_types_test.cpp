#include "rover/dl/locomotion/drive_types.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace rover::dl {
namespace {

// The enumerators must keep the IDL ordinals (idl/rover_dl.idl, idl/rover_ddl.idl) so that the
// services can static_cast between the wire and the library.
static_assert(static_cast<int>(DrivePrimitive::kSteer) == 4);
static_assert(static_cast<int>(DriveState::kRejected) == 6);
static_assert(static_cast<int>(DriveTermination::kStaleSensor) == 11);
static_assert(static_cast<int>(GroupMode::kStop) == 2);
static_assert(static_cast<int>(GroupState::kRejected) == 4);
static_assert(static_cast<int>(MotorFault::kStopped) == 7);
static_assert(kMobilityMotorMask == 0x3FF);
static_assert(SteerMotor(3) == 9);

TEST(DriveTypes, NamesMatchTheIdl) {
  EXPECT_STREQ(DrivePrimitiveName(DrivePrimitive::kTurnInPlace), "TURN_IN_PLACE");
  EXPECT_STREQ(DriveStateName(DriveState::kSteering), "STEERING");
  EXPECT_STREQ(DriveTerminationName(DriveTermination::kRejectedBusy), "REJECTED_BUSY");
  EXPECT_STREQ(DriveTerminationName(DriveTermination::kStaleSensor), "STALE_SENSOR");
  EXPECT_STREQ(MotorFaultName(MotorFault::kOverCurrent), "OVERCURRENT");
  EXPECT_STREQ(InvalidReasonName(InvalidReason::kCurvatureOutOfRange), "curvature_out_of_range");
  EXPECT_STREQ(DrivePrimitiveName(static_cast<DrivePrimitive>(42)), "UNKNOWN");
  EXPECT_STREQ(DriveTerminationName(static_cast<DriveTermination>(-1)), "UNKNOWN");
}

TEST(DriveTypes, KnownPrimitives) {
  for (int p = 0; p <= 4; ++p) EXPECT_TRUE(IsKnownPrimitive(static_cast<DrivePrimitive>(p)));
  EXPECT_FALSE(IsKnownPrimitive(static_cast<DrivePrimitive>(5)));
  EXPECT_FALSE(IsKnownPrimitive(static_cast<DrivePrimitive>(-1)));
}

TEST(DriveTypes, JointSampleFiniteness) {
  JointSample s;
  EXPECT_TRUE(s.AllFinite());
  s.bogie_angle[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(s.AllFinite());
  s.bogie_angle[1] = 0.0;
  s.wheel_rate[5] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(s.AllFinite());
}

}  // namespace
}  // namespace rover::dl
