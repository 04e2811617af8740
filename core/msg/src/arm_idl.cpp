#include "rover/msg/arm_idl.hpp"

#include <algorithm>

#include "idl_enum.hpp"

namespace rover::msg {

static_assert(rover_dl_ARM_MODE_JOINTS == static_cast<int>(ArmMode::kJoints));
static_assert(rover_dl_ARM_MODE_PLACE == static_cast<int>(ArmMode::kPlace));
static_assert(rover_dl_ARM_MODE_STOW == static_cast<int>(ArmMode::kStow));
static_assert(rover_dl_ARM_MODE_STOP == static_cast<int>(ArmMode::kStop));
static_assert(rover_dl_ARM_MODE_AUTOFOCUS == static_cast<int>(ArmMode::kAutofocus));
static_assert(rover_dl_ARM_FOCUSED == static_cast<int>(ArmState::kFocused));
static_assert(rover_dl_ARM_IDLE == static_cast<int>(ArmState::kIdle));
static_assert(rover_dl_ARM_MOVING == static_cast<int>(ArmState::kMoving));
static_assert(rover_dl_ARM_AT_GOAL == static_cast<int>(ArmState::kAtGoal));
static_assert(rover_dl_ARM_PLACED == static_cast<int>(ArmState::kPlaced));
static_assert(rover_dl_ARM_STOWED == static_cast<int>(ArmState::kStowed));
static_assert(rover_dl_ARM_FAULT == static_cast<int>(ArmState::kFault));
static_assert(rover_dl_ARM_REJECTED == static_cast<int>(ArmState::kRejected));

namespace {
Eigen::Vector3d FromIdl(const rover_Vector3& v) { return {v.x, v.y, v.z}; }
rover_Vector3 ToIdl(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }
}  // namespace

ArmCommand ArmCommandFromIdl(const rover_dl_ArmCommand& in) {
  ArmCommand c;
  c.stamp = Time{in.header.stamp_ns};
  c.command_id = in.command_id;
  c.mode = internal::RawEnumFromIdl<ArmMode>(in.mode);
  for (std::size_t j = 0; j < c.joints.size(); ++j) c.joints[j] = in.joints[j];
  c.target = FromIdl(in.target);
  c.timeout_s = in.timeout_s;
  c.focus_steps = in.focus_steps;
  c.focus_span = in.focus_span;
  return c;
}

void ArmCommandToIdl(const ArmCommand& in, rover_dl_ArmCommand* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->command_id = in.command_id;
  idl::SetRawEnum(&out->mode, static_cast<std::int32_t>(in.mode));
  for (std::size_t j = 0; j < in.joints.size(); ++j) out->joints[j] = in.joints[j];
  out->target = ToIdl(in.target);
  out->timeout_s = in.timeout_s;
  out->focus_steps = static_cast<std::uint16_t>(std::clamp(in.focus_steps, 0, 65535));
  out->focus_span = in.focus_span;
}

Result<ArmStatus> ArmStatusFromIdl(const rover_dl_ArmStatus& in) {
  ArmStatus s;
  s.stamp = Time{in.header.stamp_ns};
  s.command_id = in.command_id;
  ROVER_ASSIGN_OR_RETURN(s.state, internal::EnumFromIdl<ArmState>(in.state, kNumArmStates, "dl/arm_status state",
                                                                  "ArmState"));
  for (std::size_t j = 0; j < s.joints.size(); ++j) {
    s.joints[j] = in.joints[j];
    s.joint_goals[j] = in.joint_goals[j];
  }
  s.tool_point = FromIdl(in.tool_point);
  s.contact = in.contact;
  s.stowed = in.stowed;
  s.focus_height = in.focus_height;
  s.focus_predicted = in.focus_predicted;
  s.focus_images = in.focus_images;
  s.focus_image_id = in.focus_image_id;
  s.focus_measure = in.focus_measure;
  s.message = idl::ReadString(in.message);
  return s;
}

void ArmStatusToIdl(const ArmStatus& in, rover_dl_ArmStatus* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->command_id = in.command_id;
  out->state = internal::EnumToIdl<rover_dl_ArmState>(in.state);
  for (std::size_t j = 0; j < in.joints.size(); ++j) {
    out->joints[j] = in.joints[j];
    out->joint_goals[j] = in.joint_goals[j];
  }
  out->tool_point = ToIdl(in.tool_point);
  out->contact = in.contact;
  out->stowed = in.stowed;
  out->focus_height = in.focus_height;
  out->focus_predicted = in.focus_predicted;
  out->focus_images = static_cast<std::uint16_t>(std::clamp(in.focus_images, 0, 65535));
  out->focus_image_id = in.focus_image_id;
  out->focus_measure = in.focus_measure;
  idl::CopyString(out->message, in.message);
}

}  // namespace rover::msg
