#pragma once
/// @file
/// EnavPlanner: an ENav-class local planner (after Mars 2020's Enhanced Navigation: a tree of
/// candidate paths ranked by a cheap cost and a cost-to-go, then an approximate clearance check
/// on the best few, in rank order), behind nav_core's ArcSelector so the mobility manager drives
/// it as it drives GESTALT's arc voting. It needs heights: Plan() requires apl/enav's
/// HeightTerrain as the manager's assessor (FailedPrecondition otherwise).
///
/// The tree (site frame, from the request's pose): a turn in place by one of num_turns headings
/// evenly over the circle (0 = none), then an arc of first_length at one of num_curvatures
/// curvatures evenly in [-k_max, k_max] (k_max = the rover description's MaxCurvature()), then a
/// second arc of second_length at each curvature again: 24 x 9 x 9 = 1,944 paths over 5.5 m by
/// default.
///
/// Cheap cost of a path (metres of driving on open known ground):
///   J = turn_cost |turn| + sum over samples of factor(centre) ds + curvature_cost sum |k| L
///       + CostToGo(end)   (- commit_bonus for the previous choice continued)
/// with CostToGoField's factor and cost (a blocked sample discards the path). A path whose centre
/// comes within the goal tolerance ends there (J then has no cost-to-go term), so near the goal
/// short paths win.
///
/// When the cost-to-go reaches no path of the tree (the rover in a pocket its heading-blind
/// configuration space closes), the tree is ranked "blind": blocked cells priced at 10 per metre
/// and the straight-line distance (x unknown_cost_factor) in place of the cost-to-go.
///
/// Check in rank order (at most max_checks): the turn (poses every 10 deg of it) and every
/// sample of the path through ClearanceChecker (ACE within ace_length of the start, the part
/// discs all along); within known_length no more than max_unknown_fraction of the wheel patches
/// unseen. The first path that passes is the choice; a failing turn or first segment fails
/// every path that shares it without being checked again. If none of the forward paths passes,
/// backward arcs of first_length (one per curvature) are checked, ranked by cost-to-go at their
/// end (a K-turn's first half). No path passing: if the rover stands on the arc of the last
/// choice (after its turn; within 0.15 m and 0.15 rad, at least 0.1 m along), the choice is that
/// arc backward to where it began, unchecked (the rover's parts swept that ground; the map
/// beside a wheel is what changed); back there, nothing is left to retrace; else no choice
/// (NOPATH).
///
/// Route search (route_max_expansions > 0; off by default): RouteSearch's cheapest way over
/// poses to the goal, tried at every decision (route_first) or only when no tree path passes;
/// the step is a turn toward the farthest route pose (within route_lookahead, before the route
/// reverses) whose straight line keeps route_margin, lies on seen ground and passes CheckPath.
/// The route is kept while the rover is on it and it still fits. apl/enav/README.md.
///
/// A goal on a seen rock taller than the belly clearance (a body-class hazard cell) gets no
/// choice at once, `why` saying so (the manager's NOPATH, a goal error), unless the rover is
/// within first_length of reaching it.
///
/// What the manager drives is the first segment only (choice()): the turn when there is one,
/// else the first arc for at most its step length; the next decision replans from the new pose.
/// `path` carries the whole chosen path; candidates/votes carry the checked paths' first
/// segments in rank order (hazard vote 255 passed / 0 failed; waypoint vote 255 J_best / J).

#include <optional>
#include <vector>

#include "rover/apl/enav/clearance.hpp"
#include "rover/apl/enav/cost_to_go.hpp"
#include "rover/apl/enav/route_search.hpp"
#include "rover/apl/enav/height_terrain.hpp"
#include "rover/apl/nav_core/arc_selector.hpp"

namespace rover::apl::enav {

/// One path of the tree.
struct TreePath {
  double turn = 0.0;  ///< [rad] leading turn in place (0 = none)
  double k1 = 0.0;    ///< [1/m]
  double k2 = 0.0;    ///< [1/m]
  int direction = 1;  ///< +1 forward tree, -1 a backward arc (k2, second length unused)
  double length1 = 0.0, length2 = 0.0;  ///< [m] (length2 0 for backward arcs)
  /// [m] arc length sampled and checked (0 = all): for a path that enters the goal's
  /// tolerance, the larger of that entry and the goal's straight-line distance (the most the
  /// mobility manager drives of it before deciding again).
  double end_s = 0.0;
  /// [m] for a path that enters the goal's tolerance: where it does (0 otherwise). When the
  /// check to end_s fails beyond this, the path is checked again only a little past it and,
  /// passing, offered with its first segment that short (the rover stops inside the tolerance
  /// rather than at the goal).
  double entry_s = 0.0;
  bool settled = false;  ///< chosen on that shorter check (end_s = entry_s + 5 cm)
  int turn_index = 0, k1_index = 0;     ///< for sharing checks between paths
  double cost = 0.0;                    ///< J (+inf = discarded)
  int checked = 0;                      ///< 0 not checked, 1 passed, -1 failed
  std::string why;                      ///< the check's failure
};

/// The latest decision, for pictures, logs and benchmarks.
struct PlanRecord {
  geometry::Pose2 start;
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();
  std::vector<TreePath> paths;  ///< the forward tree (and backward arcs if they were tried)
  int chosen = -1;              ///< index into paths
  int ranked = 0;               ///< paths with a finite cost
  int checks = 0;               ///< clearance checks run
  bool escape = false;          ///< chosen with hazards near the footprint ignored
  bool blind = false;           ///< ranked without the cost-to-go (it reached no path)
  bool retrace = false;         ///< nothing passed: the choice backs along the last drive
  std::optional<Route> route;   ///< the route search's result, when it ran and found one
  bool routed = false;          ///< the choice is a straight line along the route
  bool route_kept = false;      ///< `route` is the one followed before (the new search's cost
                                ///< was not route_switch_m lower); its expansions: the search's
};

class EnavPlanner : public nav_core::ArcSelector {
 public:
  /// Errors: InvalidArgument from options.Validate().
  static Result<EnavPlanner> Create(const EnavOptions& options);

