#include "rover/msg/navigation_idl.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <string>

#include "idl_enum.hpp"
#include "rover/base/format.hpp"
#include "rover/msg/pose_idl.hpp"

namespace rover::msg {

using internal::ClampSize;

static_assert(rover_apl_CANDIDATE_ARC == static_cast<int>(CandidateKind::kArc));
static_assert(rover_apl_CANDIDATE_POINT_TURN == static_cast<int>(CandidateKind::kPointTurn));

namespace {

std::vector<std::uint8_t> Copy(const auto& seq) {
  const auto view = idl::View(seq);
  return std::vector<std::uint8_t>(view.begin(), view.end());
}

}  // namespace

Status GoodnessMapToIdl(const GoodnessMap& in, rover_apl_GoodnessMap* out) {
  ROVER_RETURN_IF_ERROR(in.CheckSizes());
  out->header.stamp_ns = in.stamp.ns;
  out->origin_x = in.origin_x;
  out->origin_y = in.origin_y;
  out->resolution = in.resolution;
  out->width = ClampSize(in.width);
  out->height = ClampSize(in.height);
  out->unknown_goodness = static_cast<std::uint8_t>(std::clamp(in.unknown_goodness, 0, 255));
  idl::BorrowSequence(out->goodness, std::span<const std::uint8_t>(in.goodness));
  idl::BorrowSequence(out->certainty, std::span<const std::uint8_t>(in.certainty));
  idl::BorrowSequence(out->flags, std::span<const std::uint8_t>(in.flags));
  return Status::Ok();
}

Result<GoodnessMap> GoodnessMapFromIdl(const rover_apl_GoodnessMap& in) {
  GoodnessMap m;
  m.stamp = Time{in.header.stamp_ns};
  m.origin_x = in.origin_x;
  m.origin_y = in.origin_y;
  m.resolution = in.resolution;
  m.width = in.width;
  m.height = in.height;
  m.unknown_goodness = in.unknown_goodness;
  m.goodness = Copy(in.goodness);
  m.certainty = Copy(in.certainty);
  m.flags = Copy(in.flags);
  ROVER_RETURN_IF_ERROR(m.CheckSizes());
  return m;
}

ArcVotesMessage& ArcVotesMessage::operator=(const ArcVotesMessage& o) {
  msg = o.msg;
  votes = o.votes;
  Repoint();
  return *this;
}

void ArcVotesMessage::Repoint() { idl::BorrowSequence(msg.votes, votes); }

void ArcVotesToIdl(const ArcVotes& in, ArcVotesMessage* out) {
  rover_apl_ArcVotes& m = out->msg;
  m.header.stamp_ns = in.stamp.ns;
  m.command_id = in.command_id;
  m.step = in.step;
  IsometryToIdl(in.rover_pose, &m.rover_pose);
  const std::size_t n = std::min(in.votes.size(), kMaxArcVotes);
  out->votes.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const ArcVote& v = in.votes[i];
    rover_apl_ArcVote w{};
    idl::SetRawEnum(&w.kind, static_cast<std::int32_t>(v.kind));
    w.curvature = v.curvature;
    w.direction = static_cast<std::int8_t>(v.direction < 0 ? -1 : 1);
    w.turn_angle = v.turn_angle;
    w.hazard = v.hazard;
    w.waypoint = v.waypoint;
    w.merged = v.merged;
    out->votes.push_back(w);
  }
  m.chosen = static_cast<std::int16_t>(
      in.chosen >= 0 && static_cast<std::size_t>(in.chosen) < n ? in.chosen : -1);
  out->Repoint();
}

Result<ArcVotes> ArcVotesFromIdl(const rover_apl_ArcVotes& in) {
  ArcVotes a;
  a.stamp = Time{in.header.stamp_ns};
  a.command_id = in.command_id;
  a.step = in.step;
  const rover_Quaternion& qi = in.rover_pose.orientation;
  const double norm = Eigen::Quaterniond(qi.w, qi.x, qi.y, qi.z).norm();
  if (!(std::abs(norm - 1.0) <= 1e-3)) {
    return InvalidArgument("apl/arc_votes rover_pose orientation is not a unit quaternion (norm " +
                           FormatNumber(norm) + ")");
  }
  a.rover_pose = IsometryFromIdl(in.rover_pose);
  const auto votes = idl::View(in.votes);
  for (std::size_t i = 0; i < votes.size(); ++i) {
    const rover_apl_ArcVote& w = votes[i];
    ArcVote v;
    ROVER_ASSIGN_OR_RETURN(
        v.kind,
        internal::EnumFromIdl<CandidateKind>(
            w.kind, 2, "apl/arc_votes votes[" + std::to_string(i) + "].kind", "CandidateKind"));
    v.curvature = w.curvature;
    v.direction = w.direction;
    v.turn_angle = w.turn_angle;
    v.hazard = w.hazard;
    v.waypoint = w.waypoint;
    v.merged = w.merged;
    a.votes.push_back(v);
  }
  if (in.chosen < -1 || in.chosen >= static_cast<int>(votes.size())) {
    return InvalidArgument("apl/arc_votes chosen = " + std::to_string(in.chosen) +
                           " is outside -1.." + std::to_string(static_cast<int>(votes.size()) - 1));
  }
  a.chosen = in.chosen;
  return a;
}

}  // namespace rover::msg
