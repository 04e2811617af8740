#pragma once
/// @file
/// ArcEvaluator: GESTALT path selection (nav_core::ArcSelector), seed 002 steps 4-7 and seed 000
/// "Path Selection".
///
/// Candidates, in this order (the order matters for tie-breaking): num_forward_arcs forward
/// arcs and num_backward_arcs backward arcs with curvatures evenly spaced over
/// [-max_curvature, max_curvature] (ascending; one arc = straight), then num_point_turns turns in
/// place by j 360° / (num_point_turns + 1), j = 1..n, wrapped to (-180°, 180°] (ascending).
///
/// Hazard vote of a path (its cells C, arc_geometry.hpp, evaluated from plan_min_dist to
/// L = min(plan_max_dist, distance to goal)):
///   w(s) = 1 + (near_weight - 1) max(0, 1 - s / plan_max_dist)     (nearer cells weigh more)
///   goodness  = round(Σ_C w g_c / Σ_C w),  certainty = round(Σ_C w c_c / Σ_C w),
///   forbidden (0, 255) if any g_c < min_allowed_goodness.
/// Cells off the map count as unknown. A turn in place sweeps the cells at the rover centre.
///
/// Footprint check (footprint_check, options.hpp): the hazard cells (kCellHazard) within
/// plan_max_dist plus the footprint's reach of the rover, as rover-frame points, less those
/// already inside the grown footprint F = [min_x - m, max_x + m] x [min_y - m, max_y + m];
/// an arc's poses from s = 0 to L every cell_size / 2 (heading d k s), a turn's every 2.5° from
/// 0 to θ; the first s at which a point lies in F. A turn hit, or an arc hit at s <=
/// footprint_forbid_dist, forbids the candidate (0, 255); a later arc hit scales its goodness by
/// s / L (at least 1).
/// With footprint_straddle the test at a pose is against the contact parts instead of F: a
/// point hits when it lies within footprint_margin of a part's outline, and counts for the
/// rocker and body parts (non-zero clearance) only when it is tall (kCellTall). The points
/// skipped at the start are then those that already hit at the rover's pose.
///
/// Cost-to-go waypoint vote (cost_to_go): with the map's CostToGo toward the goal (clearance
/// = the footprint's half width + margin), each candidate's cost is
///   arc:  L + D(end of the arc at L),   turn by θ: L + 0.5 m |θ| + D(L straight ahead after it),
/// and its vote peak exp(-(cost - best)² / (2 cost_vote_sigma²)), peak waypoint_peak_toward
/// for forward arcs and waypoint_peak_away for backward arcs and turns (no camera looks back),
/// certainty waypoint_certainty; an unreachable end votes 0. When no candidate's end reaches
/// the goal, the MER vote below stands.
///
/// Waypoint vote (goal g in the rover frame, bearing β = atan2(g_y, g_x), k* = 2 g_y / |g|²):
///   the goal's direction is forward when |β| <= 90°, backward otherwise, except that after an
///   arc in direction d (request.last_direction) it stays d while the goal is within
///   direction_hysteresis of abeam on the other side (forward while |β| <= 90° + h, backward
///   while |β| >= 90° - h);
///   normal:  arc in the goal's direction
///                peak_toward exp(-(k - k*)² / (2 arc_vote_variance)),
///            arc in the other direction: peak_away exp(...same...),
///            turn by θ: peak_away exp(-wrap(θ - β)² / (2 turn_vote_variance));
///   back-up (|k*| > max_curvature, the goal inside a tightest turning circle: no arc reaches
///   it): the preferred arc is the tightest backward arc away from the goal, k_b = -sign(g_y)
///   max_curvature (it swings the heading toward the goal, a K-turn), and the highest
///   evaluation is scaled by backup_vote_scale (MER: halved, which in practice makes a turn in
///   place win):
///            backward arcs: scale peak_toward exp(-(k - k_b)² / (2 arc_vote_variance)),
///            forward arcs:  scale peak_away exp(-(k - clamp(k*))² / (2 arc_vote_variance)),
///            turns:         peak_toward exp(-wrap(θ - β)² / (2 turn_vote_variance));
///   certainty waypoint_certainty; reached (|g| <= tolerance): no choice.
///
/// Merge (per candidate, hazard h and waypoint p): min(h, p) by goodness when either is below
/// min_vote_goodness, else round((h_g h_c + p_g p_c) / (h_c + p_c)) with certainty max(h_c, p_c).
///
/// Choice: the candidate with the highest merged goodness (> 0); among ties, the middle of the
/// longest run of consecutive tied candidates of one group (forward arcs, backward arcs, turns;
/// the lower middle for an even run, the first run when runs tie). No candidate above 0: none.
///
/// Skip imaging: all_paths_safe when the choice is an arc and every arc of its direction lies
/// on known cells only with a hazard vote >= skip_imaging_goodness. Rear imaging: image_rear
/// when the best merged forward-arc vote is below min_fwd_threshold.

