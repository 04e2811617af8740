#include "rover/msg/hw_idl.hpp"

#include <gtest/gtest.h>

#include <vector>

#include "rover/idl/access.hpp"

namespace rover::msg {
namespace {

TEST(HwIdl, MotorTelemetryRoundTrip) {
  rover_hw_MotorTelemetry t{};
  t.header.stamp_ns = 55;
  t.command_id = 4;
  t.motors[3] = {-2147483647, -20, 300, 2400, rover_hw_kMotorFlagStall};
  t.motors[10] = {123456, -7, 20, 2048, rover_hw_kMotorFlagEnabled};
  const hw::MotorTelemetry ht = MotorTelemetryFromIdl(t);
  EXPECT_EQ(ht.stamp_ns, 55);
  EXPECT_EQ(ht.command_id, 4u);
  EXPECT_EQ(ht.motors[3].position, -2147483647);
  EXPECT_EQ(ht.motors[3].velocity, -20);
  EXPECT_EQ(ht.motors[3].current_adc, 300);
  EXPECT_EQ(ht.motors[3].temperature_adc, 2400);
  EXPECT_EQ(ht.motors[3].flags, hw::kMotorFlagStall);
  EXPECT_EQ(ht.motors[10].position, 123456);
  EXPECT_EQ(ht.motors[10].flags, hw::kMotorFlagEnabled);
  rover_hw_MotorTelemetry back{};
  MotorTelemetryToIdl(ht, &back);
  EXPECT_EQ(back.header.stamp_ns, 55);
  EXPECT_EQ(back.command_id, 4u);
  for (int i = 0; i < hw::kNumMotors; ++i) {
    EXPECT_EQ(back.motors[i].position, t.motors[i].position);
    EXPECT_EQ(back.motors[i].velocity, t.motors[i].velocity);
    EXPECT_EQ(back.motors[i].current_adc, t.motors[i].current_adc);
    EXPECT_EQ(back.motors[i].temperature_adc, t.motors[i].temperature_adc);
    EXPECT_EQ(back.motors[i].flags, t.motors[i].flags);
  }
}

TEST(HwIdl, MotorGoalsRoundTripAndAnUnknownModeIsAnError) {
  hw::MotorGoals g;
  g.stamp_ns = 8;
  g.command_id = 17;
  g.goals[5] = {hw::MotorMode::kPosition, -500, 800, 1300};
  g.goals[11] = {hw::MotorMode::kBrake, 0, 0, 0};
  rover_hw_MotorGoals out{};
  MotorGoalsToIdl(g, &out);
  EXPECT_EQ(out.header.stamp_ns, 8);
  EXPECT_EQ(out.command_id, 17u);
  EXPECT_EQ(out.goals[5].mode, rover_hw_MOTOR_POSITION);
  EXPECT_EQ(out.goals[5].position, -500);
  EXPECT_EQ(out.goals[5].velocity, 800);
  EXPECT_EQ(out.goals[5].current_limit_ma, 1300);
  EXPECT_EQ(out.goals[11].mode, rover_hw_MOTOR_BRAKE);
  EXPECT_EQ(out.goals[0].mode, rover_hw_MOTOR_IDLE);
  auto back = MotorGoalsFromIdl(out);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->stamp_ns, 8);
  EXPECT_EQ(back->command_id, 17u);
  EXPECT_EQ(back->goals[5].mode, hw::MotorMode::kPosition);
  EXPECT_EQ(back->goals[5].position, -500);
  EXPECT_EQ(back->goals[5].velocity, 800);
  EXPECT_EQ(back->goals[5].current_limit_ma, 1300);
  EXPECT_EQ(back->goals[11].mode, hw::MotorMode::kBrake);
  idl::SetRawEnum(&out.goals[7].mode, 6);
  auto bad = MotorGoalsFromIdl(out);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "goals[7].mode = 6 is not a MotorMode (0..3)");
}

