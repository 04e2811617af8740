#include "rover/msg/mobility_idl.hpp"

#include <algorithm>
#include <utility>

#include "idl_enum.hpp"

namespace rover::msg {

static_assert(rover_apl_MOBILITY_DIRECTED == static_cast<int>(MobilityMode::kDirected));
static_assert(rover_apl_MOBILITY_GUARDED_ARC == static_cast<int>(MobilityMode::kGuardedArc));
static_assert(rover_apl_MOBILITY_CLEAR_FAULT == static_cast<int>(MobilityMode::kClearFault));
static_assert(rover_apl_MOBILITY_CLEAR_FAULT + 1 == kMobilityModeCount);
static_assert(rover_apl_THINK_DRIVE_WHILE_THINKING ==
              static_cast<int>(ThinkMode::kDriveWhileThinking));
static_assert(rover_apl_MOBILITY_REJECTED == static_cast<int>(MobilityState::kRejected));
static_assert(rover_apl_FAULT_MOTION_ERROR == static_cast<int>(FaultClass::kMotionError));
static_assert(rover_apl_MOBFAULT_BAD_COMMAND == static_cast<int>(MobilityFault::kBadCommand));
static_assert(rover_apl_MOBFAULT_IMG == static_cast<int>(MobilityFault::kImg));
static_assert(rover_apl_MOBFAULT_NORTH == static_cast<int>(MobilityFault::kNorth));
static_assert(rover_apl_MOBFAULT_RESTART == static_cast<int>(MobilityFault::kRestart));
static_assert(rover_apl_MOBFAULT_RESTART + 1 == kMobilityFaultCount);

MobilityCommandMessage& MobilityCommandMessage::operator=(const MobilityCommandMessage& o) {
  msg = o.msg;
  primitives = o.primitives;
  zones = o.zones;
  vertices = o.vertices;
  Repoint();
  return *this;
}

void MobilityCommandMessage::Repoint() {
  for (std::size_t i = 0; i < zones.size() && i < vertices.size(); ++i) {
    idl::BorrowSequence(zones[i].vertices, vertices[i]);
  }
  idl::BorrowSequence(msg.primitives, primitives);
  idl::BorrowSequence(msg.keep_out, zones);
}

MobilityCommand MobilityCommandFromIdl(const rover_apl_MobilityCommand& in) {
  MobilityCommand c;
  c.stamp = Time{in.header.stamp_ns};
  c.command_id = in.command_id;
  c.mode = internal::RawEnumFromIdl<MobilityMode>(in.mode);
  c.goal = Eigen::Vector3d(in.goal.x, in.goal.y, in.goal.z);
  c.tolerance = in.tolerance;
  c.time_budget_s = in.time_budget_s;
  for (const rover_apl_MobilityPrimitive& p : idl::View(in.primitives)) {
    c.primitives.push_back(
        {internal::RawEnumFromIdl<DrivePrimitive>(p.primitive), p.curvature, p.distance, p.angle});
  }
  for (const rover_apl_KeepOutZone& z : idl::View(in.keep_out)) {
    KeepOutZone k;
    k.name = idl::ReadString(z.name);
    for (const rover_apl_Point2& v : idl::View(z.vertices)) k.vertices.emplace_back(v.x, v.y);
    c.keep_out.push_back(std::move(k));
  }
  c.think = internal::RawEnumFromIdl<ThinkMode>(in.think);
  c.max_tilt = in.max_tilt;
  c.min_northerly_tilt = in.min_northerly_tilt;
  c.lmst_end_h = in.lmst_end_h;
  c.max_steps = in.max_steps;
  return c;
}

void MobilityCommandToIdl(const MobilityCommand& in, MobilityCommandMessage* out) {
  rover_apl_MobilityCommand& m = out->msg;
  m.header.stamp_ns = in.stamp.ns;
  m.command_id = in.command_id;
  idl::SetRawEnum(&m.mode, static_cast<std::int32_t>(in.mode));
  m.goal = {in.goal.x(), in.goal.y(), in.goal.z()};
  m.tolerance = in.tolerance;
  m.time_budget_s = in.time_budget_s;
  out->primitives.clear();
  for (const MobilityPrimitive& p : in.primitives) {
    rover_apl_MobilityPrimitive w{};
    idl::SetRawEnum(&w.primitive, static_cast<std::int32_t>(p.kind));
    w.curvature = p.curvature;
    w.distance = p.distance;
    w.angle = p.angle;
    out->primitives.push_back(w);
  }
  out->zones.clear();
  out->vertices.clear();
  for (const KeepOutZone& z : in.keep_out) {
    rover_apl_KeepOutZone k{};
    idl::CopyString(k.name, z.name);
    out->zones.push_back(k);
    std::vector<rover_apl_Point2> v;
    for (const Eigen::Vector2d& p : z.vertices) v.push_back({p.x(), p.y()});
    out->vertices.push_back(std::move(v));
  }
  idl::SetRawEnum(&m.think, static_cast<std::int32_t>(in.think));
  m.max_tilt = in.max_tilt;
  m.min_northerly_tilt = in.min_northerly_tilt;
  m.lmst_end_h = in.lmst_end_h;
  m.max_steps = static_cast<std::uint16_t>(std::clamp(in.max_steps, 0, 65535));
  out->Repoint();
}

Result<MobilityStatus> MobilityStatusFromIdl(const rover_apl_MobilityStatus& in) {
  MobilityStatus s;
  s.stamp = Time{in.header.stamp_ns};
  s.command_id = in.command_id;
  ROVER_ASSIGN_OR_RETURN(
      s.mode, internal::EnumFromIdl<MobilityMode>(in.mode, kMobilityModeCount,
                                                  "apl/mobility_status mode", "MobilityMode"));
  ROVER_ASSIGN_OR_RETURN(
      s.state, internal::EnumFromIdl<MobilityState>(in.state, kMobilityStateCount,
                                                    "apl/mobility_status state", "MobilityState"));
  ROVER_ASSIGN_OR_RETURN(s.fault_class, internal::EnumFromIdl<FaultClass>(
                                            in.fault_class, kFaultClassCount,
                                            "apl/mobility_status fault_class", "FaultClass"));
  ROVER_ASSIGN_OR_RETURN(
      s.fault, internal::EnumFromIdl<MobilityFault>(in.fault, kMobilityFaultCount,
                                                    "apl/mobility_status fault", "MobilityFault"));
  s.message = idl::ReadString(in.message);
  s.distance_to_goal = in.distance_to_goal;
  s.distance_driven = in.distance_driven;
  s.steps = in.steps;
  s.images = in.images;
  s.motion_error_latched = in.motion_error_latched;
  return s;
}

void MobilityStatusToIdl(const MobilityStatus& in, rover_apl_MobilityStatus* out) {
  out->header.stamp_ns = in.stamp.ns;
  out->command_id = in.command_id;
  out->mode = internal::EnumToIdl<rover_apl_MobilityMode>(in.mode);
  out->state = internal::EnumToIdl<rover_apl_MobilityState>(in.state);
  out->fault_class = internal::EnumToIdl<rover_apl_FaultClass>(in.fault_class);
  out->fault = internal::EnumToIdl<rover_apl_MobilityFault>(in.fault);
  idl::CopyString(out->message, in.message);
  out->distance_to_goal = in.distance_to_goal;
  out->distance_driven = in.distance_driven;
  out->steps = in.steps;
  out->images = in.images;
  out->motion_error_latched = in.motion_error_latched;
}

}  // namespace rover::msg