#include <vector>

#include "rover/apl/gestalt/arc_geometry.hpp"
#include "rover/apl/gestalt/options.hpp"
#include "rover/apl/nav_core/arc_selector.hpp"

namespace rover::apl::gestalt {

/// Hazard vote of one path, and whether all of its cells were known.
struct PathVote {
  nav_core::Vote vote;
  bool all_known = false;
  int cells = 0;
};

/// The merge rule of the file comment.
nav_core::Vote MergeVotes(const nav_core::Vote& hazard, const nav_core::Vote& waypoint,
                          int min_vote_goodness);
/// The choice rule of the file comment: `group[k]` names candidate k's group. Returns -1 when no
/// merged goodness is above 0. Preconditions: merged.size() == group.size().
int ChooseCandidate(const std::vector<nav_core::Vote>& merged, const std::vector<int>& group);

/// A footprint-check hazard cell as a rover-frame point (arc_evaluator.hpp file comment).
struct FootprintHazard {
  Eigen::Vector2d q = Eigen::Vector2d::Zero();  ///< [m] cell centre, rover frame
  bool tall = false;                            ///< kCellTall
};

class ArcEvaluator final : public nav_core::ArcSelector {
 public:
  /// Errors: InvalidArgument naming the field when options.Validate() fails.
  static Result<ArcEvaluator> Create(const GestaltOptions& options);

  Result<nav_core::ArcEvaluation> Evaluate(const nav_core::GoodnessMap& map,
                                           const nav_core::ArcRequest& request) const override;

  const GestaltOptions& options() const { return options_; }
  /// The candidates in order (length 0: it is set per evaluation).
  const std::vector<nav_core::Candidate>& candidates() const { return candidates_; }
  /// Group of each candidate: 0 forward arcs, 1 backward arcs, 2 turns.
  const std::vector<int>& groups() const { return groups_; }
  /// The hazard vote of a path over `cells` of `map`.
  PathVote HazardVote(const nav_core::GoodnessMap& map, const std::vector<PathCell>& cells) const;
  /// The footprint check's hazard points of `map` about `pose` (rover frame, see the file
  /// comment).
  std::vector<FootprintHazard> FootprintHazards(const nav_core::GoodnessMap& map,
                                                const Pose2& pose) const;
  /// [m] arc length (0 for a turn) of the first pose of `candidate` (arcs evaluated to
  /// `length`) whose grown footprint holds one of `hazards`; infinity when none does.
  double FirstFootprintHit(const nav_core::Candidate& candidate, double length,
                           const std::vector<FootprintHazard>& hazards) const;

 private:
  explicit ArcEvaluator(const GestaltOptions& options);

  GestaltOptions options_;
  std::vector<nav_core::Candidate> candidates_;
  std::vector<int> groups_;
};

}  // namespace rover::apl::gestalt
