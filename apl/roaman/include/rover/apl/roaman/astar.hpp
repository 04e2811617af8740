#pragma once
/// @file
/// Grid search on the planning grid: A* (the baseline planner), Dijkstra (its brute-force
/// reference, and the shortest safe path the benchmark compares against), the region reachable
/// from the rover, and string pulling from a cell path to turn-in-place + straight legs.
///
/// Graph: cells whose clearance is at least `min_clearance` (the planner uses half the footprint
/// width: the rover can drive over them), 8-connected; a diagonal move also needs both
/// cells it passes between. Move cost from a to b: |ab| (1 + w (p(a) + p(b)) / 2) with the
/// clearance penalty p(c) = max(0, 1 - clearance(c) / ref) (w = clearance_weight, ref =
/// clearance_ref), so paths keep away from hazards when it costs little. A* uses the octile
/// distance times the cell size, a lower bound of every path's cost (the factor is >= 1), so it
/// returns an optimal path of this graph.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rover/apl/roaman/options.hpp"
#include "rover/apl/roaman/planning_grid.hpp"
#include "rover/base/status.hpp"

namespace rover::apl::roaman {

struct SearchCost {
  double min_clearance = 0.0;     ///< [m] cells with less are not in the graph
  double clearance_weight = 0.0;  ///< w
  double clearance_ref = 1.0;     ///< [m] ref
};

struct GridPath {
  std::vector<Eigen::Vector2i> cells;  ///< (i, j), from first to last
  double cost = 0.0;                   ///< sum of move costs
  double length = 0.0;                 ///< [m] sum of move lengths
  std::size_t expanded = 0;            ///< cells taken off the open list
};

/// A* from cell `from` to cell `to`. Errors: NotFound when `to` cannot be reached;
/// InvalidArgument when either cell is outside the grid or not in the graph.
Result<GridPath> AStarSearch(const PlanningGrid& grid, Eigen::Vector2i from, Eigen::Vector2i to,
                             const SearchCost& cost);
/// Dijkstra on the same graph and costs (no heuristic): the reference A* must match.
Result<GridPath> DijkstraSearch(const PlanningGrid& grid, Eigen::Vector2i from, Eigen::Vector2i to,
                                const SearchCost& cost);

/// 1 for every cell of the graph connected to `from` (8-connected, as the search moves).
Layer<std::uint8_t> ReachableCells(const PlanningGrid& grid, Eigen::Vector2i from,
                                   double min_clearance);

/// Turns a path of points into waypoints: from each waypoint, look ahead to the farthest later
/// point the rover can drive to straight (SegmentClear with half the footprint width) before
/// the first that it cannot; the next waypoint is the farthest point up to there where the rover
/// can turn to any heading (clearance >= the turn radius), or that farthest point when there is
/// none. Returns the waypoints, first and last point included. (Turns at the fallback points
/// may not be safe: the planner checks the result with PolylineSafe.)
std::vector<Eigen::Vector2d> PullString(const PlanningGrid& grid,
                                        const std::vector<Eigen::Vector2d>& points,
                                        const Footprint& footprint);

/// [m] length of a polyline.
double PolylineLength(const std::vector<Eigen::Vector2d>& points);

}  // namespace rover::apl::roaman
