#include "motor_idl.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "rover/ddl/motor/motor_group_manager.hpp"

namespace rover::ddl {
namespace {

TEST(MotorIdl, CommandFieldsAndAnUnknownModeSurvive) {
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
  EXPECT_EQ(c.stamp_ns, 123);
  EXPECT_EQ(c.command_id, 9u);
  EXPECT_EQ(c.motor_mask, 0x0801);
  EXPECT_EQ(c.mode, GroupMode::kVelocity);
  EXPECT_EQ(c.goal[0], 0.25);
  EXPECT_TRUE(std::isnan(c.goal[11]));
  EXPECT_EQ(c.max_rate[11], 0.5);
  EXPECT_EQ(c.timeout_s, 3.0);
  // A value no GroupMode has (as a corrupt sample could carry) is kept for the library to reject.
  const std::int32_t seven = 7;
  std::memcpy(&in.mode, &seven, sizeof seven);
  c = MotorCommandFromIdl(in);
  EXPECT_EQ(static_cast<int>(c.mode), 7);
  auto manager = MotorGroupManager::Create(HardwareConfig());
  ASSERT_TRUE(manager.ok());
  std::string msg;
  EXPECT_EQ(manager->Check(c, &msg, nullptr), CommandError::kUnknownMode);
}

TEST(MotorIdl, TelemetryGoalsAndStatus) {
  rover_hw_MotorTelemetry t{};
  t.header.stamp_ns = 55;
  t.command_id = 4;
  t.motors[3] = {-2147483647, -20, 300, 2400, rover_hw_kMotorFlagStall};
  const hw::MotorTelemetry ht = MotorTelemetryFromIdl(t);
  EXPECT_EQ(ht.stamp_ns, 55);
  EXPECT_EQ(ht.command_id, 4u);
  EXPECT_EQ(ht.motors[3].position, -2147483647);
  EXPECT_EQ(ht.motors[3].velocity, -20);
  EXPECT_EQ(ht.motors[3].current_adc, 300);
  EXPECT_EQ(ht.motors[3].temperature_adc, 2400);
  EXPECT_EQ(ht.motors[3].flags, hw::kMotorFlagStall);

  hw::MotorGoals g;
  g.command_id = 17;
  g.goals[5] = {hw::MotorMode::kPosition, -500, 800, 1300};
  g.goals[11] = {hw::MotorMode::kBrake, 0, 0, 0};
  rover_hw_MotorGoals out{};
  MotorGoalsToIdl(g, &out);
  EXPECT_EQ(out.command_id, 17u);
  EXPECT_EQ(out.goals[5].mode, rover_hw_MOTOR_POSITION);
  EXPECT_EQ(out.goals[5].position, -500);
  EXPECT_EQ(out.goals[5].velocity, 800);
  EXPECT_EQ(out.goals[5].current_limit_ma, 1300);
  EXPECT_EQ(out.goals[11].mode, rover_hw_MOTOR_BRAKE);
  EXPECT_EQ(out.goals[0].mode, rover_hw_MOTOR_IDLE);

  MotorStatus s;
  s.command_id = 3;
  s.state = GroupState::kFault;
  s.fault = MotorFault::kOverTemp;
  s.fault_motor = 10;
  s.message = std::string(200, 'x');
  s.position[10] = 1.5;
  s.temperature[2] = 40.0;
  rover_ddl_MotorStatus m{};
  MotorStatusToIdl(s, &m);
  EXPECT_EQ(m.state, rover_ddl_GROUP_FAULT);
  EXPECT_EQ(m.fault, rover_ddl_MOTOR_FAULT_OVERTEMP);
  EXPECT_EQ(m.fault_motor, 10);
  EXPECT_EQ(std::strlen(m.message), 127u);  // truncated to string<127>
  EXPECT_EQ(m.position[10], 1.5);
  EXPECT_EQ(m.temperature[2], 40.0);
  EXPECT_EQ(HealthToIdl(SensorHealth::kStale), rover_HEALTH_STALE);
}

}  // namespace
}  // namespace rover::ddl
