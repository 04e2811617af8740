#pragma once
/// @file
/// ArcSelector: chooses the next drive primitive toward a goal from a goodness map (MER's Path
/// Selection, GESTALT's second half). It is given the map rather than owning it, so any
/// TerrainAssessor can feed any selector.
///
/// Candidates are MER's drive primitives: arcs of constant curvature driven forward or backward
/// (straight lines are k = 0) and turns in place. Each gets a hazard vote (how safe its swept
/// path is), a waypoint vote (how well it heads for the goal) and their merge; the choice is the
/// best merged vote. Votes are MER's 8-bit (goodness, certainty) pairs, 0..255.
///
/// Frames: the request's pose and goal are in the site frame (x north, y west, z up); a
/// candidate's curvature is signed in the rover frame (positive = centre of the turn on the left,
/// i.e. heading increases when driving forward), its turn angle positive = counter-clockwise
/// seen from above (to the left). Metres, radians.

#include <Eigen/Geometry>
#include <optional>
#include <string>
#include <vector>

#include "rover/apl/nav_core/goodness_map.hpp"
#include "rover/apl/nav_core/terrain_assessor.hpp"
#include "rover/base/range_check.hpp"
#include "rover/base/status.hpp"

namespace rover::apl::nav_core {

enum class MotionKind {
  kArc,        ///< drive along a circle of `curvature`, `direction` +1 forward / -1 backward
  kPointTurn,  ///< turn in place by `turn_angle`
};

struct Candidate {
  MotionKind kind = MotionKind::kArc;
  double curvature = 0.0;   ///< [1/m] arcs
  int direction = 1;        ///< arcs: +1 forward, -1 backward
  double length = 0.0;      ///< [m] arcs: path length that was evaluated
  double turn_angle = 0.0;  ///< [rad] point turns
};

/// An 8-bit (goodness, certainty) pair.
struct Vote {
  int goodness = 0;   ///< 0..255, 0 = forbidden
  int certainty = 0;  ///< 0..255
};

struct ArcRequest {
  Eigen::Isometry3d site_from_rover = Eigen::Isometry3d::Identity();  ///< current pose
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();                     ///< [m] site x, y of the goal
  double goal_tolerance = 0.0;  ///< [m] radius counted as arrived, >= 0
  /// Direction of the arc driven last: +1 forward, -1 backward, 0 none yet (selectors may keep
  /// driving that way while the goal is near abeam instead of reversing at once).
  int last_direction = 0;
  /// [m] the most of the chosen path the caller drives before it asks again; 0 = not said.
  /// Planners that check their paths check at least this far (without it, as far as the goal's
  /// straight-line distance: no caller drives past the goal).
  double drive_length = 0.0;

  /// OK, or InvalidArgument naming the field: a non-finite pose or goal, a negative tolerance
  /// or drive_length, last_direction outside {-1, 0, 1}.
  Status Validate() const {
    ROVER_RETURN_IF_ERROR(CheckPoseFinite("ArcRequest.site_from_rover", site_from_rover));
    ROVER_RETURN_IF_ERROR(CheckFinite("ArcRequest.goal.x", goal.x()));
    ROVER_RETURN_IF_ERROR(CheckFinite("ArcRequest.goal.y", goal.y()));
    ROVER_RETURN_IF_ERROR(CheckNonNegative("ArcRequest.goal_tolerance", goal_tolerance, "m"));
    ROVER_RETURN_IF_ERROR(CheckNonNegative("ArcRequest.drive_length", drive_length, "m"));
    return CheckIntRange("ArcRequest.last_direction", last_direction, -1, 1);
  }
};

/// How the selector read the goal.
enum class GoalMode {
  kNormal,   ///< votes centred on the arc that passes through the goal
  kReached,  ///< within tolerance: nothing to drive (chosen = -1)
  kBackUp,   ///< goal inside the tightest turning circle: K-turn (back-up arc, vote halved)
};

struct ArcEvaluation {
  std::vector<Candidate> candidates;
  std::vector<Vote> hazard;    ///< per candidate
  std::vector<Vote> waypoint;  ///< per candidate
  std::vector<Vote> merged;    ///< per candidate
  /// Per candidate, why it was forbidden ("wheel_lf 0.03 m from a wheel hazard"), for planners
  /// that say (the ENav-class tree); empty otherwise.
  std::vector<std::string> why;
  int chosen = -1;             ///< index into candidates; -1 = none (reached, or no safe path)
  GoalMode mode = GoalMode::kNormal;
  double distance_to_goal = 0.0;  ///< [m] horizontal
  /// Every candidate path in the chosen direction lies on known cells with a hazard vote at or
  /// above the selector's skip threshold: the next step may skip imaging (MER's "skip Terrain
  /// Assessment when the existing data already ensure that all paths are safe").
  bool all_paths_safe = false;
  /// The best merged forward vote is below the selector's forward-imaging threshold: image
  /// behind the rover too before the next step (MER's min-fwd-threshold).
  bool image_rear = false;

