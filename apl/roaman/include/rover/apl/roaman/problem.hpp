#pragma once
/// @file
/// PlanProblem: one plan request checked against the traversability map and set up on its
/// goal-aligned planning grid, shared by both planners (so that they plan on the same map), and
/// the typed reasons a request can fail.
///
/// Start: routes begin at the start anchor, the rover's own cell when it has the clearance to
/// turn in place, else the nearest cell within start_search_radius that has it and a straight
/// first leg that never comes nearer to a hazard than the rover already is (or than half its
/// width). Goal: a goal counts as on the grid when it lies at least goal_margin inside the
/// grid's far edge (rows run to goal distance + goal_margin, at most plan_length). Its anchor is
/// the goal itself when the rover could stand and turn there, else the nearest such cell within
/// goal_tolerance. A goal off the grid, or on the grid in cells without data, is planned toward
/// when the request allows a partial plan (the plan then ends where the known map runs out).

#include <Eigen/Core>
#include <string>

#include "rover/apl/nav_core/global_planner.hpp"
#include "rover/apl/roaman/options.hpp"
#include "rover/apl/roaman/planning_grid.hpp"
#include "rover/apl/roaman/traversability.hpp"
#include "rover/base/status.hpp"

namespace rover::apl::roaman {

/// Why a plan request failed.
enum class PlanFailure {
  kNone = 0,
  kInvalidRequest,  ///< non-finite start or goal, negative tolerance (InvalidArgument)
  kNoMap,           ///< no range data yet (FailedPrecondition)
  kGoalOffMap,      ///< goal beyond the planning grid and no partial plan allowed (NotFound)
  kGoalMissing,     ///< goal on cells the map has no data for, no partial plan allowed
  kGoalInHazard,    ///< goal on a hazard, or too near one to stand and turn there
  kNoSafeStart,     ///< no cell near the rover it could turn on and reach
  kBlocked,         ///< every route to the goal is blocked
};
/// "none", "invalid_request", "no_map", "goal_off_map", "goal_missing", "goal_in_hazard",
/// "no_safe_start", "blocked".
const char* PlanFailureName(PlanFailure f);

struct PlanProblem {
  nav_core::PlanRequest request;
  PlanningGrid grid;
  Footprint footprint;          ///< the rover, for turn tests
  double turn_clearance = 0.0;  ///< [m] clearance any turn in place is safe with (turn radius)
  double leg_clearance = 0.0;   ///< [m] clearance a straight drive needs (half width)
  Eigen::Vector2d start_anchor = Eigen::Vector2d::Zero();  ///< [m] site
  int start_i = 0, start_j = 0;                            ///< its cell
  /// The goal is on the grid where the map has data: routes must reach goal_anchor. Otherwise
  /// (a partial plan) they end as near the goal as the map allows.
  bool goal_on_grid = false;
  Eigen::Vector2d goal_anchor = Eigen::Vector2d::Zero();  ///< [m] site (goal_on_grid only)
  int goal_i = 0, goal_j = 0;                             ///< its cell (goal_on_grid only)
};

/// Checks a request's numbers; messages name the field ("PlanRequest.goal.x is nan ...").
Status ValidateRequest(const nav_core::PlanRequest& request);

/// Sets up `request` on `map`. Preconditions: the request is valid and its goal is farther than
/// goal_tolerance from its start. Errors (with *failure set; messages name the point and the
/// reason): NotFound for kGoalOffMap, kGoalMissing, kGoalInHazard, kNoSafeStart.
Result<PlanProblem> PreparePlan(const TraversabilityMap& map, const nav_core::PlanRequest& request,
                                const RoamanOptions& options, PlanFailure* failure);

/// "(x, y)" with FormatNumber at 4 significant digits.
std::string FormatPoint(const Eigen::Vector2d& p);
/// The nearest non-safe cell to p within `radius` on the grid, as "<class> at (x, y), d m away",
/// or "the edge of the planning grid, d m away", or "none within r m".
std::string DescribeNearestHazard(const PlanningGrid& grid, const Eigen::Vector2d& p,
                                  double radius);

}  // namespace rover::apl::roaman
