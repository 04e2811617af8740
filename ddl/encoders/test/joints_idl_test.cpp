#include "joints_idl.hpp"

#include <gtest/gtest.h>

namespace rover::ddl {
namespace {

TEST(JointsIdl, InputsAndJointStateFieldByField) {
  rover_hw_MotorTelemetry t{};
  t.header.stamp_ns = 77;
  t.command_id = 5;
  t.motors[10] = {123456, -7, 20, 2048, rover_hw_kMotorFlagEnabled};
  const hw::MotorTelemetry ht = JointTelemetryFromIdl(t);
  EXPECT_EQ(ht.stamp_ns, 77);
  EXPECT_EQ(ht.motors[10].position, 123456);
  EXPECT_EQ(ht.motors[10].velocity, -7);
  EXPECT_EQ(ht.motors[10].flags, hw::kMotorFlagEnabled);

  rover_hw_SuspensionPots p{};
  p.header.stamp_ns = 88;
  p.adc[0] = 1;
  p.adc[3] = 4095;
  const hw::SuspensionPots hp = SuspensionPotsFromIdl(p);
  EXPECT_EQ(hp.stamp_ns, 88);
  EXPECT_EQ(hp.adc[0], 1);
  EXPECT_EQ(hp.adc[3], 4095);

  JointState js;
  for (int i = 0; i < 6; ++i) {
    js.wheel_angle[static_cast<std::size_t>(i)] = i;
    js.wheel_rate[static_cast<std::size_t>(i)] = -i;
  }
  js.steer_angle = {0.1, 0.2, 0.3, 0.4};
  js.rocker_angle = {0.05, -0.05};
  js.bogie_angle = {0.2, -0.1};
  js.mast_pan = 1.0;
  js.mast_tilt = -0.5;
  js.health = SensorHealth::kDegraded;
  rover_ddl_JointState out{};
  JointStateToIdl(js, &out);
  EXPECT_EQ(out.wheel_angle[5], 5.0);
  EXPECT_EQ(out.wheel_rate[4], -4.0);
  EXPECT_EQ(out.steer_angle[3], 0.4);
  EXPECT_EQ(out.rocker_angle[1], -0.05);
  EXPECT_EQ(out.bogie_angle[0], 0.2);
  EXPECT_EQ(out.mast_pan, 1.0);
  EXPECT_EQ(out.mast_tilt, -0.5);
  EXPECT_EQ(out.health, rover_HEALTH_DEGRADED);
}

}  // namespace
}  // namespace rover::ddl
