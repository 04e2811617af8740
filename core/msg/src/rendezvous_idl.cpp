#include "rover/msg/rendezvous_idl.hpp"

#include <algorithm>

#include "idl_enum.hpp"

namespace rover::msg {

static_assert(rover_apl_TARGET_LANDER == static_cast<int>(RendezvousTarget::kLander));
static_assert(rover_apl_TARGET_STOP == static_cast<int>(RendezvousTarget::kStop));
static_assert(rover_apl_PHASE_IDLE == static_cast<int>(RendezvousPhase::kIdle));
static_assert(rover_apl_PHASE_AT_RAMP_BASE == static_cast<int>(RendezvousPhase::kAtRampBase));
static_assert(rover_apl_PHASE_FAILED == static_cast<int>(RendezvousPhase::kFailed));
static_assert(rover_apl_PHASE_AT_TARGET == static_cast<int>(RendezvousPhase::kAtTarget));
static_assert(rover_apl_RZFAULT_NONE == static_cast<int>(RendezvousFault::kNone));
static_assert(rover_apl_RZFAULT_TARGET_LOST == static_cast<int>(RendezvousFault::kTargetLost));
static_assert(rover_apl_PHASE_PLACED == static_cast<int>(RendezvousPhase::kPlaced));
static_assert(rover_apl_PHASE_FOCUSED == static_cast<int>(RendezvousPhase::kFocused));
static_assert(rover_apl_RZFAULT_ARM == static_cast<int>(RendezvousFault::kArm));

RendezvousCommand RendezvousCommandFromIdl(const rover_apl_RendezvousCommand& in) {
  RendezvousCommand c;
  c.stamp = Time{in.header.stamp_ns};
  c.command_id = in.command_id;
  c.target = internal::RawEnumFromIdl<RendezvousTarget>(in.target);
  c.target_estimate = internal::Vec(in.target_estimate);
  c.standoff = in.standoff;
  c.ramp = in.ramp;
  c.climb = in.climb;
  c.time_budget_s = in.time_budget_s;
  c.image_id = in.image_id;
  c.pixel_x = in.pixel_x;
  c.pixel_y = in.pixel_y;
  c.place_instrument = in.place_instrument;
  c.autofocus = in.autofocus;
  return c;
}

void RendezvousCommandToIdl(const RendezvousCommand& in, rover_apl_RendezvousCommand* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->command_id = in.command_id;
  idl::SetRawEnum(&out->target, static_cast<std::int32_t>(in.target));
  out->target_estimate = internal::Vec(in.target_estimate);
  out->standoff = in.standoff;
  out->ramp = static_cast<std::int8_t>(std::clamp(in.ramp, -128, 127));
  out->climb = in.climb;
  out->time_budget_s = in.time_budget_s;
  out->image_id = in.image_id;
  out->pixel_x = in.pixel_x;
  out->pixel_y = in.pixel_y;
  out->place_instrument = in.place_instrument;
  out->autofocus = in.autofocus;
}

Result<RendezvousStatus> RendezvousStatusFromIdl(const rover_apl_RendezvousStatus& in) {
  RendezvousStatus s;
  s.stamp = Time{in.header.stamp_ns};
  s.command_id = in.command_id;
  ROVER_ASSIGN_OR_RETURN(s.phase, internal::EnumFromIdl<RendezvousPhase>(
                                      in.phase, kRendezvousPhaseCount,
                                      "apl/rendezvous_status phase", "RendezvousPhase"));
  ROVER_ASSIGN_OR_RETURN(s.fault, internal::EnumFromIdl<RendezvousFault>(
                                      in.fault, kRendezvousFaultCount,
                                      "apl/rendezvous_status fault", "RendezvousFault"));
  s.target_position = internal::Vec(in.target_position);
  s.target_sigma = in.target_sigma;
  s.range = in.range;
  s.range_sigma = in.range_sigma;
  s.bearing = in.bearing;
  s.bearing_sigma = in.bearing_sigma;
  s.ramp = in.ramp;
  s.images = in.images;
  s.features = idl::ReadString(in.features);
  s.message = idl::ReadString(in.message);
  s.target_in_rover = internal::Vec(in.target_in_rover);
  return s;
}

void RendezvousStatusToIdl(const RendezvousStatus& in, rover_apl_RendezvousStatus* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->command_id = in.command_id;
  out->phase = internal::EnumToIdl<rover_apl_RendezvousPhase>(in.phase);
  out->fault = internal::EnumToIdl<rover_apl_RendezvousFault>(in.fault);
  out->target_position = internal::Vec(in.target_position);
  out->target_sigma = in.target_sigma;
  out->range = in.range;
  out->range_sigma = in.range_sigma;
  out->bearing = in.bearing;
  out->bearing_sigma = in.bearing_sigma;
  out->ramp = static_cast<std::int8_t>(std::clamp(in.ramp, -1, 1));
  out->images = internal::ClampSize(in.images);
  idl::CopyString(out->features, in.features);
  idl::CopyString(out->message, in.message);
  out->target_in_rover = internal::Vec(in.target_in_rover);
}

}  // namespace rover::msg
