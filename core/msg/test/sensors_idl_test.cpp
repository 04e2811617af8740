#include "rover/msg/sensors_idl.hpp"

#include <gtest/gtest.h>

#include "rover/idl/access.hpp"

namespace rover::msg {
namespace {

TEST(SensorsIdl, ImuRoundTrip) {
  Imu imu;
  imu.stamp = Time{42};
  imu.angular_velocity = Eigen::Vector3d(1, 2, 3);
  imu.linear_acceleration = Eigen::Vector3d(-1, -2, 9.81);
  imu.temperature = 21.5;
  imu.health = SensorHealth::kFailed;
  rover_ddl_Imu out{};
  ImuToIdl(imu, &out);
  EXPECT_EQ(out.header.stamp_ns, 42);
  EXPECT_EQ(out.angular_velocity.x, 1.0);
  EXPECT_EQ(out.angular_velocity.z, 3.0);
  EXPECT_EQ(out.linear_acceleration.y, -2.0);
  EXPECT_EQ(out.linear_acceleration.z, 9.81);
  EXPECT_EQ(out.temperature, 21.5);
  EXPECT_EQ(out.health, rover_HEALTH_FAILED);
  auto back = ImuFromIdl(out);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->stamp, imu.stamp);
  EXPECT_EQ(back->angular_velocity, imu.angular_velocity);
  EXPECT_EQ(back->linear_acceleration, imu.linear_acceleration);
  EXPECT_EQ(back->temperature, 21.5);
  EXPECT_EQ(back->health, SensorHealth::kFailed);
  idl::SetRawEnum(&out.health, 4);
  auto bad = ImuFromIdl(out);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("ddl/imu health = 4"), std::string::npos);
}

TEST(SensorsIdl, SunSensorRoundTrip) {
  SunSensor s;
  s.stamp = Time{9};
  s.sun_vector = Eigen::Vector3d(0.6, 0.0, 0.8);
  s.valid = true;
  s.intensity = 0.75;
  s.health = SensorHealth::kFailed;
  rover_ddl_SunSensor out{};
  SunSensorToIdl(s, &out);
  EXPECT_EQ(out.sun_vector.x, 0.6);
  EXPECT_EQ(out.sun_vector.z, 0.8);
  EXPECT_TRUE(out.valid);
  EXPECT_EQ(out.intensity, 0.75);
  EXPECT_EQ(out.health, rover_HEALTH_FAILED);
  auto back = SunSensorFromIdl(out);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->stamp, s.stamp);
  EXPECT_EQ(back->sun_vector, s.sun_vector);
  EXPECT_TRUE(back->valid);
  EXPECT_EQ(back->intensity, 0.75);
  EXPECT_EQ(back->health, SensorHealth::kFailed);
  idl::SetRawEnum(&out.health, -1);
  EXPECT_FALSE(SunSensorFromIdl(out).ok());
}

TEST(SensorsIdl, JointStateRoundTrip) {
  JointState js;
  js.stamp = Time{123};
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
  auto back = JointStateFromIdl(out);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->stamp, js.stamp);
  EXPECT_EQ(back->wheel_angle, js.wheel_angle);
  EXPECT_EQ(back->wheel_rate, js.wheel_rate);
  EXPECT_EQ(back->steer_angle, js.steer_angle);
  EXPECT_EQ(back->rocker_angle, js.rocker_angle);
  EXPECT_EQ(back->bogie_angle, js.bogie_angle);
  EXPECT_EQ(back->mast_pan, 1.0);
  EXPECT_EQ(back->mast_tilt, -0.5);
  EXPECT_EQ(back->health, SensorHealth::kDegraded);
  // A STALE sample converts (it is the consumer's to drop); an unknown health value does not.
  out.health = rover_HEALTH_STALE;
  ASSERT_TRUE(JointStateFromIdl(out).ok());
  EXPECT_FALSE(IsUsable(JointStateFromIdl(out)->health));
  idl::SetRawEnum(&out.health, 17);
  auto bad = JointStateFromIdl(out);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "ddl/joint_state health = 17 is not a SensorHealth (0..3)");
}

}  // namespace
}  // namespace rover::msg
