#pragma once
/// @file
/// apl/goodness_map and apl/arc_votes <-> their idlc C structs (conventions: see
/// rover/msg/camera_idl.hpp). Both are written with header.frame_id "site" by their service.

#include <vector>

#include "rover/base/status.hpp"
#include "rover/idl/types.hpp"
#include "rover/msg/navigation.hpp"

namespace rover::msg {

/// The cell arrays borrow `in`'s vectors (they must outlive the write); width and height are
/// clamped to 0..65535, unknown_goodness to 0..255. Errors: the sizes of
/// GoodnessMap::CheckSizes (nothing is written to `out` then).
Status GoodnessMapToIdl(const GoodnessMap& in, rover_apl_GoodnessMap* out);
/// Copies the arrays. Errors: cell arrays whose sizes disagree with width x height (naming the
/// array and both sizes).
Result<GoodnessMap> GoodnessMapFromIdl(const rover_apl_GoodnessMap& in);

/// An apl/arc_votes C struct and the storage its votes point at (see MobilityCommandMessage).
struct ArcVotesMessage {
  rover_apl_ArcVotes msg{};
  std::vector<rover_apl_ArcVote> votes;

  ArcVotesMessage() = default;
  ArcVotesMessage(const ArcVotesMessage& o) { *this = o; }
  ArcVotesMessage& operator=(const ArcVotesMessage& o);
  void Repoint();
};

/// The first kMaxArcVotes votes are carried; a `chosen` outside them becomes -1. Directions are
/// sent as their sign (+1 or -1).
void ArcVotesToIdl(const ArcVotes& in, ArcVotesMessage* out);
/// Copies the votes. Errors: an unknown candidate kind (naming the vote), a chosen index outside
/// -1 .. votes - 1, a rover_pose quaternion whose norm is not within 1e-3 of 1.
Result<ArcVotes> ArcVotesFromIdl(const rover_apl_ArcVotes& in);

}  // namespace rover::msg
