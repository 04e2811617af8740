#include "rover/apl/roaman/problem.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::apl::roaman {
namespace {

struct Candidate {
  double distance;
  int i, j;
};

// Cells within `radius` of p whose clearance is at least `clearance`, nearest first (ties in
// raster order, so the choice is deterministic).
std::vector<Candidate> TurnSafeCellsNear(const PlanningGrid& g, const Eigen::Vector2d& p,
                                         double radius, double clearance) {
  std::vector<Candidate> out;
  int ci = 0, cj = 0;
  g.CellOf(p, &ci, &cj);
  const int r = static_cast<int>(std::ceil(radius / g.cell)) + 1;
  for (int j = std::max(0, cj - r); j <= std::min(g.height - 1, cj + r); ++j) {
    for (int i = std::max(0, ci - r); i <= std::min(g.width - 1, ci + r); ++i) {
      if (g.clearance.at(i, j) < clearance) continue;
      const double d = (g.Center(i, j) - p).norm();
      if (d <= radius) out.push_back({d, i, j});
    }
  }
  std::stable_sort(out.begin(), out.end(),
                   [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
  return out;
}

Status Fail(PlanFailure* out, PlanFailure f, std::string message) {
  *out = f;
  return NotFound(std::move(message));
}

}  // namespace

const char* PlanFailureName(PlanFailure f) {
  switch (f) {
    case PlanFailure::kNone:
      return "none";
    case PlanFailure::kInvalidRequest:
      return "invalid_request";
    case PlanFailure::kNoMap:
      return "no_map";
    case PlanFailure::kGoalOffMap:
      return "goal_off_map";
    case PlanFailure::kGoalMissing:
      return "goal_missing";
    case PlanFailure::kGoalInHazard:
      return "goal_in_hazard";
    case PlanFailure::kNoSafeStart:
      return "no_safe_start";
    case PlanFailure::kBlocked:
      return "blocked";
  }
  return "?";
}

std::string FormatPoint(const Eigen::Vector2d& p) {
  return "(" + FormatNumber(p.x(), 4) + ", " + FormatNumber(p.y(), 4) + ")";
}

std::string DescribeNearestHazard(const PlanningGrid& g, const Eigen::Vector2d& p, double radius) {
  int ci = 0, cj = 0;
  g.CellOf(p, &ci, &cj);
  const int r = static_cast<int>(std::ceil(radius / g.cell)) + 1;
  double best = std::numeric_limits<double>::infinity();
  int bi = -1, bj = -1;
  for (int j = cj - r; j <= cj + r; ++j) {
    for (int i = ci - r; i <= ci + r; ++i) {
      if (!g.Contains(i, j) || g.cls.at(i, j) == CellClass::kSafe) continue;
      const double d = (g.Center(i, j) - p).norm();
      if (d < best) {
        best = d;
        bi = i;
        bj = j;
      }
    }
  }
  const Eigen::Vector2d q = g.frame.ToFrame(p);
  const double to_edge = std::min({q.y() - g.across0, g.across0 + g.width * g.cell - q.y(),
                                   q.x() - g.along0, g.along0 + g.height * g.cell - q.x()});
  if (to_edge < best && to_edge <= radius) {
    return "the edge of the planning grid, " + FormatNumber(std::max(0.0, to_edge), 3) + " m away";
  }
  if (bi < 0) return "none within " + FormatNumber(radius, 3) + " m";
  return std::string(CellClassName(g.cls.at(bi, bj))) + " at " + FormatPoint(g.Center(bi, bj)) +
         ", " + FormatNumber(best, 3) + " m away";
}

Status ValidateRequest(const nav_core::PlanRequest& r) {
  ROVER_RETURN_IF_ERROR(CheckFinite("PlanRequest.start.x", r.start.x()));
  ROVER_RETURN_IF_ERROR(CheckFinite("PlanRequest.start.y", r.start.y()));
  ROVER_RETURN_IF_ERROR(CheckFinite("PlanRequest.goal.x", r.goal.x()));
  ROVER_RETURN_IF_ERROR(CheckFinite("PlanRequest.goal.y", r.goal.y()));
  ROVER_RETURN_IF_ERROR(
      CheckRange("PlanRequest.goal_tolerance", r.goal_tolerance, 0.0, 1000.0, "m"));
  return Status::Ok();
}

Result<PlanProblem> PreparePlan(const TraversabilityMap& map, const nav_core::PlanRequest& request,
                                const RoamanOptions& options, PlanFailure* failure) {
  *failure = PlanFailure::kNone;
  const double distance = (request.goal - request.start).norm();
  ROVER_DEMAND(distance > request.goal_tolerance && distance > 0.0);
  PlanProblem p;
  p.request = request;
  p.footprint = options.footprint();
  p.turn_clearance = options.turn_radius();
  p.leg_clearance = options.leg_clearance();
  const bool fits = distance + options.goal_margin <= options.plan_length;
  const double along_max = fits ? distance + options.goal_margin : options.plan_length;
  p.grid = BuildPlanningGrid(map, request.start, request.goal, along_max, options);
  const PlanningGrid& g = p.grid;
  const std::string goal_text = "goal " + FormatPoint(request.goal);

  // Goal.
  if (!fits) {
    if (!request.allow_partial) {
      return Fail(failure, PlanFailure::kGoalOffMap,
                  goal_text + " is off the map: " + FormatNumber(distance, 4) +
                      " m from the rover, beyond the " + FormatNumber(options.plan_length, 4) +
                      " m planning grid less its " + FormatNumber(options.goal_margin, 3) +
                      " m goal margin (plan_length_m, goal_margin_m); allow a partial plan to "
                      "plan toward it");
    }
  } else {
    const std::vector<Candidate> near =
        TurnSafeCellsNear(g, request.goal, request.goal_tolerance, p.turn_clearance);
    if (g.ClearanceAt(request.goal) >= p.turn_clearance) {
      p.goal_on_grid = true;
      p.goal_anchor = request.goal;
      g.CellOf(request.goal, &p.goal_i, &p.goal_j);
    } else if (!near.empty()) {
      p.goal_on_grid = true;
      p.goal_i = near.front().i;
      p.goal_j = near.front().j;
      p.goal_anchor = g.Center(p.goal_i, p.goal_j);
    } else {
      const CellClass c = g.ClassAt(request.goal);
      if (c == CellClass::kMissing) {
        if (!request.allow_partial) {
          return Fail(failure, PlanFailure::kGoalMissing,
                      goal_text +
                          " is on terrain the map has no data for (unseen, or in the "
                          "shadow of a rock); allow a partial plan to plan toward it");
        }
      } else if (c != CellClass::kSafe) {
        return Fail(failure, PlanFailure::kGoalInHazard,
                    goal_text + " is inside a hazard (" + CellClassName(c) +
                        " cell) and no cell within goal_tolerance " +
                        FormatNumber(request.goal_tolerance, 3) + " m is safe to stand on");
      } else {
        return Fail(failure, PlanFailure::kGoalInHazard,
                    goal_text + " is inside a hazard's reach: clearance " +
                        FormatNumber(g.ClearanceAt(request.goal), 3) +
                        " m (nearest: " + DescribeNearestHazard(g, request.goal, p.turn_clearance) +
                        "); the rover needs " + FormatNumber(p.turn_clearance, 3) +
                        " m to stand and turn there, and no cell within goal_tolerance " +
                        FormatNumber(request.goal_tolerance, 3) + " m has it");
      }
    }
  }

  // Start.
  const double start_clearance = g.ClearanceAt(request.start);
  if (start_clearance >= p.turn_clearance) {
    p.start_anchor = request.start;
    g.CellOf(request.start, &p.start_i, &p.start_j);
  } else {
    const double leg = std::min(p.leg_clearance, start_clearance);
    bool found = false;
    if (start_clearance > 0.0) {
      for (const Candidate& c :
           TurnSafeCellsNear(g, request.start, options.start_search_radius, p.turn_clearance)) {
        if (g.SegmentClear(request.start, g.Center(c.i, c.j), leg)) {
          p.start_i = c.i;
          p.start_j = c.j;
          p.start_anchor = g.Center(c.i, c.j);
          found = true;
          break;
        }
      }
    }
    if (!found) {
      return Fail(failure, PlanFailure::kNoSafeStart,
                  "no safe cell near the rover at " + FormatPoint(request.start) + ": " +
                      (start_clearance > 0.0
                           ? "no cell within start_search_radius " +
                                 FormatNumber(options.start_search_radius, 3) + " m has the " +
                                 FormatNumber(p.turn_clearance, 3) +
                                 " m clearance to turn in place and a clear straight leg to it"
                           : std::string("the rover stands on a ") +
                                 CellClassName(g.ClassAt(request.start)) + " cell") +
                      " (nearest hazard: " +
                      DescribeNearestHazard(g, request.start, options.start_search_radius) + ")");
    }
  }
  return p;
}

}  // namespace rover::apl::roaman