TEST(HwIdl, PotsImuAndSunRoundTrip) {
  rover_hw_SuspensionPots p{};
  p.header.stamp_ns = 88;
  p.adc[0] = 1;
  p.adc[3] = 4095;
  const hw::SuspensionPots hp = SuspensionPotsFromIdl(p);
  EXPECT_EQ(hp.stamp_ns, 88);
  EXPECT_EQ(hp.adc[0], 1);
  EXPECT_EQ(hp.adc[3], 4095);
  rover_hw_SuspensionPots p2{};
  SuspensionPotsToIdl(hp, &p2);
  EXPECT_EQ(p2.header.stamp_ns, 88);
  for (int i = 0; i < 4; ++i) EXPECT_EQ(p2.adc[i], p.adc[i]);

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
  rover_hw_ImuRaw raw2{};
  ImuRawToIdl(r, &raw2);
  EXPECT_EQ(raw2.header.stamp_ns, 42);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(raw2.gyro[i], raw.gyro[i]);
    EXPECT_EQ(raw2.accel[i], raw.accel[i]);
  }
  EXPECT_EQ(raw2.temperature, -1234);
  EXPECT_EQ(raw2.status, 4);

  rover_hw_SunSensorRaw sun{};
  sun.header.stamp_ns = 9;
  sun.spot[0] = -32768;
  sun.spot[1] = 1234;
  sun.intensity = 4095;
  const hw::SunSensorRaw s = SunSensorRawFromIdl(sun);
  EXPECT_EQ(s.stamp_ns, 9);
  EXPECT_EQ(s.spot[0], -32768);
  EXPECT_EQ(s.spot[1], 1234);
  EXPECT_EQ(s.intensity, 4095);
  rover_hw_SunSensorRaw sun2{};
  SunSensorRawToIdl(s, &sun2);
  EXPECT_EQ(sun2.header.stamp_ns, 9);
  EXPECT_EQ(sun2.spot[0], -32768);
  EXPECT_EQ(sun2.spot[1], 1234);
  EXPECT_EQ(sun2.intensity, 4095);
}

TEST(HwIdl, CameraRequestAndFrameRoundTrip) {
  rover_hw_CameraRequest hw{};
  CameraRequestToIdl({31, 77, 1, 300}, &hw);
  EXPECT_EQ(hw.header.stamp_ns, 31);
  EXPECT_EQ(hw.request_id, 77u);
  EXPECT_EQ(hw.camera, rover_CAMERA_FRONT_HAZCAM);
  EXPECT_EQ(hw.exposure_us, 300u);
  const hw::CameraRequest q = CameraRequestFromIdl(hw);
  EXPECT_EQ(q.stamp_ns, 31);
  EXPECT_EQ(q.request_id, 77u);
  EXPECT_EQ(q.camera, 1);
  EXPECT_EQ(q.exposure_us, 300u);
  idl::SetRawEnum(&hw.camera, 9);  // a camera no enum value names: kept for the receiver to judge
  EXPECT_EQ(CameraRequestFromIdl(hw).camera, 9);

  std::vector<std::uint8_t> left(6, 1), right(5, 2);
  rover_hw_CameraFrame f{};
  f.header.stamp_ns = 99;
  f.request_id = 77;
  f.camera = rover_CAMERA_FRONT_HAZCAM;
  f.exposure_us = 250;
  f.width = 3;
  f.height = 2;
  idl::BorrowSequence(f.left, left);
  idl::BorrowSequence(f.right, right);
  const hw::CameraFrame v = CameraFrameFromIdl(f);
  EXPECT_EQ(v.stamp_ns, 99);
  EXPECT_EQ(v.request_id, 77u);
  EXPECT_EQ(v.camera, 1);
  EXPECT_EQ(v.exposure_us, 250u);
  EXPECT_EQ(v.width, 3);
  EXPECT_EQ(v.height, 2);
  EXPECT_EQ(v.left.size(), 6u);
  EXPECT_EQ(v.right.size(), 5u);  // sizes are checked by the driver, not here
  EXPECT_EQ(v.left.data(), left.data());
  rover_hw_CameraFrame f2{};
  CameraFrameToIdl(v, &f2);
  EXPECT_EQ(f2.header.stamp_ns, 99);
  EXPECT_EQ(f2.request_id, 77u);
  EXPECT_EQ(f2.camera, rover_CAMERA_FRONT_HAZCAM);
  EXPECT_EQ(f2.exposure_us, 250u);
  EXPECT_EQ(f2.width, 3);
  EXPECT_EQ(f2.height, 2);
  EXPECT_EQ(f2.left._buffer, left.data());  // borrowed, not copied
  EXPECT_EQ(f2.right._length, 5u);
  EXPECT_FALSE(f2.right._release);
}

}  // namespace
}  // namespace rover::msg
