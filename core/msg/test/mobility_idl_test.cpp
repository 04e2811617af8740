#include "rover/msg/mobility_idl.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "rover/idl/access.hpp"

namespace rover::msg {
namespace {

MobilityCommand FullCommand() {
  MobilityCommand c;
  c.stamp = Time{123};
  c.command_id = 42;
  c.mode = MobilityMode::kGuardedArc;
  c.goal = {1.5, -2.5, 0.25};
  c.tolerance = 0.3;
  c.time_budget_s = 600;
  c.primitives = {{DrivePrimitive::kTurnInPlace, 0.0, 0.0, 1.0},
                  {DrivePrimitive::kArc, 0.5, 2.0, 0.0}};
  c.keep_out = {{"crater", {{0, 0}, {1, 0}, {1, 1}}}, {"dune", {{5, 5}, {6, 5}, {6, 6}, {5, 6}}}};
  c.think = ThinkMode::kStopAndGo;
  c.max_tilt = 0.3;
  c.min_northerly_tilt = 0.05;
  c.lmst_end_h = 15.5;
  c.max_steps = 77;
  return c;
}

TEST(MobilityIdl, CommandRoundTripThroughACopiedHolder) {
  const MobilityCommand c = FullCommand();
  MobilityCommandMessage m;
  MobilityCommandToIdl(c, &m);
  EXPECT_EQ(m.msg.mode, rover_apl_MOBILITY_GUARDED_ARC);
  EXPECT_EQ(m.msg.primitives._length, 2u);
  EXPECT_EQ(m.msg.keep_out._length, 2u);
  const MobilityCommandMessage copy = m;  // re-pointed at its own storage
  m = MobilityCommandMessage{};           // the original's storage is gone
  const MobilityCommand b = MobilityCommandFromIdl(copy.msg);
  EXPECT_EQ(b.stamp.ns, 123);
  EXPECT_EQ(b.command_id, 42u);
  EXPECT_EQ(b.mode, MobilityMode::kGuardedArc);
  EXPECT_EQ(b.goal, c.goal);
  EXPECT_EQ(b.tolerance, 0.3);
  EXPECT_EQ(b.time_budget_s, 600);
  ASSERT_EQ(b.primitives.size(), 2u);
  EXPECT_EQ(b.primitives[0].kind, DrivePrimitive::kTurnInPlace);
  EXPECT_EQ(b.primitives[0].angle, 1.0);
  EXPECT_EQ(b.primitives[1].kind, DrivePrimitive::kArc);
  EXPECT_EQ(b.primitives[1].curvature, 0.5);
  EXPECT_EQ(b.primitives[1].distance, 2.0);
  ASSERT_EQ(b.keep_out.size(), 2u);
  EXPECT_EQ(b.keep_out[0].name, "crater");
  EXPECT_EQ(b.keep_out[1].name, "dune");
  EXPECT_EQ(b.keep_out[0].vertices, c.keep_out[0].vertices);
  EXPECT_EQ(b.keep_out[1].vertices, c.keep_out[1].vertices);
  EXPECT_EQ(b.think, ThinkMode::kStopAndGo);
  EXPECT_EQ(b.max_tilt, 0.3);
  EXPECT_EQ(b.min_northerly_tilt, 0.05);
  EXPECT_EQ(b.lmst_end_h, 15.5);
  EXPECT_EQ(b.max_steps, 77);
}

TEST(MobilityIdl, CommandLimitsOfTheWire) {
  MobilityCommand c = FullCommand();
  c.max_steps = 1 << 20;
  c.keep_out[0].name = std::string(40, 'z');
  MobilityCommandMessage m;
  MobilityCommandToIdl(c, &m);
  EXPECT_EQ(m.msg.max_steps, 65535);
  EXPECT_EQ(std::strlen(m.zones[0].name), 31u);
  c.max_steps = -4;
  MobilityCommandToIdl(c, &m);  // refilling a holder replaces what it held
  EXPECT_EQ(m.msg.max_steps, 0);
  EXPECT_EQ(m.msg.keep_out._length, 2u);
  EXPECT_EQ(MobilityCommandFromIdl(m.msg).keep_out[1].vertices.size(), 4u);
}

TEST(MobilityIdl, UnknownCommandEnumsSurviveForTheManagerToReject) {
  MobilityCommand c = FullCommand();
  c.mode = static_cast<MobilityMode>(42);
  c.think = static_cast<ThinkMode>(7);
  c.primitives[1].kind = static_cast<DrivePrimitive>(9);
  MobilityCommandMessage m;
  MobilityCommandToIdl(c, &m);
  EXPECT_EQ(idl::RawEnum(m.msg.mode), 42);
  const MobilityCommand b = MobilityCommandFromIdl(m.msg);
  EXPECT_EQ(static_cast<int>(b.mode), 42);
  EXPECT_EQ(static_cast<int>(b.think), 7);
  EXPECT_EQ(static_cast<int>(b.primitives[1].kind), 9);
}

TEST(MobilityIdl, StatusRoundTripTruncatesTheMessage) {
  MobilityStatus s;
  s.stamp = Time{5};
  s.command_id = 3;
  s.mode = MobilityMode::kAutoNav;
  s.state = MobilityState::kFailed;
  s.fault_class = FaultClass::kMotionError;
  s.fault = MobilityFault::kImg;
  s.message = "no range image";
  s.distance_to_goal = 2.5;
  s.distance_driven = 7.0;
  s.steps = 9;
  s.images = 4;
  s.motion_error_latched = true;
  rover_apl_MobilityStatus m{};
  MobilityStatusToIdl(s, &m);
  EXPECT_EQ(m.fault, rover_apl_MOBFAULT_IMG);
  EXPECT_EQ(m.state, rover_apl_MOBILITY_FAILED);
  const auto b = MobilityStatusFromIdl(m);
  ASSERT_TRUE(b.ok()) << b.status().message();
  EXPECT_EQ(b->stamp.ns, 5);
  EXPECT_EQ(b->command_id, 3u);
  EXPECT_EQ(b->mode, MobilityMode::kAutoNav);
  EXPECT_EQ(b->state, MobilityState::kFailed);
  EXPECT_EQ(b->fault, MobilityFault::kImg);
  EXPECT_EQ(b->fault_class, FaultClass::kMotionError);
  EXPECT_EQ(b->message, "no range image");
  EXPECT_EQ(b->distance_to_goal, 2.5);
  EXPECT_EQ(b->distance_driven, 7.0);
  EXPECT_EQ(b->steps, 9u);
  EXPECT_EQ(b->images, 4u);
  EXPECT_TRUE(b->motion_error_latched);
  s.message.assign(300, 'x');
  MobilityStatusToIdl(s, &m);
  EXPECT_EQ(MobilityStatusFromIdl(m)->message, std::string(127, 'x'));
}

TEST(MobilityIdl, StatusWithAnUnknownEnumIsRefusedNamingTheField) {
  rover_apl_MobilityStatus m{};
  idl::SetRawEnum(&m.mode, 12);
  auto b = MobilityStatusFromIdl(m);
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.status().message(), "apl/mobility_status mode = 12 is not a MobilityMode (0..11)");
  m = rover_apl_MobilityStatus{};
  idl::SetRawEnum(&m.state, -1);
  b = MobilityStatusFromIdl(m);
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.status().message(), "apl/mobility_status state = -1 is not a MobilityState (0..4)");
  m = rover_apl_MobilityStatus{};
  idl::SetRawEnum(&m.fault_class, 3);
  b = MobilityStatusFromIdl(m);
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.status().message(), "apl/mobility_status fault_class = 3 is not a FaultClass (0..2)");
  m = rover_apl_MobilityStatus{};
  idl::SetRawEnum(&m.fault, 21);
  b = MobilityStatusFromIdl(m);
  ASSERT_FALSE(b.ok());
  EXPECT_EQ(b.status().message(), "apl/mobility_status fault = 21 is not a MobilityFault (0..20)");
}

}  // namespace
}  // namespace rover::msg
