#include "rover/msg/hw_idl.hpp"

#include <algorithm>
#include <string>

#include "idl_enum.hpp"

namespace rover::msg {

using internal::ClampSize;
static_assert(rover_hw_kNumMotors == hw::kNumMotors);
static_assert(rover_hw_MOTOR_IDLE == static_cast<int>(hw::MotorMode::kIdle));
static_assert(rover_hw_MOTOR_POSITION == static_cast<int>(hw::MotorMode::kPosition));
static_assert(rover_hw_MOTOR_VELOCITY == static_cast<int>(hw::MotorMode::kVelocity));
static_assert(rover_hw_MOTOR_BRAKE == static_cast<int>(hw::MotorMode::kBrake));
static_assert(rover_hw_kMotorFlagEnabled == hw::kMotorFlagEnabled);
static_assert(rover_hw_kMotorFlagAtGoal == hw::kMotorFlagAtGoal);
static_assert(rover_hw_kMotorFlagStall == hw::kMotorFlagStall);
static_assert(rover_hw_kMotorFlagOverCurrent == hw::kMotorFlagOverCurrent);
static_assert(rover_hw_kMotorFlagOverTemp == hw::kMotorFlagOverTemp);

hw::MotorTelemetry MotorTelemetryFromIdl(const rover_hw_MotorTelemetry& in) {
  hw::MotorTelemetry t;
  t.stamp_ns = in.header.stamp_ns;
  t.command_id = in.command_id;
  for (std::size_t i = 0; i < t.motors.size(); ++i) {
    const rover_hw_MotorReading& r = in.motors[i];
    t.motors[i] = {r.position, r.velocity, r.current_adc, r.temperature_adc, r.flags};
  }
  return t;
}

void MotorTelemetryToIdl(const hw::MotorTelemetry& in, rover_hw_MotorTelemetry* out) {
  out->header.stamp_ns = in.stamp_ns;
  out->command_id = in.command_id;
  for (std::size_t i = 0; i < in.motors.size(); ++i) {
    const hw::MotorReading& r = in.motors[i];
    out->motors[i] = {r.position, r.velocity, r.current_adc, r.temperature_adc, r.flags};
  }
}

Result<hw::MotorGoals> MotorGoalsFromIdl(const rover_hw_MotorGoals& in) {
  hw::MotorGoals g;
  g.stamp_ns = in.header.stamp_ns;
  g.command_id = in.command_id;
  for (std::size_t i = 0; i < g.goals.size(); ++i) {
    const rover_hw_MotorGoal& src = in.goals[i];
    hw::MotorGoal& dst = g.goals[i];
    ROVER_ASSIGN_OR_RETURN(dst.mode,
                           internal::EnumFromIdl<hw::MotorMode>(
                               src.mode, 4, "goals[" + std::to_string(i) + "].mode", "MotorMode"));
    dst.position = src.position;
    dst.velocity = src.velocity;
    dst.current_limit_ma = src.current_limit_ma;
  }
  return g;
}

void MotorGoalsToIdl(const hw::MotorGoals& in, rover_hw_MotorGoals* out) {
  out->header.stamp_ns = in.stamp_ns;
  out->command_id = in.command_id;
  for (std::size_t i = 0; i < in.goals.size(); ++i) {
    const hw::MotorGoal& g = in.goals[i];
    rover_hw_MotorGoal& o = out->goals[i];
    o.mode = internal::EnumToIdl<rover_hw_MotorMode>(g.mode);
    o.position = g.position;
    o.velocity = g.velocity;
    o.current_limit_ma = g.current_limit_ma;
  }
}

hw::SuspensionPots SuspensionPotsFromIdl(const rover_hw_SuspensionPots& in) {
  hw::SuspensionPots p;
  p.stamp_ns = in.header.stamp_ns;
  for (std::size_t i = 0; i < p.adc.size(); ++i) p.adc[i] = in.adc[i];
  return p;
}

void SuspensionPotsToIdl(const hw::SuspensionPots& in, rover_hw_SuspensionPots* out) {
  out->header.stamp_ns = in.stamp_ns;
  for (std::size_t i = 0; i < in.adc.size(); ++i) out->adc[i] = in.adc[i];
}

hw::ArmContact ArmContactFromIdl(const rover_hw_ArmContact& in) {
  return {in.header.stamp_ns, in.closed};
}

void ArmContactToIdl(const hw::ArmContact& in, rover_hw_ArmContact* out) {
  out->header.stamp_ns = in.stamp_ns;
  out->closed = in.closed;
}

hw::ImuRaw ImuRawFromIdl(const rover_hw_ImuRaw& in) {
  hw::ImuRaw r;
  r.stamp_ns = in.header.stamp_ns;
  for (std::size_t i = 0; i < 3; ++i) {
    r.gyro[i] = in.gyro[i];
    r.accel[i] = in.accel[i];
  }
  r.temperature = in.temperature;
  r.status = in.status;
  return r;
}

void ImuRawToIdl(const hw::ImuRaw& in, rover_hw_ImuRaw* out) {
  out->header.stamp_ns = in.stamp_ns;
  for (std::size_t i = 0; i < 3; ++i) {
    out->gyro[i] = in.gyro[i];
    out->accel[i] = in.accel[i];
  }
  out->temperature = in.temperature;
  out->status = in.status;
}

hw::SunSensorRaw SunSensorRawFromIdl(const rover_hw_SunSensorRaw& in) {
  hw::SunSensorRaw r;
  r.stamp_ns = in.header.stamp_ns;
  r.spot = {in.spot[0], in.spot[1]};
  r.intensity = in.intensity;
  return r;
}

void SunSensorRawToIdl(const hw::SunSensorRaw& in, rover_hw_SunSensorRaw* out) {
  out->header.stamp_ns = in.stamp_ns;
  out->spot[0] = in.spot[0];
  out->spot[1] = in.spot[1];
  out->intensity = in.intensity;
}

hw::CameraRequest CameraRequestFromIdl(const rover_hw_CameraRequest& in) {
  return {in.header.stamp_ns, in.request_id, idl::RawEnum(in.camera), in.exposure_us,
          in.readout_width};
}

void CameraRequestToIdl(const hw::CameraRequest& in, rover_hw_CameraRequest* out) {
  out->header.stamp_ns = in.stamp_ns;
  out->request_id = in.request_id;
  idl::SetRawEnum(&out->camera, in.camera);
  out->exposure_us = in.exposure_us;
  out->readout_width = static_cast<std::uint16_t>(std::clamp(in.readout_width, 0, 65535));
}

hw::CameraFrame CameraFrameFromIdl(const rover_hw_CameraFrame& in) {
  return {in.header.stamp_ns, in.request_id, idl::RawEnum(in.camera), in.exposure_us,
          in.width,           in.height,     idl::View(in.left),      idl::View(in.right)};
}

void CameraFrameToIdl(const hw::CameraFrame& in, rover_hw_CameraFrame* out) {
  out->header.stamp_ns = in.stamp_ns;
  out->request_id = in.request_id;
  idl::SetRawEnum(&out->camera, in.camera);
  out->exposure_us = in.exposure_us;
  out->width = ClampSize(in.width);
  out->height = ClampSize(in.height);
  idl::BorrowSequence(out->left, in.left);
  idl::BorrowSequence(out->right, in.right);
}

hw::MiRequest MiRequestFromIdl(const rover_hw_MiRequest& in) {
  return {in.header.stamp_ns, in.request_id, in.exposure_us};
}

void MiRequestToIdl(const hw::MiRequest& in, rover_hw_MiRequest* out) {
  out->header.stamp_ns = in.stamp_ns;
  out->request_id = in.request_id;
  out->exposure_us = in.exposure_us;
}

hw::MiFrame MiFrameFromIdl(const rover_hw_MiFrame& in) {
  return {in.header.stamp_ns, in.request_id, in.exposure_us, in.width, in.height,
          idl::View(in.image)};
}

void MiFrameToIdl(const hw::MiFrame& in, rover_hw_MiFrame* out) {
  out->header.stamp_ns = in.stamp_ns;
  out->request_id = in.request_id;
  out->exposure_us = in.exposure_us;
  out->width = ClampSize(in.width);
  out->height = ClampSize(in.height);
  idl::BorrowSequence(out->image, in.image);
}

}  // namespace rover::msg
