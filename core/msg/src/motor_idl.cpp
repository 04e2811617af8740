#include "rover/msg/motor_idl.hpp"

#include "idl_enum.hpp"

namespace rover::msg {

static_assert(rover_ddl_GROUP_POSITION == static_cast<int>(GroupMode::kPosition));
static_assert(rover_ddl_GROUP_VELOCITY == static_cast<int>(GroupMode::kVelocity));
static_assert(rover_ddl_GROUP_STOP == static_cast<int>(GroupMode::kStop));
static_assert(rover_ddl_GROUP_IDLE == static_cast<int>(GroupState::kIdle));
static_assert(rover_ddl_GROUP_RUNNING == static_cast<int>(GroupState::kRunning));
static_assert(rover_ddl_GROUP_DONE == static_cast<int>(GroupState::kDone));
static_assert(rover_ddl_GROUP_FAULT == static_cast<int>(GroupState::kFault));
static_assert(rover_ddl_GROUP_REJECTED == static_cast<int>(GroupState::kRejected));
static_assert(rover_ddl_MOTOR_FAULT_NONE == static_cast<int>(MotorFault::kNone));
static_assert(rover_ddl_MOTOR_FAULT_STALL == static_cast<int>(MotorFault::kStall));
static_assert(rover_ddl_MOTOR_FAULT_OVERCURRENT == static_cast<int>(MotorFault::kOverCurrent));
static_assert(rover_ddl_MOTOR_FAULT_OVERTEMP == static_cast<int>(MotorFault::kOverTemp));
static_assert(rover_ddl_MOTOR_FAULT_TIMEOUT == static_cast<int>(MotorFault::kTimeout));
static_assert(rover_ddl_MOTOR_FAULT_NO_TELEMETRY == static_cast<int>(MotorFault::kNoTelemetry));
static_assert(rover_ddl_MOTOR_FAULT_BAD_COMMAND == static_cast<int>(MotorFault::kBadCommand));
static_assert(rover_ddl_MOTOR_FAULT_STOPPED == static_cast<int>(MotorFault::kStopped));

MotorCommand MotorCommandFromIdl(const rover_ddl_MotorCommand& in) {
  MotorCommand c;
  c.stamp = Time{in.header.stamp_ns};
  c.command_id = in.command_id;
  c.motor_mask = in.motor_mask;
  c.mode = internal::RawEnumFromIdl<GroupMode>(in.mode);
  for (std::size_t i = 0; i < c.goal.size(); ++i) {
    c.goal[i] = in.goal[i];
    c.max_rate[i] = in.max_rate[i];
  }
  c.timeout_s = in.timeout_s;
  return c;
}

void MotorCommandToIdl(const MotorCommand& in, rover_ddl_MotorCommand* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->command_id = in.command_id;
  out->motor_mask = in.motor_mask;
  idl::SetRawEnum(&out->mode, static_cast<std::int32_t>(in.mode));
  for (std::size_t i = 0; i < in.goal.size(); ++i) {
    out->goal[i] = in.goal[i];
    out->max_rate[i] = in.max_rate[i];
  }
  out->timeout_s = in.timeout_s;
}

Result<MotorStatus> MotorStatusFromIdl(const rover_ddl_MotorStatus& in) {
  MotorStatus s;
  s.stamp = Time{in.header.stamp_ns};
  s.command_id = in.command_id;
  ROVER_ASSIGN_OR_RETURN(s.state, internal::EnumFromIdl<GroupState>(
                                      in.state, 5, "ddl/motor_status state", "GroupState"));
  ROVER_ASSIGN_OR_RETURN(s.fault, internal::EnumFromIdl<MotorFault>(
                                      in.fault, 8, "ddl/motor_status fault", "MotorFault"));
  s.fault_motor = in.fault_motor;
  s.message = idl::ReadString(in.message);
  for (std::size_t i = 0; i < s.position.size(); ++i) {
    s.position[i] = in.position[i];
    s.velocity[i] = in.velocity[i];
    s.current[i] = in.current[i];
    s.temperature[i] = in.temperature[i];
  }
  return s;
}

void MotorStatusToIdl(const MotorStatus& in, rover_ddl_MotorStatus* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->command_id = in.command_id;
  out->state = internal::EnumToIdl<rover_ddl_GroupState>(in.state);
  out->fault = internal::EnumToIdl<rover_ddl_MotorFault>(in.fault);
  out->fault_motor = in.fault_motor;
  idl::CopyString(out->message, in.message);
  for (std::size_t i = 0; i < in.position.size(); ++i) {
    out->position[i] = in.position[i];
    out->velocity[i] = in.velocity[i];
    out->current[i] = in.current[i];
    out->temperature[i] = in.temperature[i];
  }
}

}  // namespace rover::msg
