#include "rover/msg/drive_idl.hpp"

#include "idl_enum.hpp"

namespace rover::msg {

static_assert(rover_dl_PRIMITIVE_STOP == static_cast<int>(DrivePrimitive::kStop));
static_assert(rover_dl_PRIMITIVE_ARC == static_cast<int>(DrivePrimitive::kArc));
static_assert(rover_dl_PRIMITIVE_STRAIGHT == static_cast<int>(DrivePrimitive::kStraight));
static_assert(rover_dl_PRIMITIVE_TURN_IN_PLACE == static_cast<int>(DrivePrimitive::kTurnInPlace));
static_assert(rover_dl_PRIMITIVE_STEER == static_cast<int>(DrivePrimitive::kSteer));
static_assert(rover_dl_DRIVE_IDLE == static_cast<int>(DriveState::kIdle));
static_assert(rover_dl_DRIVE_STEERING == static_cast<int>(DriveState::kSteering));
static_assert(rover_dl_DRIVE_DRIVING == static_cast<int>(DriveState::kDriving));
static_assert(rover_dl_DRIVE_TURNING == static_cast<int>(DriveState::kTurning));
static_assert(rover_dl_DRIVE_DONE == static_cast<int>(DriveState::kDone));
static_assert(rover_dl_DRIVE_FAILED == static_cast<int>(DriveState::kFailed));
static_assert(rover_dl_DRIVE_REJECTED == static_cast<int>(DriveState::kRejected));
static_assert(rover_dl_TERMINATION_NONE == static_cast<int>(DriveTermination::kNone));
static_assert(rover_dl_TERMINATION_NOMINAL == static_cast<int>(DriveTermination::kNominal));
static_assert(rover_dl_TERMINATION_TILT == static_cast<int>(DriveTermination::kTilt));
static_assert(rover_dl_TERMINATION_SUSPENSION == static_cast<int>(DriveTermination::kSuspension));
static_assert(rover_dl_TERMINATION_MOTOR_STALL == static_cast<int>(DriveTermination::kMotorStall));
static_assert(rover_dl_TERMINATION_MOTOR_CURRENT ==
              static_cast<int>(DriveTermination::kMotorCurrent));
static_assert(rover_dl_TERMINATION_MOTOR_FAULT == static_cast<int>(DriveTermination::kMotorFault));
static_assert(rover_dl_TERMINATION_TIMEOUT == static_cast<int>(DriveTermination::kTimeout));
static_assert(rover_dl_TERMINATION_STOP_COMMAND ==
              static_cast<int>(DriveTermination::kStopCommand));
static_assert(rover_dl_TERMINATION_REJECTED_BUSY ==
              static_cast<int>(DriveTermination::kRejectedBusy));
static_assert(rover_dl_TERMINATION_REJECTED_INVALID ==
              static_cast<int>(DriveTermination::kRejectedInvalid));
static_assert(rover_dl_TERMINATION_STALE_SENSOR ==
              static_cast<int>(DriveTermination::kStaleSensor));

DriveCommand DriveCommandFromIdl(const rover_dl_DriveCommand& in) {
  DriveCommand c;
  c.stamp = Time{in.header.stamp_ns};
  c.command_id = in.command_id;
  c.primitive = internal::RawEnumFromIdl<DrivePrimitive>(in.primitive);
  c.curvature = in.curvature;
  c.distance = in.distance;
  c.angle = in.angle;
  c.speed = in.speed;
  c.timeout_s = in.timeout_s;
  return c;
}

void DriveCommandToIdl(const DriveCommand& in, rover_dl_DriveCommand* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->command_id = in.command_id;
  idl::SetRawEnum(&out->primitive, static_cast<std::int32_t>(in.primitive));
  out->curvature = in.curvature;
  out->distance = in.distance;
  out->angle = in.angle;
  out->speed = in.speed;
  out->timeout_s = in.timeout_s;
}

Result<DriveStatus> DriveStatusFromIdl(const rover_dl_DriveStatus& in) {
  DriveStatus s;
  s.stamp = Time{in.header.stamp_ns};
  s.command_id = in.command_id;
  ROVER_ASSIGN_OR_RETURN(s.primitive,
                         internal::EnumFromIdl<DrivePrimitive>(
                             in.primitive, 5, "dl/drive_status primitive", "DrivePrimitive"));
  ROVER_ASSIGN_OR_RETURN(s.state, internal::EnumFromIdl<DriveState>(
                                      in.state, 7, "dl/drive_status state", "DriveState"));
  ROVER_ASSIGN_OR_RETURN(
      s.termination, internal::EnumFromIdl<DriveTermination>(
                         in.termination, 12, "dl/drive_status termination", "DriveTermination"));
  s.distance_done = in.distance_done;
  s.heading_change = in.heading_change;
  s.message = idl::ReadString(in.message);
  return s;
}

rover_dl_DrivePrimitive DrivePrimitiveToIdl(DrivePrimitive p) {
  return IsKnownPrimitive(p) ? internal::EnumToIdl<rover_dl_DrivePrimitive>(p)
                             : rover_dl_PRIMITIVE_STOP;
}

void DriveStatusToIdl(const DriveStatus& in, rover_dl_DriveStatus* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->command_id = in.command_id;
  out->primitive = DrivePrimitiveToIdl(in.primitive);
  out->state = internal::EnumToIdl<rover_dl_DriveState>(in.state);
  out->termination = internal::EnumToIdl<rover_dl_DriveTermination>(in.termination);
  out->distance_done = in.distance_done;
  out->heading_change = in.heading_change;
  idl::CopyString(out->message, in.message);
}

}  // namespace rover::msg
