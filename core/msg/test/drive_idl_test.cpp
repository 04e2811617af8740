#include "rover/msg/drive_idl.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <string>

#include "rover/idl/access.hpp"

namespace rover::msg {
namespace {

TEST(DriveIdl, CommandRoundTripKeepsAnUnknownPrimitiveAndNaN) {
  DriveCommand c;
  c.stamp = Time{11};
  c.command_id = 31;
  c.primitive = DrivePrimitive::kArc;
  c.curvature = 0.5;
  c.distance = -2.0;
  c.angle = 0.1;
  c.speed = 0.04;
  c.timeout_s = 60.0;
  rover_dl_DriveCommand w{};
  DriveCommandToIdl(c, &w);
  EXPECT_EQ(w.header.stamp_ns, 11);
  EXPECT_EQ(w.primitive, rover_dl_PRIMITIVE_ARC);
  EXPECT_EQ(w.distance, -2.0);
  const DriveCommand back = DriveCommandFromIdl(w);
  EXPECT_EQ(back.stamp, c.stamp);
  EXPECT_EQ(back.command_id, 31u);
  EXPECT_EQ(back.primitive, DrivePrimitive::kArc);
  EXPECT_EQ(back.curvature, 0.5);
  EXPECT_EQ(back.distance, -2.0);
  EXPECT_EQ(back.angle, 0.1);
  EXPECT_EQ(back.speed, 0.04);
  EXPECT_EQ(back.timeout_s, 60.0);
  // A value outside the IDL enum (another vendor's writer might send it) reaches locomotion.
  idl::SetRawEnum(&w.primitive, 42);
  w.speed = std::numeric_limits<double>::quiet_NaN();
  const DriveCommand odd = DriveCommandFromIdl(w);
  EXPECT_EQ(static_cast<int>(odd.primitive), 42);
  EXPECT_FALSE(IsKnownPrimitive(odd.primitive));
  EXPECT_TRUE(std::isnan(odd.speed));
}

TEST(DriveIdl, StatusRoundTripAndAWireSafePrimitive) {
  DriveStatus s;
  s.stamp = Time{77};
  s.command_id = 5;
  s.primitive = DrivePrimitive::kTurnInPlace;
  s.state = DriveState::kFailed;
  s.termination = DriveTermination::kMotorStall;
  s.distance_done = 1.25;
  s.heading_change = -0.5;
  s.message = std::string(300, 'm');
  rover_dl_DriveStatus w{};
  DriveStatusToIdl(s, &w);
  EXPECT_EQ(w.header.stamp_ns, 77);
  EXPECT_EQ(w.state, rover_dl_DRIVE_FAILED);
  EXPECT_EQ(w.termination, rover_dl_TERMINATION_MOTOR_STALL);
  EXPECT_EQ(std::strlen(w.message), 127u);
  auto back = DriveStatusFromIdl(w);
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_EQ(back->stamp, s.stamp);
  EXPECT_EQ(back->command_id, 5u);
  EXPECT_EQ(back->primitive, DrivePrimitive::kTurnInPlace);
  EXPECT_EQ(back->state, DriveState::kFailed);
  EXPECT_EQ(back->termination, DriveTermination::kMotorStall);
  EXPECT_EQ(back->distance_done, 1.25);
  EXPECT_EQ(back->heading_change, -0.5);
  EXPECT_EQ(back->message, std::string(127, 'm'));

  // An unknown primitive (only possible in a rejection) goes out as STOP.
  s.primitive = static_cast<DrivePrimitive>(42);
  s.state = DriveState::kRejected;
  s.termination = DriveTermination::kRejectedInvalid;
  DriveStatusToIdl(s, &w);
  EXPECT_EQ(w.primitive, rover_dl_PRIMITIVE_STOP);
  idl::SetRawEnum(&w.termination, 12);
  auto bad = DriveStatusFromIdl(w);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(),
            "dl/drive_status termination = 12 is not a DriveTermination (0..11)");
}

}  // namespace
}  // namespace rover::msg

namespace rover::msg {
namespace {

TEST(DriveIdl, PrimitiveToIdlMapsEveryKnownPrimitiveAndAnUnknownOneToStop) {
  EXPECT_EQ(DrivePrimitiveToIdl(DrivePrimitive::kStop), rover_dl_PRIMITIVE_STOP);
  EXPECT_EQ(DrivePrimitiveToIdl(DrivePrimitive::kArc), rover_dl_PRIMITIVE_ARC);
  EXPECT_EQ(DrivePrimitiveToIdl(DrivePrimitive::kStraight), rover_dl_PRIMITIVE_STRAIGHT);
  EXPECT_EQ(DrivePrimitiveToIdl(DrivePrimitive::kTurnInPlace), rover_dl_PRIMITIVE_TURN_IN_PLACE);
  EXPECT_EQ(DrivePrimitiveToIdl(DrivePrimitive::kSteer), rover_dl_PRIMITIVE_STEER);
  EXPECT_EQ(DrivePrimitiveToIdl(static_cast<DrivePrimitive>(9)), rover_dl_PRIMITIVE_STOP);
}

}  // namespace
}  // namespace rover::msg
