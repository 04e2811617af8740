#pragma once
/// @file
/// GlobalPlanner: long-range planning beyond what the local goodness map covers (FIDO's ROAMAN,
/// seed 004: a traversability map built from mast stereo out to ~12 m, a medial axis of the free
/// space per grid row, a depth-first search for the longest connected path and a least-squares
/// fit that yields waypoints). The mobility manager drives from waypoint to waypoint with the
/// TerrainAssessor and ArcSelector for local avoidance; as in ROAMAN the planner keeps its own
/// map, since long traverses accumulate localisation error and the maps are not shared.
///
/// Declared here so that apl/mobility can depend on it now; apl/roaman (ROAMAN) implements it and
/// the apl/planner service runs it.
/// Frames: site frame (x north, y west, z up), metres.

#include <Eigen/Core>
#include <vector>

#include "rover/apl/nav_core/range_scan.hpp"
#include "rover/base/status.hpp"

namespace rover::apl::nav_core {

struct PlanRequest {
  Eigen::Vector2d start = Eigen::Vector2d::Zero();  ///< [m] site x, y
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();   ///< [m] site x, y
  double goal_tolerance = 0.0;                      ///< [m]
  /// The goal may lie beyond what the planner's map covers (a long traverse, FIDO's panorama ->
  /// plan -> drive -> panorama loop): plan toward it as far as the map allows; the plan then
  /// ends short of the goal (GlobalPlan::reaches_goal false). When false, such a goal is an
  /// error (NotFound naming it).
  bool allow_partial = false;
};

struct GlobalPlan {
  std::vector<Eigen::Vector2d> waypoints;  ///< [m] site x, y, first leg first; ends near the goal
  double cost = 0.0;                       ///< planner-defined, comparable between plans
  /// The last waypoint is within goal_tolerance of the goal (false only for partial plans).
  bool reaches_goal = true;
};

class GlobalPlanner {
 public:
  virtual ~GlobalPlanner() = default;
  /// Adds range data (typically a mast NAVCAM panorama, one scan per pointing) to the planner's
  /// own map. Errors: InvalidArgument for a malformed scan.
  virtual Status AddScan(const RangeScan& scan) = 0;
  /// Plans from start to goal over the planner's map. Errors: NotFound when no path exists
  /// (the mobility manager's NOPATH), InvalidArgument for a non-finite request.
  virtual Result<GlobalPlan> MakePlan(const PlanRequest& request) = 0;
  /// Replanning: the corridor of half-width `half_width` around the segment from -> to (site
  /// x, y, metres) is not traversable (the mobility manager ended a leg there with NOPATH or
  /// NOPROGRESS); later plans route around it until Clear(). Errors: InvalidArgument for a
  /// non-finite point or a half-width that is not > 0. A planner that cannot route around
  /// reports (the default) returns FailedPrecondition, and the caller ends the traverse there.
  virtual Status ReportBlocked(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                               double half_width) {
    (void)from;
    (void)to;
    (void)half_width;
    return FailedPrecondition("this global planner does not replan around blocked corridors");
  }
  /// Forgets the planner's map and the blocked corridors.
  virtual void Clear() = 0;
};

}  // namespace rover::apl::nav_core
