#pragma once
/// @file
/// RoamanPlanner: FIDO's ROAMAN long-range planner (seed 004 §3.1) behind nav_core's
/// GlobalPlanner, plus what goes beyond FIDO: the A* baseline on the same map, a site-frame map
/// memory across panoramas, and replanning around corridors reported blocked.
///
///   AddScan (mast NAVCAM scans, one per pointing) -> SiteMap (site_map.hpp)
///   MakePlan -> the seven-step TraversabilityMap (traversability.hpp, recomputed when the map
///     changed) -> PlanProblem on the goal-aligned planning grid (problem.hpp) ->
///     ROAMAN: road map, DFS, least-squares waypoints (road_map.hpp, waypoint_fit.hpp), or
///     A* (astar.hpp) -> waypoints and turn-in-place + straight legs.
///
/// When the selected algorithm finds no route and `fallback` is set, the other one is tried;
/// when neither does, the plan fails with NotFound "every route to the goal ... is blocked: ..."
/// and last_failure() == kBlocked. Other failures name their reason (problem.hpp). The library
/// is synchronous and single-threaded; the apl/planner service calls it directly (Plan()
/// returns everything the apl/plan topic needs: waypoints, legs, cost, algorithm).

#include <Eigen/Core>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rover/apl/nav_core/global_planner.hpp"
#include "rover/apl/nav_core/range_scan.hpp"
#include "rover/apl/roaman/options.hpp"
#include "rover/apl/roaman/problem.hpp"
#include "rover/apl/roaman/road_map.hpp"
#include "rover/apl/roaman/site_map.hpp"
#include "rover/apl/roaman/traversability.hpp"
#include "rover/apl/roaman/waypoint_fit.hpp"
#include "rover/base/status.hpp"

namespace rover::apl::roaman {

struct RoamanPlan {
  Algorithm algorithm = Algorithm::kRoaman;  ///< the algorithm that made this plan
  bool fell_back = false;  ///< the requested algorithm found no route; the other one did
  /// [m] site; the end of the first leg first, the rover's start excluded.
  std::vector<Eigen::Vector2d> waypoints;
  std::vector<Leg> legs;     ///< turn in place, then drive straight, from the rover's start
  double length = 0.0;       ///< [m]
  double total_turn = 0.0;   ///< [rad] sum of |turn| between legs
  double cost = 0.0;         ///< length + turn_cost x total_turn
  bool reaches_goal = false; ///< the last waypoint is within goal_tolerance of the goal
  double goal_distance = 0;  ///< [m] from the last waypoint (or the start) to the goal
  /// [m] site: the path before waypoint selection (road-map vertices, or A* cell centres).
  std::vector<Eigen::Vector2d> path;
  int road_nodes = 0;        ///< ROAMAN: axis cells kept
  int road_dropped = 0;      ///< ROAMAN: axis cells the virtual drive dropped
  std::size_t expanded = 0;  ///< nodes or cells the search expanded
  double fit_error_before = 0.0;  ///< [m^2] ROAMAN: least-squares error of the initial waypoints
  double fit_error_after = 0.0;   ///< [m^2] ... and of the fitted ones
  std::string fit_outcome;        ///< ROAMAN: NLopt's outcome

  /// The nav_core form (waypoints, cost, reaches_goal).
  nav_core::GlobalPlan ToGlobalPlan() const;
};

/// ROAMAN on a prepared problem; the road map it built goes to *road when given. Errors:
/// NotFound when the road map has no route (road_map.hpp).
Result<RoamanPlan> PlanWithRoadMap(const PlanProblem& problem, const RoamanOptions& options,
                                   RoadMap* road = nullptr);
/// A* on a prepared problem: to the goal anchor, or for a partial plan to the reachable cell
/// nearest the goal; the cell path string-pulled into legs. Errors: NotFound when there is no
/// route (or, partial, none that gets min_progress nearer the goal).
Result<RoamanPlan> PlanWithAStar(const PlanProblem& problem, const RoamanOptions& options);
/// The reference: the shortest safe path on the same graph (Dijkstra with length costs only,
/// no clearance term), string-pulled the same way. Same errors as PlanWithAStar.
Result<RoamanPlan> ShortestSafePath(const PlanProblem& problem, const RoamanOptions& options);

class RoamanPlanner final : public nav_core::GlobalPlanner {
 public:
  /// Errors: the options' Validate() message.
  static Result<std::unique_ptr<RoamanPlanner>> Create(const RoamanOptions& options);
  /// Preconditions: options.Validate() is ok.
  explicit RoamanPlanner(const RoamanOptions& options);

  // nav_core::GlobalPlanner
  Status AddScan(const nav_core::RangeScan& scan) override;
  Result<nav_core::GlobalPlan> MakePlan(const nav_core::PlanRequest& request) override;
  Status ReportBlocked(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                       double half_width) override;
  void Clear() override;

  /// AddScan with what happened to the scan's pixels.
  Result<ScanStats> Add(const nav_core::RangeScan& scan);
  /// Starts a new panorama explicitly (AddScan also detects one when the rover has moved).
  void BeginPanorama() { map_.BeginPanorama(); }
  /// Plans with options().algorithm (and its fallback).
  Result<RoamanPlan> Plan(const nav_core::PlanRequest& request);
  /// Plans with `algorithm` (and the other one as fallback when options().fallback).
  Result<RoamanPlan> Plan(const nav_core::PlanRequest& request, Algorithm algorithm);
  /// Why the last Plan/MakePlan failed (kNone after a success).
  PlanFailure last_failure() const { return last_failure_; }

  const RoamanOptions& options() const { return options_; }
  const SiteMap& site_map() const { return map_; }
  /// The seven-step map of the current map memory (recomputed when it changed).
  const TraversabilityMap& Traversability();
  /// The problem and road map of the last plan that got that far (for pictures and tools).
  const PlanProblem* last_problem() const { return problem_ ? &*problem_ : nullptr; }
  const RoadMap* last_road_map() const { return road_ ? &*road_ : nullptr; }

 private:
  Result<RoamanPlan> Run(Algorithm algorithm);
  Status Failed(PlanFailure failure, Status status);

  RoamanOptions options_;
  SiteMap map_;
  std::optional<TraversabilityMap> traversability_;
  std::optional<PlanProblem> problem_;
  std::optional<RoadMap> road_;
  PlanFailure last_failure_ = PlanFailure::kNone;
};

}  // namespace rover::apl::roaman
