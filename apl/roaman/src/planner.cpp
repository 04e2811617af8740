#include "rover/apl/roaman/planner.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "rover/apl/roaman/astar.hpp"
#include "rover/base/format.hpp"

namespace rover::apl::roaman {
namespace {

// Completes a plan from `polyline` (start anchor first): the leg from the rover's start to the
// anchor, legs, length, turns, cost, whether it reaches the goal.
RoamanPlan Finish(const PlanProblem& problem, const RoamanOptions& options,
                  const std::vector<Eigen::Vector2d>& polyline, Algorithm algorithm) {
  RoamanPlan plan;
  plan.algorithm = algorithm;
  std::vector<Eigen::Vector2d> full;
  full.push_back(problem.request.start);
  for (const Eigen::Vector2d& p : polyline) {
    if ((p - full.back()).norm() > 1e-9) full.push_back(p);
  }
  plan.waypoints.assign(full.begin() + 1, full.end());
  plan.legs = MakeLegs(full);
  for (const Leg& l : plan.legs) {
    plan.length += l.length;
    plan.total_turn += std::abs(l.turn);
  }
  plan.cost = plan.length + options.turn_cost * plan.total_turn;
  plan.goal_distance = (full.back() - problem.request.goal).norm();
  plan.reaches_goal =
      problem.goal_on_grid && (plan.goal_distance <= problem.request.goal_tolerance + 1e-9 ||
                               (full.back() - problem.goal_anchor).norm() < 1e-9);
  return plan;
}

// The cell A* and the reference search head for: the goal anchor, or (partial plan) the
// reachable turn-safe cell nearest the goal.
Result<Eigen::Vector2i> SearchTarget(const PlanProblem& problem, const RoamanOptions& options) {
  const PlanningGrid& g = problem.grid;
  const Layer<std::uint8_t> reach =
      ReachableCells(g, {problem.start_i, problem.start_j}, problem.leg_clearance);
  if (problem.goal_on_grid) {
    if (!reach.at(problem.goal_i, problem.goal_j)) {
      return NotFound("grid search: the goal anchor " + FormatPoint(problem.goal_anchor) +
                      " is not connected to the rover by cells it can drive over");
    }
    return Eigen::Vector2i(problem.goal_i, problem.goal_j);
  }
  double best = std::numeric_limits<double>::infinity();
  Eigen::Vector2i target(problem.start_i, problem.start_j);
  for (int j = 0; j < g.height; ++j) {
    for (int i = 0; i < g.width; ++i) {
      if (!reach.at(i, j)) continue;
      const double d = (g.Center(i, j) - problem.request.goal).norm();
      if (d < best) {
        best = d;
        target = {i, j};
      }
    }
  }
  const double progress = (problem.start_anchor - problem.request.goal).norm() - best;
  if (progress < options.min_progress) {
    return NotFound("grid search: no cell the rover can reach gets " +
                    FormatNumber(options.min_progress, 3) + " m nearer the goal " +
                    FormatPoint(problem.request.goal) + " (the nearest is " +
                    FormatNumber(best, 4) + " m from it)");
  }
  return target;
}

Result<RoamanPlan> GridPlan(const PlanProblem& problem, const RoamanOptions& options,
                            const SearchCost& cost, bool astar) {
  ROVER_ASSIGN_OR_RETURN(const Eigen::Vector2i target, SearchTarget(problem, options));
  const Eigen::Vector2i from(problem.start_i, problem.start_j);
  ROVER_ASSIGN_OR_RETURN(GridPath path, astar ? AStarSearch(problem.grid, from, target, cost)
                                              : DijkstraSearch(problem.grid, from, target, cost));
  std::vector<Eigen::Vector2d> points;
  for (const Eigen::Vector2i& c : path.cells) points.push_back(problem.grid.Center(c.x(), c.y()));
  points.front() = problem.start_anchor;
  if (problem.goal_on_grid) points.back() = problem.goal_anchor;
  const std::vector<Eigen::Vector2d> waypoints =
      PullString(problem.grid, points, problem.footprint);
  for (std::size_t k = 1; k + 1 < waypoints.size(); ++k) {
    if (!TurnSafe(problem.grid, problem.footprint, waypoints[k - 1], waypoints[k],
                  waypoints[k + 1])) {
      const double turn = TurnAngle(waypoints[k - 1], waypoints[k], waypoints[k + 1]);
      return NotFound("grid search: the path turns by " +
                      FormatNumber(std::abs(turn) * 180.0 / std::numbers::pi, 3) + " deg at " +
                      FormatPoint(waypoints[k]) + ", where the clearance " +
                      FormatNumber(problem.grid.ClearanceAt(waypoints[k]), 3) + " m is below the " +
                      FormatNumber(problem.footprint.TurnClearance(turn), 3) + " m that needs");
    }
  }
  RoamanPlan plan = Finish(problem, options, waypoints, Algorithm::kAStar);
  plan.path = std::move(points);
  plan.expanded = path.expanded;
  return plan;
}

}  // namespace

nav_core::GlobalPlan RoamanPlan::ToGlobalPlan() const {
  nav_core::GlobalPlan g;
  g.waypoints = waypoints;
  g.cost = cost;
  g.reaches_goal = reaches_goal;
  return g;
}

Result<RoamanPlan> PlanWithRoadMap(const PlanProblem& problem, const RoamanOptions& options,
                                   RoadMap* road_out) {
  RoadMap road = BuildRoadMap(problem.grid, options);
  const Result<RoadPath> found = LongestRoadPath(road, problem, options);
  const int kept = road.nodes(), dropped = road.dropped;
  if (road_out) *road_out = std::move(road);
  if (!found.ok()) return found.status();
  const RoadPath& path = *found;
  const std::vector<int> keep =
      SelectWaypoints(problem.grid, path.vertices, options.fit_tolerance, problem.footprint);
  std::vector<Eigen::Vector2d> initial;
  for (const int k : keep) initial.push_back(path.vertices[static_cast<std::size_t>(k)]);
  std::vector<int> index;
  const std::vector<Eigen::Vector2d> samples = SamplePath(path.vertices, problem.grid.cell, &index);
  const FitResult fit =
      FitWaypoints(problem.grid, samples, initial, problem.footprint, options.fit_max_evaluations);
  RoamanPlan plan = Finish(problem, options, fit.waypoints, Algorithm::kRoaman);
  plan.path = path.vertices;
  plan.road_nodes = kept;
  plan.road_dropped = dropped;
  plan.expanded = path.expanded;
  plan.fit_error_before = fit.error_before;
  plan.fit_error_after = fit.error_after;
  plan.fit_outcome = fit.outcome;
  return plan;
}

Result<RoamanPlan> PlanWithAStar(const PlanProblem& problem, const RoamanOptions& options) {
  const SearchCost cost{problem.leg_clearance, options.clearance_weight, options.clearance_ref};
  return GridPlan(problem, options, cost, true);
}

Result<RoamanPlan> ShortestSafePath(const PlanProblem& problem, const RoamanOptions& options) {
  const SearchCost cost{problem.leg_clearance, 0.0, options.clearance_ref};
  return GridPlan(problem, options, cost, false);
}

// ---- RoamanPlanner ------------------------------------------------------------------------

Result<std::unique_ptr<RoamanPlanner>> RoamanPlanner::Create(const RoamanOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  return std::make_unique<RoamanPlanner>(options);
}

RoamanPlanner::RoamanPlanner(const RoamanOptions& options) : options_(options), map_(options) {}

Status RoamanPlanner::AddScan(const nav_core::RangeScan& scan) { return Add(scan).status(); }

Result<ScanStats> RoamanPlanner::Add(const nav_core::RangeScan& scan) { return map_.AddScan(scan); }

Status RoamanPlanner::ReportBlocked(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                                    double half_width) {
  return map_.MarkBlocked(from, to, half_width).status();
}

void RoamanPlanner::Clear() {
  map_.Clear();
  traversability_.reset();
  problem_.reset();
  road_.reset();
  last_failure_ = PlanFailure::kNone;
}

const TraversabilityMap& RoamanPlanner::Traversability() {
  if (!traversability_ || traversability_->revision != map_.revision()) {
    traversability_ = ComputeTraversability(map_, options_);
  }
  return *traversability_;
}

Result<nav_core::GlobalPlan> RoamanPlanner::MakePlan(const nav_core::PlanRequest& request) {
  ROVER_ASSIGN_OR_RETURN(const RoamanPlan plan, Plan(request));
  return plan.ToGlobalPlan();
}

Result<RoamanPlan> RoamanPlanner::Plan(const nav_core::PlanRequest& request) {
  return Plan(request, options_.algorithm);
}

Status RoamanPlanner::Failed(PlanFailure failure, Status status) {
  last_failure_ = failure;
  return status;
}

Result<RoamanPlan> RoamanPlanner::Run(Algorithm algorithm) {
  if (algorithm == Algorithm::kAStar) return PlanWithAStar(*problem_, options_);
  road_.emplace();
  return PlanWithRoadMap(*problem_, options_, &*road_);
}

Result<RoamanPlan> RoamanPlanner::Plan(const nav_core::PlanRequest& request, Algorithm algorithm) {
  last_failure_ = PlanFailure::kNone;
  problem_.reset();
  road_.reset();
  if (const Status s = ValidateRequest(request); !s.ok()) {
    return Failed(PlanFailure::kInvalidRequest, s);
  }
  if (map_.data_cells() == 0 && map_.corridors().empty()) {
    return Failed(PlanFailure::kNoMap,
                  FailedPrecondition("no map to plan on: add the scans of a panorama first"));
  }
  const double distance = (request.goal - request.start).norm();
  if (distance <= request.goal_tolerance || distance == 0.0) {
    RoamanPlan plan;
    plan.algorithm = algorithm;
    plan.reaches_goal = true;
    plan.goal_distance = distance;
    return plan;
  }
  const TraversabilityMap& map = Traversability();
  PlanFailure failure = PlanFailure::kNone;
  Result<PlanProblem> problem = PreparePlan(map, request, options_, &failure);
  if (!problem.ok()) return Failed(failure, problem.status());
  problem_ = std::move(problem).value();

  Result<RoamanPlan> first = Run(algorithm);
  if (first.ok()) return first;
  const Algorithm other = algorithm == Algorithm::kRoaman ? Algorithm::kAStar : Algorithm::kRoaman;
  std::string why = std::string(AlgorithmName(algorithm)) + ": " + first.status().message();
  if (options_.fallback) {
    Result<RoamanPlan> second = Run(other);
    if (second.ok()) {
      second->fell_back = true;
      return second;
    }
    why += "; " + std::string(AlgorithmName(other)) + ": " + second.status().message();
  }
  // Every route is blocked: say how far the rover's safe region reaches.
  const PlanProblem& p = *problem_;
  const Layer<std::uint8_t> reach = ReachableCells(p.grid, {p.start_i, p.start_j}, p.leg_clearance);
  int cells = 0;
  double nearest = std::numeric_limits<double>::infinity();
  for (int j = 0; j < p.grid.height; ++j) {
    for (int i = 0; i < p.grid.width; ++i) {
      if (!reach.at(i, j)) continue;
      ++cells;
      nearest = std::min(nearest, (p.grid.Center(i, j) - request.goal).norm());
    }
  }
  const std::size_t corridors = map_.corridors().size();
  return Failed(
      PlanFailure::kBlocked,
      NotFound("every route to the goal " + FormatPoint(request.goal) + " is blocked: the " +
               FormatNumber(cells * p.grid.cell * p.grid.cell, 3) + " m^2 the rover at " +
               FormatPoint(request.start) + " can reach come no nearer than " +
               FormatNumber(nearest, 4) + " m to it; " + std::to_string(corridors) + " corridor" +
               (corridors == 1 ? "" : "s") + " reported blocked (" + why + ")"));
}

}  // namespace rover::apl::roaman
