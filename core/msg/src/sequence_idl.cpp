#include "rover/msg/sequence_idl.hpp"

#include "idl_enum.hpp"

namespace rover::msg {

static_assert(rover_apl_SEQUENCE_IDLE == static_cast<int>(SequenceState::kIdle));
static_assert(rover_apl_SEQUENCE_RUNNING == static_cast<int>(SequenceState::kRunning));
static_assert(rover_apl_SEQUENCE_DONE == static_cast<int>(SequenceState::kDone));
static_assert(rover_apl_SEQUENCE_FAILED == static_cast<int>(SequenceState::kFailed));
static_assert(sizeof(rover_apl_SequenceCommand::text) == kMaxSequenceTextBytes + 1);
static_assert(sizeof(rover_apl_SequenceCommand::overrides) == kMaxSequenceOverridesBytes + 1);

SequenceCommand SequenceCommandFromIdl(const rover_apl_SequenceCommand& in) {
  SequenceCommand c;
  c.stamp = Time{in.header.stamp_ns};
  c.command_id = in.command_id;
  c.text = idl::ReadString(in.text);
  c.overrides = idl::ReadString(in.overrides);
  return c;
}

Status SequenceCommandToIdl(const SequenceCommand& in, rover_apl_SequenceCommand* out) {
  if (in.text.size() > kMaxSequenceTextBytes) {
    return InvalidArgument("apl/sequence_command text is " + std::to_string(in.text.size()) +
                           " bytes; the message carries at most " +
                           std::to_string(kMaxSequenceTextBytes));
  }
  if (in.overrides.size() > kMaxSequenceOverridesBytes) {
    return InvalidArgument("apl/sequence_command overrides are " +
                           std::to_string(in.overrides.size()) + " bytes; the message carries at most " +
                           std::to_string(kMaxSequenceOverridesBytes));
  }
  out->header.stamp_ns = in.stamp.ns;
  out->command_id = in.command_id;
  idl::CopyString(out->text, in.text);
  idl::CopyString(out->overrides, in.overrides);
  return Status::Ok();
}

Result<SequenceStatus> SequenceStatusFromIdl(const rover_apl_SequenceStatus& in) {
  SequenceStatus s;
  s.stamp = Time{in.header.stamp_ns};
  s.command_id = in.command_id;
  ROVER_ASSIGN_OR_RETURN(s.state, internal::EnumFromIdl<SequenceState>(
                                      in.state, 4, "apl/sequence_status state",
                                      "SequenceState"));
  s.step = in.step;
  s.message = idl::ReadString(in.message);
  return s;
}

void SequenceStatusToIdl(const SequenceStatus& in, rover_apl_SequenceStatus* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->command_id = in.command_id;
  out->state = internal::EnumToIdl<rover_apl_SequenceState>(in.state);
  out->step = in.step;
  idl::CopyString(out->message, in.message);
}

}  // namespace rover::msg
