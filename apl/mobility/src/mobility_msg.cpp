#include "mobility_msg.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "rover/runtime/dds.hpp"

namespace rover::apl::mobility::msg {
namespace {

template <class E, class I>
E Cast(I v) {
  return static_cast<E>(static_cast<int>(v));
}

std::uint8_t Byte(int v) { return static_cast<std::uint8_t>(std::clamp(v, 0, 255)); }

}  // namespace

Eigen::Isometry3d IsometryFromIdl(const rover_Pose3& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  Eigen::Quaterniond q(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z);
  const double n = q.norm();
  if (!(n > 1e-9) || !std::isfinite(n)) {
    t.linear().setConstant(std::numeric_limits<double>::quiet_NaN());
  } else {
    t.linear() = (Eigen::Quaterniond(q.coeffs() / n)).toRotationMatrix();
  }
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  return t;
}

rover_Pose3 IsometryToIdl(const Eigen::Isometry3d& t) {
  const Eigen::Quaterniond q(t.linear());
  rover_Pose3 p{};
  p.position = {t.translation().x(), t.translation().y(), t.translation().z()};
  p.orientation = {q.w(), q.x(), q.y(), q.z()};
  return p;
}

// ---- command -----------------------------------------------------------------------------------

MobilityCommand CommandFromIdl(const rover_apl_MobilityCommand& m) {
  MobilityCommand c;
  c.command_id = m.command_id;
  c.mode = Cast<Mode>(m.mode);
  c.goal = Eigen::Vector3d(m.goal.x, m.goal.y, m.goal.z);
  c.tolerance = m.tolerance;
  c.time_budget_s = m.time_budget_s;
  for (const auto& p : dds::View(m.primitives)) {
    c.primitives.push_back({Cast<PrimitiveKind>(p.primitive), p.curvature, p.distance, p.angle});
  }
  for (const auto& z : dds::View(m.keep_out)) {
    KeepOutZone k;
    k.name = std::string(z.name, strnlen(z.name, sizeof(z.name)));
    for (const auto& v : dds::View(z.vertices)) k.vertices.emplace_back(v.x, v.y);
    c.keep_out.push_back(std::move(k));
  }
  c.think = Cast<ThinkMode>(m.think);
  c.max_tilt = m.max_tilt;
  c.min_northerly_tilt = m.min_northerly_tilt;
  c.lmst_end_h = m.lmst_end_h;
  c.max_steps = m.max_steps;
  return c;
}

CommandMessage& CommandMessage::operator=(const CommandMessage& o) {
  msg = o.msg;
  primitives = o.primitives;
  zones = o.zones;
  vertices = o.vertices;
  Repoint();
  return *this;
}

void CommandMessage::Repoint() {
  for (std::size_t i = 0; i < zones.size(); ++i)
    dds::BorrowSequence(zones[i].vertices, vertices[i]);
  dds::BorrowSequence(msg.primitives, primitives);
  dds::BorrowSequence(msg.keep_out, zones);
}

CommandMessage CommandToIdl(const MobilityCommand& c, std::int64_t stamp_ns) {
  CommandMessage out;
  out.msg.header.stamp_ns = stamp_ns;
  out.msg.command_id = c.command_id;
  out.msg.mode = Cast<rover_apl_MobilityMode>(c.mode);
  out.msg.goal = {c.goal.x(), c.goal.y(), c.goal.z()};
  out.msg.tolerance = c.tolerance;
  out.msg.time_budget_s = c.time_budget_s;
  for (const Primitive& p : c.primitives) {
    out.primitives.push_back(
        {Cast<rover_dl_DrivePrimitive>(p.kind), p.curvature, p.distance, p.angle});
  }
  for (const KeepOutZone& z : c.keep_out) {
    rover_apl_KeepOutZone k{};
    dds::CopyString(k.name, z.name);
    out.zones.push_back(k);
    std::vector<rover_apl_Point2> v;
    for (const auto& p : z.vertices) v.push_back({p.x(), p.y()});
    out.vertices.push_back(std::move(v));
  }
  out.msg.think = Cast<rover_apl_ThinkMode>(c.think);
  out.msg.max_tilt = c.max_tilt;
  out.msg.min_northerly_tilt = c.min_northerly_tilt;
  out.msg.lmst_end_h = c.lmst_end_h;
  out.msg.max_steps = static_cast<std::uint16_t>(std::clamp(c.max_steps, 0, 65535));
  out.Repoint();
  return out;
}

// ---- status ------------------------------------------------------------------------------------

rover_apl_MobilityStatus StatusToIdl(const MobilityStatus& s) {
  rover_apl_MobilityStatus m{};
  m.header.stamp_ns = s.stamp.ns;
  m.command_id = s.command_id;
  m.mode = Cast<rover_apl_MobilityMode>(s.mode);
  m.state = Cast<rover_apl_MobilityState>(s.state);
  m.fault_class = Cast<rover_apl_FaultClass>(s.fault_class);
  m.fault = Cast<rover_apl_MobilityFault>(s.fault);
  dds::CopyString(m.message, s.message);
  m.distance_to_goal = s.distance_to_goal;
  m.distance_driven = s.distance_driven;
  m.steps = s.steps;
  m.images = s.images;
  m.motion_error_latched = s.motion_error_latched;
  return m;
}

MobilityStatus StatusFromIdl(const rover_apl_MobilityStatus& m) {
  MobilityStatus s;
  s.stamp = Time{m.header.stamp_ns};
  s.command_id = m.command_id;
  s.mode = Cast<Mode>(m.mode);
  s.state = Cast<State>(m.state);
  s.fault_class = Cast<FaultClass>(m.fault_class);
  s.fault = Cast<Fault>(m.fault);
  s.message = std::string(m.message, strnlen(m.message, sizeof(m.message)));
  s.distance_to_goal = m.distance_to_goal;
  s.distance_driven = m.distance_driven;
  s.steps = m.steps;
  s.images = m.images;
  s.motion_error_latched = m.motion_error_latched;
  return s;
}

// ---- goodness map, arc votes -------------------------------------------------------------------

GoodnessMapMessage& GoodnessMapMessage::operator=(const GoodnessMapMessage& o) {
  msg = o.msg;
  goodness = o.goodness;
  certainty = o.certainty;
  flags = o.flags;
  Repoint();
  return *this;
}

void GoodnessMapMessage::Repoint() {
  dds::BorrowSequence(msg.goodness, goodness);
  dds::BorrowSequence(msg.certainty, certainty);
  dds::BorrowSequence(msg.flags, flags);
}

GoodnessMapMessage GoodnessMapToIdl(const nav_core::GoodnessMap& map) {
  GoodnessMapMessage out;
  out.msg.header.stamp_ns = map.stamp.ns;
  dds::CopyString(out.msg.header.frame_id, "site");
  out.msg.origin_x = map.origin_x;
  out.msg.origin_y = map.origin_y;
  out.msg.resolution = map.resolution;
  out.msg.width = static_cast<std::uint16_t>(std::clamp(map.width, 0, 65535));
  out.msg.height = static_cast<std::uint16_t>(std::clamp(map.height, 0, 65535));
  out.msg.unknown_goodness = Byte(map.unknown_goodness);
  out.goodness = map.goodness;
  out.certainty = map.certainty;
  out.flags = map.flags;
  out.Repoint();
  return out;
}

Result<nav_core::GoodnessMap> GoodnessMapFromIdl(const rover_apl_GoodnessMap& m) {
  nav_core::GoodnessMap map;
  map.origin_x = m.origin_x;
  map.origin_y = m.origin_y;
  map.resolution = m.resolution;
  map.width = m.width;
  map.height = m.height;
  map.unknown_goodness = m.unknown_goodness;
  map.stamp = Time{m.header.stamp_ns};
  const std::size_t n = map.cell_count();
  const auto check = [n](const char* name, std::size_t got) -> Status {
    if (got == n) return Status::Ok();
    return InvalidArgument(std::string("GoodnessMap.") + name + ": " + std::to_string(got) +
                           " cells for " + std::to_string(n) + " = width x height");
  };
  ROVER_RETURN_IF_ERROR(check("goodness", m.goodness._length));
  ROVER_RETURN_IF_ERROR(check("certainty", m.certainty._length));
  ROVER_RETURN_IF_ERROR(check("flags", m.flags._length));
  const auto g = dds::View(m.goodness), c = dds::View(m.certainty), f = dds::View(m.flags);
  map.goodness.assign(g.begin(), g.end());
  map.certainty.assign(c.begin(), c.end());
  map.flags.assign(f.begin(), f.end());
  return map;
}

ArcVotesMessage& ArcVotesMessage::operator=(const ArcVotesMessage& o) {
  msg = o.msg;
  votes = o.votes;
  Repoint();
  return *this;
}

void ArcVotesMessage::Repoint() { dds::BorrowSequence(msg.votes, votes); }

ArcVotesMessage ArcVotesToIdl(const ArcVotesSnapshot& s) {
  ArcVotesMessage out;
  out.msg.header.stamp_ns = s.stamp.ns;
  dds::CopyString(out.msg.header.frame_id, "site");
  out.msg.command_id = s.command_id;
  out.msg.step = s.step;
  out.msg.rover_pose = IsometryToIdl(s.site_from_rover);
  const auto& e = s.evaluation;
  const std::size_t n = std::min<std::size_t>(e.candidates.size(), 128);
  for (std::size_t i = 0; i < n; ++i) {
    const nav_core::Candidate& c = e.candidates[i];
    rover_apl_ArcVote v{};
    v.kind = c.kind == nav_core::MotionKind::kArc ? rover_apl_CANDIDATE_ARC
                                                  : rover_apl_CANDIDATE_POINT_TURN;
    v.curvature = c.curvature;
    v.direction = static_cast<std::int8_t>(c.direction < 0 ? -1 : 1);
    v.turn_angle = c.turn_angle;
    v.hazard = i < e.hazard.size() ? Byte(e.hazard[i].goodness) : 0;
    v.waypoint = i < e.waypoint.size() ? Byte(e.waypoint[i].goodness) : 0;
    v.merged = i < e.merged.size() ? Byte(e.merged[i].goodness) : 0;
    out.votes.push_back(v);
  }
  out.msg.chosen = static_cast<std::int16_t>(
      e.chosen >= 0 && static_cast<std::size_t>(e.chosen) < n ? e.chosen : -1);
  out.Repoint();
  return out;
}

// ---- device layer ------------------------------------------------------------------------------

Result<nav_core::RangeScan> RangeScanFromIdl(const rover_dl_RangeImage& m) {
  nav_core::RangeScan s;
  s.width = m.width;
  s.height = m.height;
  const std::size_t n = s.pixel_count();
  if (m.xyz._length != 3 * n) {
    return InvalidArgument("RangeImage.xyz: " + std::to_string(m.xyz._length) + " floats for " +
                           std::to_string(m.width) + " x " + std::to_string(m.height) +
                           " pixels (need " + std::to_string(3 * n) + ")");
  }
  if (m.valid._length != n) {
    return InvalidArgument("RangeImage.valid: " + std::to_string(m.valid._length) + " bytes for " +
                           std::to_string(n) + " pixels");
  }
  const auto xyz = dds::View(m.xyz);
  const auto valid = dds::View(m.valid);
  s.xyz.assign(xyz.begin(), xyz.end());
  s.valid.assign(valid.begin(), valid.end());
  s.capture_time = Time{m.header.stamp_ns};
  s.site_from_rover = IsometryFromIdl(m.rover_pose);
  s.camera = std::string(CameraName(CameraFromIdl(m.camera)));
  return s;
}

Camera CameraFromIdl(rover_CameraId c) { return Cast<Camera>(c); }
rover_CameraId CameraToIdl(Camera c) { return Cast<rover_CameraId>(c); }

rover_dl_DriveCommand DriveCommandToIdl(const DriveRequest& d) {
  rover_dl_DriveCommand m{};
  m.header.stamp_ns = d.stamp.ns;
  m.command_id = d.command_id;
  m.primitive = Cast<rover_dl_DrivePrimitive>(d.kind);
  m.curvature = d.curvature;
  m.distance = d.distance;
  m.angle = d.angle;
  m.speed = d.speed;
  m.timeout_s = d.timeout_s;
  return m;
}

DriveRequest DriveCommandFromIdl(const rover_dl_DriveCommand& m) {
  DriveRequest d;
  d.stamp = Time{m.header.stamp_ns};
  d.command_id = m.command_id;
  d.kind = Cast<PrimitiveKind>(m.primitive);
  d.curvature = m.curvature;
  d.distance = m.distance;
  d.angle = m.angle;
  d.speed = m.speed;
  d.timeout_s = m.timeout_s;
  return d;
}

DriveReport DriveStatusFromIdl(const rover_dl_DriveStatus& m) {
  DriveReport r;
  r.command_id = m.command_id;
  r.state = Cast<DriveState>(m.state);
  r.termination = Cast<DriveTermination>(m.termination);
  r.distance_done = m.distance_done;
  r.message = std::string(m.message, strnlen(m.message, sizeof(m.message)));
  return r;
}

rover_dl_RangeRequest RangeRequestToIdl(const RangeRequest& r) {
  rover_dl_RangeRequest m{};
  m.header.stamp_ns = r.stamp.ns;
  m.request_id = r.request_id;
  m.camera = CameraToIdl(r.camera);
  m.width = static_cast<std::uint16_t>(std::clamp(r.width, 0, 65535));
  return m;
}

rover_dl_MastCommand MastCommandToIdl(const MastRequest& r) {
  rover_dl_MastCommand m{};
  m.header.stamp_ns = r.stamp.ns;
  m.command_id = r.command_id;
  m.pointing = r.look_at ? rover_dl_MAST_POINT_LOOK_AT : rover_dl_MAST_POINT_ANGLES;
  m.pan = r.pan;
  m.tilt = r.tilt;
  m.look_at = {r.target.x(), r.target.y(), r.target.z()};
  return m;
}

MastReport MastStatusFromIdl(const rover_dl_MastStatus& m) {
  return {m.command_id, Cast<MastState>(m.state)};
}

PoseSample PoseFromIdl(const rover_dl_PoseEstimate& m) {
  PoseSample p;
  p.stamp = Time{m.header.stamp_ns};
  p.site_from_rover = IsometryFromIdl(m.pose);
  return p;
}

std::optional<VisOdomResult> VisOdomFromIdl(const rover_dl_RelativePose& m) {
  if (m.source != rover_dl_SOURCE_VISUAL_ODOMETRY) return std::nullopt;
  return VisOdomResult{Time{m.t_to_ns}, m.status == rover_dl_RELPOSE_CONVERGED};
}

}  // namespace rover::apl::mobility::msg
