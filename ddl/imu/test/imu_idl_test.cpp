#include "imu_idl.hpp"

#include <gtest/gtest.h>

namespace rover::ddl {
namespace {

TEST(ImuIdl, FieldByField) {
  rover_hw_ImuRaw raw{};
  raw.header.stamp_ns = 42;
  raw.gyro[0] = -5;
  raw.gyro[2] = 2147483647;
  raw.accel[1] = 9810000;
  raw.temperature = -1234;
  raw.status = rover_hw_kMotorFlagStall;  // any bits pass through
  const hw::ImuRaw r = ImuRawFromIdl(raw);
  EXPECT_EQ(r.stamp_ns, 42);
  EXPECT_EQ(r.gyro[0], -5);
  EXPECT_EQ(r.gyro[2], 2147483647);
  EXPECT_EQ(r.accel[1], 9810000);
  EXPECT_EQ(r.temperature, -1234);
  EXPECT_EQ(r.status, 4);

  Imu imu;
  imu.angular_velocity = Eigen::Vector3d(1, 2, 3);
  imu.linear_acceleration = Eigen::Vector3d(-1, -2, 9.81);
  imu.temperature = 21.5;
  imu.health = SensorHealth::kFailed;
  rover_ddl_Imu out{};
  ImuToIdl(imu, &out);
  EXPECT_EQ(out.angular_velocity.x, 1.0);
  EXPECT_EQ(out.angular_velocity.z, 3.0);
  EXPECT_EQ(out.linear_acceleration.y, -2.0);
  EXPECT_EQ(out.linear_acceleration.z, 9.81);
  EXPECT_EQ(out.temperature, 21.5);
  EXPECT_EQ(out.health, rover_HEALTH_FAILED);
}

}  // namespace
}  // namespace rover::ddl