  /// FailedPrecondition: the ENav planner needs heights (see the file comment).
  Result<nav_core::ArcEvaluation> Evaluate(const nav_core::GoodnessMap& map,
                                           const nav_core::ArcRequest& request) const override;
  /// The decision over `terrain` (a HeightTerrain). Errors: InvalidArgument for a non-finite
  /// pose or goal or a negative tolerance; FailedPrecondition for another assessor.
  Result<nav_core::ArcEvaluation> Plan(const nav_core::TerrainAssessor& terrain,
                                       const nav_core::ArcRequest& request) const override;

  /// The cost-to-go field's value at xy when its goal is `goal` (nullopt otherwise, or when xy
  /// is blocked, unreached or off the map). With the route search first: the route cost to go
  /// from the point nearest xy (within 0.25 m) of the newest route with such a point (its
  /// decision's pose, or a route pose within route_lookahead ahead of it); nullopt when none.
  std::optional<double> CostToGo(const Eigen::Vector2d& goal,
                                 const Eigen::Vector2d& xy) const override;
  bool ChecksDriveLength() const override { return true; }
  bool ChecksTurns() const override { return true; }

  const PlanRecord& last() const { return last_; }
  const CostToGoField& cost_to_go() const { return field_; }
  /// Poses along a path every sample_spacing (the turn excluded: it is done in place).
  std::vector<geometry::Pose2> Samples(const geometry::Pose2& start, const TreePath& p) const;

 private:
  explicit EnavPlanner(const EnavOptions& options);
  bool CheckPath(const ClearanceChecker& checker, const geometry::Pose2& start,
                 const Exempt& on, TreePath* p) const;
  // A path into the goal's tolerance that failed its check to the goal: checked again only to
  // kEntryReach past its entry; passing, *p becomes that (settled, checked) and true.
  bool Settle(const ClearanceChecker& checker, const geometry::Pose2& start, const Exempt& on,
              bool escape, TreePath* p) const;
  // Escape paths: whether the first segment's end touches none of `exempt`.
  bool Clears(const ClearanceChecker& checker, const geometry::Pose2& start, const Exempt& exempt,
              TreePath* p) const;

  // The step along `route`: a turn in place to face a route pose and a straight line to it,
  // the farthest (within route_lookahead, before the route reverses) that passes CheckPath.
  // *target: the index in `route` of the pose it aims at.
  std::optional<TreePath> RouteStep(const ClearanceChecker& checker, const geometry::Pose2& start,
                                    const Route& route, const Eigen::Vector2d& goal,
                                    double tolerance, std::size_t* target) const;

  EnavOptions options_;
  std::vector<double> curvatures_;
  mutable CostToGoField field_;
  mutable CostToGoField relaxed_{false};  ///< the route search's heuristic and step factors
  RouteSearch search_;
  /// The route being followed (and its goal): kept while the rover is on it and every pose of
  /// it still fits the map, so one decision's route is not swapped for a near-equal one the
  /// next (the tree's commit_bonus does the same for its paths).
  mutable std::optional<Route> plan_;
  mutable Eigen::Vector2d plan_goal_ = Eigen::Vector2d::Zero();
  /// The last route step's line (site, after its turn) and the index in plan_ it aims at.
  struct RouteLine {
    Eigen::Vector2d from, to;
    int dir = 1;
    std::size_t target = 0;
  };
  mutable std::optional<RouteLine> step_;
  // plan_ from the node nearest `start` on, if the rover is on it and it still fits.
  // The route search's options from options_.
  RouteSearchOptions RouteOptions() const;
  // Whether the rover at `pose` keeps the room a route needs there (NeededRoom, from `start`).
  bool KeepsRouteRoom(const ClearanceChecker& checker, const geometry::Pose2& start,
                      double start_room, const geometry::Pose2& pose) const;
  std::optional<Route> Kept(const ClearanceChecker& checker, const geometry::Pose2& start,
                            const Eigen::Vector2d& goal) const;
  /// Route costs to go (site x, y; cost) at decision points and at their route's points within
  /// route_lookahead, for CostToGo, newest last.
  struct RouteCost {
    Eigen::Vector2d xy;  ///< [m] site
    double cost;         ///< [m-equivalent] the route's cost to go from xy
    std::uint64_t decision;
  };
  mutable std::vector<RouteCost> route_costs_;
  mutable std::uint64_t decisions_ = 0;  ///< routed decisions so far
  mutable PlanRecord last_;
  struct Previous {
    geometry::Pose2 start;
    TreePath path;
  };
  mutable std::optional<Previous> previous_;  ///< the last choice (forward, not an escape)
  struct LastDrive {
    geometry::Pose2 start;  ///< where its arc starts (after the choice's turn)
    double k = 0.0;         ///< [1/m] its first arc's curvature
    int direction = 1;
  };
  /// The arc of the last choice that was not a retrace.
  mutable std::optional<LastDrive> last_drive_;
  // The way back along last_drive_ to its start from `start`, if the rover is on it.
  std::optional<TreePath> Retrace(const geometry::Pose2& start) const;
};

}  // namespace rover::apl::enav
