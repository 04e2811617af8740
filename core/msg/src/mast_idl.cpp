#include "rover/msg/mast_idl.hpp"

#include "idl_enum.hpp"

namespace rover::msg {

static_assert(rover_dl_MAST_POINT_ANGLES == static_cast<int>(MastPointing::kAngles));
static_assert(rover_dl_MAST_POINT_LOOK_AT == static_cast<int>(MastPointing::kLookAt));
static_assert(rover_dl_MAST_IDLE == static_cast<int>(MastState::kIdle));
static_assert(rover_dl_MAST_MOVING == static_cast<int>(MastState::kMoving));
static_assert(rover_dl_MAST_AT_GOAL == static_cast<int>(MastState::kAtGoal));
static_assert(rover_dl_MAST_FAULT == static_cast<int>(MastState::kFault));
static_assert(rover_dl_MAST_REJECTED == static_cast<int>(MastState::kRejected));

MastCommand MastCommandFromIdl(const rover_dl_MastCommand& in) {
  MastCommand c;
  c.stamp = Time{in.header.stamp_ns};
  c.command_id = in.command_id;
  c.pointing = internal::RawEnumFromIdl<MastPointing>(in.pointing);
  c.pan = in.pan;
  c.tilt = in.tilt;
  c.look_at = Eigen::Vector3d(in.look_at.x, in.look_at.y, in.look_at.z);
  c.timeout_s = in.timeout_s;
  return c;
}

void MastCommandToIdl(const MastCommand& in, rover_dl_MastCommand* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->command_id = in.command_id;
  idl::SetRawEnum(&out->pointing, static_cast<std::int32_t>(in.pointing));
  out->pan = in.pan;
  out->tilt = in.tilt;
  out->look_at = {in.look_at.x(), in.look_at.y(), in.look_at.z()};
  out->timeout_s = in.timeout_s;
}

Result<MastStatus> MastStatusFromIdl(const rover_dl_MastStatus& in) {
  MastStatus s;
  s.stamp = Time{in.header.stamp_ns};
  s.command_id = in.command_id;
  ROVER_ASSIGN_OR_RETURN(s.state, internal::EnumFromIdl<MastState>(
                                      in.state, 5, "dl/mast_status state", "MastState"));
  s.pan = in.pan;
  s.tilt = in.tilt;
  s.pan_goal = in.pan_goal;
  s.tilt_goal = in.tilt_goal;
  s.message = idl::ReadString(in.message);
  return s;
}

void MastStatusToIdl(const MastStatus& in, rover_dl_MastStatus* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->command_id = in.command_id;
  out->state = internal::EnumToIdl<rover_dl_MastState>(in.state);
  out->pan = in.pan;
  out->tilt = in.tilt;
  out->pan_goal = in.pan_goal;
  out->tilt_goal = in.tilt_goal;
  idl::CopyString(out->message, in.message);
}

}  // namespace rover::msg
