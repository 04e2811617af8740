#include "rover/msg/motor_idl.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "rover/idl/access.hpp"

namespace rover::msg {
namespace {

TEST(MotorIdl, CommandRoundTripAndAnUnknownModeSurvives) {
  rover_ddl_MotorCommand in{};
  in.header.stamp_ns = 123;
  in.command_id = 9;
  in.motor_mask = 0x0801;
  in.mode = rover_ddl_GROUP_VELOCITY;
  in.goal[0] = 0.25;
  in.goal[11] = std::nan("");
  in.max_rate[11] = 0.5;
  in.timeout_s = 3.0;
  MotorCommand c = MotorCommandFromIdl(in);
  EXPECT_EQ(c.stamp.ns, 123);
  EXPECT_EQ(c.command_id, 9u);
  EXPECT_EQ(c.motor_mask, 0x0801);
  EXPECT_EQ(c.mode, GroupMode::kVelocity);
  EXPECT_EQ(c.goal[0], 0.25);
  EXPECT_TRUE(std::isnan(c.goal[11]));
  EXPECT_EQ(c.max_rate[11], 0.5);
  EXPECT_EQ(c.timeout_s, 3.0);
  rover_ddl_MotorCommand back{};
  MotorCommandToIdl(c, &back);
  EXPECT_EQ(back.header.stamp_ns, 123);
  EXPECT_EQ(back.command_id, 9u);
  EXPECT_EQ(back.motor_mask, 0x0801);
  EXPECT_EQ(back.mode, rover_ddl_GROUP_VELOCITY);
  EXPECT_EQ(back.goal[0], 0.25);
  EXPECT_TRUE(std::isnan(back.goal[11]));
  EXPECT_EQ(back.max_rate[11], 0.5);
  EXPECT_EQ(back.timeout_s, 3.0);
  // A value no GroupMode has (as a corrupt sample could carry) is kept for the driver to reject.
  idl::SetRawEnum(&in.mode, 7);
  c = MotorCommandFromIdl(in);
  EXPECT_EQ(static_cast<int>(c.mode), 7);
  EXPECT_FALSE(IsKnownGroupMode(c.mode));
}

TEST(MotorIdl, StatusRoundTripTruncatesTheMessage) {
  MotorStatus s;
  s.stamp = Time{77};
  s.command_id = 3;
  s.state = GroupState::kFault;
  s.fault = MotorFault::kOverTemp;
  s.fault_motor = 10;
  s.message = std::string(200, 'x');
  s.position[10] = 1.5;
  s.velocity[1] = -0.25;
  s.current[4] = 2.0;
  s.temperature[2] = 40.0;
  rover_ddl_MotorStatus m{};
  MotorStatusToIdl(s, &m);
  EXPECT_EQ(m.header.stamp_ns, 77);
  EXPECT_EQ(m.state, rover_ddl_GROUP_FAULT);
  EXPECT_EQ(m.fault, rover_ddl_MOTOR_FAULT_OVERTEMP);
  EXPECT_EQ(m.fault_motor, 10);
  EXPECT_EQ(std::strlen(m.message), 127u);  // truncated to string<127>
  EXPECT_EQ(m.position[10], 1.5);
  EXPECT_EQ(m.temperature[2], 40.0);
  auto back = MotorStatusFromIdl(m);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->stamp, s.stamp);
  EXPECT_EQ(back->command_id, 3u);
  EXPECT_EQ(back->state, GroupState::kFault);
  EXPECT_EQ(back->fault, MotorFault::kOverTemp);
  EXPECT_EQ(back->fault_motor, 10);
  EXPECT_EQ(back->message, std::string(127, 'x'));
  EXPECT_EQ(back->position, s.position);
  EXPECT_EQ(back->velocity, s.velocity);
  EXPECT_EQ(back->current, s.current);
  EXPECT_EQ(back->temperature, s.temperature);
  idl::SetRawEnum(&m.fault, 8);
  auto bad = MotorStatusFromIdl(m);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "ddl/motor_status fault = 8 is not a MotorFault (0..7)");
  m.fault = rover_ddl_MOTOR_FAULT_NONE;
  idl::SetRawEnum(&m.state, -3);
  EXPECT_FALSE(MotorStatusFromIdl(m).ok());
}

}  // namespace
}  // namespace rover::msg
