#pragma once
/// @file
/// Conversions between the mobility manager's plain types and the IDL messages (pure functions,
/// no service state; core/msg will take them over). IDL enums map by value (the library's
/// enums keep the IDL's order); values outside an IDL enumeration are kept as is so the manager
/// can reject them with a message naming the field.
///
/// Messages with sequences come with a holder that owns the element storage the message points
/// at (dds::BorrowSequence): keep the holder alive until the write returns; copying a holder
/// re-points its message at the copy's storage.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rover/apl/mobility/mobility_manager.hpp"
#include "rover/idl/types.hpp"

namespace rover::apl::mobility::msg {

/// dl/pose, dl/range_image poses: position + (w, x, y, z) quaternion, normalised; a zero or
/// non-finite quaternion gives a non-finite rotation (the manager reports it as SAPP / IMG).
Eigen::Isometry3d IsometryFromIdl(const rover_Pose3& p);
rover_Pose3 IsometryToIdl(const Eigen::Isometry3d& t);

MobilityCommand CommandFromIdl(const rover_apl_MobilityCommand& m);
/// A MobilityCommand message and the storage its sequences point at (tests, tools).
struct CommandMessage {
  rover_apl_MobilityCommand msg{};
  std::vector<rover_apl_MobilityPrimitive> primitives;
  std::vector<rover_apl_KeepOutZone> zones;
  std::vector<std::vector<rover_apl_Point2>> vertices;
  CommandMessage() = default;
  CommandMessage(const CommandMessage& o) { *this = o; }
  CommandMessage& operator=(const CommandMessage& o);
  void Repoint();
};
CommandMessage CommandToIdl(const MobilityCommand& c, std::int64_t stamp_ns);

rover_apl_MobilityStatus StatusToIdl(const MobilityStatus& s);
MobilityStatus StatusFromIdl(const rover_apl_MobilityStatus& m);

/// apl/goodness_map (frame "site").
struct GoodnessMapMessage {
  rover_apl_GoodnessMap msg{};
  std::vector<std::uint8_t> goodness, certainty, flags;
  GoodnessMapMessage() = default;
  GoodnessMapMessage(const GoodnessMapMessage& o) { *this = o; }
  GoodnessMapMessage& operator=(const GoodnessMapMessage& o);
  void Repoint();
};
GoodnessMapMessage GoodnessMapToIdl(const nav_core::GoodnessMap& map);
/// The cell arrays must hold width * height entries: else InvalidArgument naming the field.
Result<nav_core::GoodnessMap> GoodnessMapFromIdl(const rover_apl_GoodnessMap& m);

/// apl/arc_votes (at most 128 candidates are carried; `chosen` beyond them becomes -1).
struct ArcVotesMessage {
  rover_apl_ArcVotes msg{};
  std::vector<rover_apl_ArcVote> votes;
  ArcVotesMessage() = default;
  ArcVotesMessage(const ArcVotesMessage& o) { *this = o; }
  ArcVotesMessage& operator=(const ArcVotesMessage& o);
  void Repoint();
};
ArcVotesMessage ArcVotesToIdl(const ArcVotesSnapshot& s);

/// dl/range_image -> RangeScan. Errors: InvalidArgument when xyz or valid do not match
/// width x height (naming the field and sizes).
Result<nav_core::RangeScan> RangeScanFromIdl(const rover_dl_RangeImage& m);
Camera CameraFromIdl(rover_CameraId c);
rover_CameraId CameraToIdl(Camera c);

rover_dl_DriveCommand DriveCommandToIdl(const DriveRequest& d);
DriveRequest DriveCommandFromIdl(const rover_dl_DriveCommand& m);
DriveReport DriveStatusFromIdl(const rover_dl_DriveStatus& m);
rover_dl_RangeRequest RangeRequestToIdl(const RangeRequest& r);
rover_dl_MastCommand MastCommandToIdl(const MastRequest& r);
MastReport MastStatusFromIdl(const rover_dl_MastStatus& m);
PoseSample PoseFromIdl(const rover_dl_PoseEstimate& m);
/// Only visual-odometry samples count (nullopt for other sources); converged = CONVERGED.
std::optional<VisOdomResult> VisOdomFromIdl(const rover_dl_RelativePose& m);

}  // namespace rover::apl::mobility::msg
