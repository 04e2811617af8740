#pragma once
/// @file
/// The terrain-assessment outputs of the mobility manager as plain values (idl/rover_apl.idl):
/// apl/goodness_map (GESTALT's grid) and apl/arc_votes (one arc-voting decision).
/// rover/msg/navigation_idl.hpp converts them; apl/nav_core fills them from its own types.
///
/// Grid: site frame (x north, y west, z up); cell (i, j) covers x in [origin_x + i r,
/// origin_x + (i + 1) r) and y likewise (r = resolution); row-major with row = j, so
/// index = j * width + i. Votes are MER's 8-bit votes (0 = forbidden, 255 = perfect).

#include <Eigen/Geometry>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"

namespace rover::msg {

/// apl/goodness_map (frame "site").
struct GoodnessMap {
  Time stamp;                           ///< capture time of the newest range data merged
  double origin_x = 0.0;                ///< [m] site x of cell (0, 0)'s corner
  double origin_y = 0.0;                ///< [m] site y of cell (0, 0)'s corner
  double resolution = 0.2;              ///< [m] cell side
  int width = 0;                        ///< cells along x (0..65535 on the wire)
  int height = 0;                       ///< cells along y (0..65535 on the wire)
  int unknown_goodness = 0;             ///< goodness of cells with no data (0..255)
  std::vector<std::uint8_t> goodness;   ///< per cell, 0 = obstacle
  std::vector<std::uint8_t> certainty;  ///< per cell, 0 = nothing known
  std::vector<std::uint8_t> flags;      ///< per cell: 1 known, 2 border of unknown, 4 FOV edge

  /// Ok when width and height are >= 0 and each cell array holds width x height entries. Errors
  /// name the array and both sizes ("apl/goodness_map certainty: 3 cells for 4 = 2 x 2").
  Status CheckSizes() const;
};

enum class CandidateKind : std::int32_t { kArc = 0, kPointTurn = 1 };

/// One candidate motion and its votes.
struct ArcVote {
  CandidateKind kind = CandidateKind::kArc;
  double curvature = 0.0;   ///< [1/m] arcs, positive turns left
  int direction = 1;        ///< arcs: +1 forward, -1 backward
  double turn_angle = 0.0;  ///< [rad] point turns, positive = left
  std::uint8_t hazard = 0;
  std::uint8_t waypoint = 0;
  std::uint8_t merged = 0;
};

/// apl/arc_votes (frame "site").
struct ArcVotes {
  Time stamp;
  std::uint32_t command_id = 0;
  std::uint32_t step = 0;
  /// The pose the votes were computed from (site frame).
  Eigen::Isometry3d rover_pose = Eigen::Isometry3d::Identity();
  std::vector<ArcVote> votes;  ///< at most kMaxArcVotes are carried
  int chosen = -1;             ///< index into votes; -1 = none (reached or no safe path)
};

/// The IDL bound of apl/arc_votes' votes sequence.
inline constexpr std::size_t kMaxArcVotes = 128;

}  // namespace rover::msg