  /// The whole chosen path, first segment first (a turn in place, then arcs), for planners
  /// that plan several segments ahead (the ENav-class tree); empty for single-arc selectors.
  /// Only the first segment (choice()) is driven before the next decision.
  std::vector<Candidate> path;
  /// [m] the most of the chosen path the planner cleared for this step when that is less than
  /// the request's drive_length (ENav: a last step cleared only into the goal's tolerance, not
  /// to the goal); 0 = the request's drive_length.
  double max_drive = 0.0;
  int candidates_ranked = 0;  ///< paths costed (multi-segment planners; else candidates.size())
  int clearance_checks = 0;   ///< paths whose clearance was checked before one passed

  bool has_choice() const { return chosen >= 0; }
  const Candidate& choice() const { return candidates[static_cast<std::size_t>(chosen)]; }
};

class ArcSelector {
 public:
  virtual ~ArcSelector() = default;
  /// Votes on every candidate from `request`'s pose toward its goal over `map`.
  /// Errors: InvalidArgument for a non-finite pose or goal or a negative tolerance.
  virtual Result<ArcEvaluation> Evaluate(const GoodnessMap& map,
                                         const ArcRequest& request) const = 0;
  /// What the mobility manager calls: the same over everything `terrain` holds. Selectors that
  /// need more than goodness (heights: TerrainAssessor::height_map()) override it and return
  /// FailedPrecondition when the assessor lacks it; the default reads the goodness map only.
  virtual Result<ArcEvaluation> Plan(const TerrainAssessor& terrain,
                                     const ArcRequest& request) const {
    return Evaluate(terrain.goodness_map(), request);
  }
  /// Whether Plan() checks the chosen path as far as ArcRequest::drive_length (ENav does; arc
  /// voting judges its arcs by goodness only). The mobility manager lets only such a planner's
  /// last step run past step_length, to the goal.
  virtual bool ChecksDriveLength() const { return false; }
  /// Whether Plan() clearance-checks every turn in place it may need itself (ENav: the tree
  /// holds every turn, a route's turns are checked). The mobility manager then adds no turn of
  /// its own (MER's limit-cycle turn, the goal-facing turn inside the turning circle): made
  /// without the planner's check, such a turn only risks the rover.
  virtual bool ChecksTurns() const { return false; }
  /// The planner's cost-to-go [m-equivalent] from site point `xy` to `goal` over what it knows
  /// after its latest Plan() (remembered map, routes around hazards), or nullopt when it keeps
  /// none for that goal (arc voting) or `xy` is blocked, unreached or off its map. The mobility
  /// manager measures progress along it: a detour round a rock field gets no nearer the goal
  /// in a straight line for many steps, yet runs down the cost-to-go.
  virtual std::optional<double> CostToGo(const Eigen::Vector2d& goal,
                                         const Eigen::Vector2d& xy) const {
    (void)goal;
    (void)xy;
    return std::nullopt;
  }
};

}  // namespace rover::apl::nav_core
