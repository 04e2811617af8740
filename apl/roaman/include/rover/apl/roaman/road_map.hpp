#pragma once
/// @file
/// ROAMAN's road map on the goal-aligned planning grid (seed 004 §3.1) and the depth-first
/// search for the longest connected path toward the goal.
///
/// Medial axis: every row (constant j, across the direction to the goal) is scanned for its
/// free runs, maximal spans [i0, i1] of safe cells between hazards (or the grid's edge); the
/// centre cell (i0 + i1) / 2 of each run is the row's 1-D medial axis (its Voronoi point).
///
/// Virtual drive: the rover footprint is driven along the developing paths and axis cells
/// where it would not be safe are dropped: a kept cell has room for the footprint driven
/// straight through it (half its width of clearance); an axis cell of row j connects to one of
/// rows j + 1 .. j + lookahead / cell when the footprint driven straight between them stays
/// clear (every cell under the segment has half the width of clearance); and a path may turn
/// at a cell only when the turn is safe there (clearance >= Footprint::TurnClearance of the
/// angle between the connection it arrives by and the one it leaves by: W/2 for none, the turn
/// radius for sharp ones). Connections only go toward the goal, so the road map is a directed
/// acyclic graph ordered by row.
///
/// Search: the start anchor (where the rover can turn to any heading) connects to every kept
/// axis cell within connect_radius (in any row, so a route may begin by backing out), and kept
/// cells within connect_radius of the goal anchor connect to it, each when the straight drive
/// is clear. A depth-first search from the start, memoised on the connection a path arrives
/// by (the turn test depends on it; each connection is expanded once), finds the longest
/// connected path toward the goal: the path that reaches the goal if any does, else the one
/// that ends nearest to it (to the cell), and among those the shortest.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "rover/apl/roaman/options.hpp"
#include "rover/apl/roaman/planning_grid.hpp"
#include "rover/apl/roaman/problem.hpp"
#include "rover/base/status.hpp"

namespace rover::apl::roaman {

/// A free run of row j, cells [i0, i1], and its centre.
struct AxisRun {
  int j = 0;
  int i0 = 0, i1 = 0;
  int axis = 0;       ///< (i0 + i1) / 2
  bool kept = false;  ///< the footprint fits driving straight through the axis cell
};

struct RoadMap {
  std::vector<AxisRun> runs;    ///< row by row, left to right
  std::vector<int> row_first;   ///< runs of row j: [row_first[j], row_first[j + 1])
  std::vector<int> node_run;    ///< node k is the axis cell of runs[node_run[k]] (kept ones)
  std::vector<int> edge_first;  ///< successors of node k: edge_to[edge_first[k] ..
  std::vector<int> edge_to;     ///<   edge_first[k + 1])
  int dropped = 0;              ///< axis cells too narrow for the footprint

  int nodes() const { return static_cast<int>(node_run.size()); }
  Eigen::Vector2i NodeCell(int k) const {
    const AxisRun& r = runs[static_cast<std::size_t>(node_run[static_cast<std::size_t>(k)])];
    return {r.axis, r.j};
  }
};

/// Medial axis, virtual drive and connections.
RoadMap BuildRoadMap(const PlanningGrid& grid, const RoamanOptions& options);

struct RoadPath {
  /// [m] site: the start anchor, the road-map nodes, and the goal anchor when reached.
  std::vector<Eigen::Vector2d> vertices;
  std::vector<int> nodes;  ///< road-map nodes along the path
  bool reaches_goal = false;
  double length = 0.0;       ///< [m]
  double goal_distance = 0;  ///< [m] from the last vertex to the requested goal
  std::size_t expanded = 0;  ///< connections the search expanded
};

/// The depth-first search. Errors: NotFound when the path reaches neither the goal nor, for a
/// partial plan, at least min_progress nearer to it than the start anchor.
Result<RoadPath> LongestRoadPath(const RoadMap& road, const PlanProblem& problem,
                                 const RoamanOptions& options);

}  // namespace rover::apl::roaman
