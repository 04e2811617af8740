#include "joints_idl.hpp"

namespace rover::ddl {

static_assert(rover_HEALTH_OK == static_cast<int>(SensorHealth::kOk));
static_assert(rover_HEALTH_DEGRADED == static_cast<int>(SensorHealth::kDegraded));
static_assert(rover_HEALTH_FAILED == static_cast<int>(SensorHealth::kFailed));
static_assert(rover_HEALTH_STALE == static_cast<int>(SensorHealth::kStale));

hw::MotorTelemetry JointTelemetryFromIdl(const rover_hw_MotorTelemetry& in) {
  hw::MotorTelemetry t;
  t.stamp_ns = in.header.stamp_ns;
  t.command_id = in.command_id;
  for (std::size_t i = 0; i < t.motors.size(); ++i) {
    const rover_hw_MotorReading& r = in.motors[i];
    t.motors[i] = {r.position, r.velocity, r.current_adc, r.temperature_adc, r.flags};
  }
  return t;
}

hw::SuspensionPots SuspensionPotsFromIdl(const rover_hw_SuspensionPots& in) {
  hw::SuspensionPots p;
  p.stamp_ns = in.header.stamp_ns;
  for (std::size_t i = 0; i < p.adc.size(); ++i) p.adc[i] = in.adc[i];
  return p;
}

void JointStateToIdl(const JointState& in, rover_ddl_JointState* out) {
  for (std::size_t i = 0; i < in.wheel_angle.size(); ++i) {
    out->wheel_angle[i] = in.wheel_angle[i];
    out->wheel_rate[i] = in.wheel_rate[i];
  }
  for (std::size_t i = 0; i < in.steer_angle.size(); ++i) out->steer_angle[i] = in.steer_angle[i];
  for (std::size_t i = 0; i < 2; ++i) {
    out->rocker_angle[i] = in.rocker_angle[i];
    out->bogie_angle[i] = in.bogie_angle[i];
  }
  out->mast_pan = in.mast_pan;
  out->mast_tilt = in.mast_tilt;
  out->health = JointHealthToIdl(in.health);
}

rover_SensorHealth JointHealthToIdl(SensorHealth h) {
  return static_cast<rover_SensorHealth>(static_cast<int>(h));
}

}  // namespace rover::ddl
