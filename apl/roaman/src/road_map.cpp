#include "rover/apl/roaman/road_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "rover/base/format.hpp"

namespace rover::apl::roaman {

RoadMap BuildRoadMap(const PlanningGrid& grid, const RoamanOptions& options) {
  RoadMap road;
  const double turn = options.turn_radius();
  const double leg = options.leg_clearance();
  // Medial axis and virtual drive (the turn test), row by row.
  road.row_first.reserve(static_cast<std::size_t>(grid.height) + 1);
  for (int j = 0; j < grid.height; ++j) {
    road.row_first.push_back(static_cast<int>(road.runs.size()));
    int i = 0;
    while (i < grid.width) {
      if (grid.cls.at(i, j) != CellClass::kSafe) {
        ++i;
        continue;
      }
      AxisRun r;
      r.j = j;
      r.i0 = i;
      while (i < grid.width && grid.cls.at(i, j) == CellClass::kSafe) ++i;
      r.i1 = i - 1;
      r.axis = (r.i0 + r.i1) / 2;
      r.kept = grid.clearance.at(r.axis, j) >= turn;
      if (r.kept) {
        road.node_run.push_back(static_cast<int>(road.runs.size()));
      } else {
        ++road.dropped;
      }
      road.runs.push_back(r);
    }
  }
  road.row_first.push_back(static_cast<int>(road.runs.size()));

  // Node index of each run (-1 for dropped ones), then connections toward the goal.
  std::vector<int> node_of_run(road.runs.size(), -1);
  for (int k = 0; k < road.nodes(); ++k) node_of_run[static_cast<std::size_t>(road.node_run[k])] = k;
  const int rows_ahead = std::max(1, static_cast<int>(std::lround(options.lookahead / grid.cell)));
  road.edge_first.reserve(road.node_run.size() + 1);
  for (int k = 0; k < road.nodes(); ++k) {
    road.edge_first.push_back(static_cast<int>(road.edge_to.size()));
    const Eigen::Vector2i a = road.NodeCell(k);
    const Eigen::Vector2d pa = grid.Center(a.x(), a.y());
    for (int j = a.y() + 1; j <= std::min(grid.height - 1, a.y() + rows_ahead); ++j) {
      for (int r = road.row_first[j]; r < road.row_first[j + 1]; ++r) {
        const int m = node_of_run[static_cast<std::size_t>(r)];
        if (m < 0) continue;
        const Eigen::Vector2i b = road.NodeCell(m);
        if (grid.SegmentClear(pa, grid.Center(b.x(), b.y()), leg)) road.edge_to.push_back(m);
      }
    }
  }
  road.edge_first.push_back(static_cast<int>(road.edge_to.size()));
  return road;
}

namespace {

// The best continuation from a node: reaches the goal, then ends nearer to it (in whole cells),
// then is shorter.
struct Best {
  bool reach = false;
  long end_cells = std::numeric_limits<long>::max();
  double length = 0.0;
  int next = -1;  // successor node, kGoalNext for the goal, -1 to stop here
};
constexpr int kGoalNext = -2;

bool Better(bool reach, long end_cells, double length, const Best& b) {
  if (reach != b.reach) return reach;
  if (end_cells != b.end_cells) return end_cells < b.end_cells;
  return length < b.length;
}

}  // namespace

Result<RoadPath> LongestRoadPath(const RoadMap& road, const PlanProblem& problem,
                                 const RoamanOptions& options) {
  const PlanningGrid& grid = problem.grid;
  const Eigen::Vector2d goal = problem.request.goal;
  const int n = road.nodes();
  std::vector<Eigen::Vector2d> pos(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2i c = road.NodeCell(k);
    pos[static_cast<std::size_t>(k)] = grid.Center(c.x(), c.y());
  }
  const auto end_cells = [&](const Eigen::Vector2d& p) {
    return static_cast<long>(std::floor((p - goal).norm() / grid.cell));
  };
  // Which nodes connect straight to the goal anchor.
  std::vector<std::uint8_t> to_goal(static_cast<std::size_t>(n), 0);
  if (problem.goal_on_grid) {
    for (int k = 0; k < n; ++k) {
      const Eigen::Vector2d& p = pos[static_cast<std::size_t>(k)];
      if ((p - problem.goal_anchor).norm() <= options.connect_radius &&
          grid.SegmentClear(p, problem.goal_anchor, problem.leg_clearance)) {
        to_goal[static_cast<std::size_t>(k)] = 1;
      }
    }
  }

  // Depth-first search with memoisation, iteratively (post-order).
  std::vector<Best> best(static_cast<std::size_t>(n));
  std::vector<std::uint8_t> state(static_cast<std::size_t>(n), 0);  // 0 new, 1 open, 2 done
  std::size_t expanded = 0;
  const auto finish = [&](int k) {
    Best b;
    const Eigen::Vector2d& p = pos[static_cast<std::size_t>(k)];
    b.end_cells = end_cells(p);  // stopping here
    if (to_goal[static_cast<std::size_t>(k)]) {
      b = {true, 0, (p - problem.goal_anchor).norm(), kGoalNext};
    }
    for (int e = road.edge_first[k]; e < road.edge_first[k + 1]; ++e) {
      const int m = road.edge_to[static_cast<std::size_t>(e)];
      const Best& c = best[static_cast<std::size_t>(m)];
      const double len = c.length + (pos[static_cast<std::size_t>(m)] - p).norm();
      if (Better(c.reach, c.end_cells, len, b)) b = {c.reach, c.end_cells, len, m};
    }
    best[static_cast<std::size_t>(k)] = b;
    state[static_cast<std::size_t>(k)] = 2;
  };
  const auto visit = [&](int root) {
    if (state[static_cast<std::size_t>(root)] == 2) return;
    std::vector<std::pair<int, int>> stack{{root, road.edge_first[root]}};
    state[static_cast<std::size_t>(root)] = 1;
    ++expanded;
    while (!stack.empty()) {
      auto& [k, e] = stack.back();
      if (e < road.edge_first[k + 1]) {
        const int m = road.edge_to[static_cast<std::size_t>(e++)];
        if (state[static_cast<std::size_t>(m)] == 0) {
          state[static_cast<std::size_t>(m)] = 1;
          ++expanded;
          stack.emplace_back(m, road.edge_first[m]);
        }
        continue;
      }
      finish(k);
      stack.pop_back();
    }
  };

  // The start anchor: straight to the goal, or to axis cells within connect_radius.
  const Eigen::Vector2d s = problem.start_anchor;
  Best start;
  start.end_cells = end_cells(s);
  if (problem.goal_on_grid && grid.SegmentClear(s, problem.goal_anchor, problem.leg_clearance) &&
      ((s - problem.goal_anchor).norm() <= options.connect_radius)) {
    start = {true, 0, (s - problem.goal_anchor).norm(), kGoalNext};
  }
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d& p = pos[static_cast<std::size_t>(k)];
    if ((p - s).norm() > options.connect_radius) continue;
    if (!grid.SegmentClear(s, p, problem.leg_clearance)) continue;
    visit(k);
    const Best& c = best[static_cast<std::size_t>(k)];
    const double len = c.length + (p - s).norm();
    if (Better(c.reach, c.end_cells, len, start)) start = {c.reach, c.end_cells, len, k};
  }

  RoadPath path;
  path.expanded = expanded;
  path.vertices.push_back(s);
  for (int k = start.next; k >= 0; k = best[static_cast<std::size_t>(k)].next) {
    path.nodes.push_back(k);
    path.vertices.push_back(pos[static_cast<std::size_t>(k)]);
  }
  path.reaches_goal = start.reach;
  if (path.reaches_goal) path.vertices.push_back(problem.goal_anchor);
  path.length = start.length;
  path.goal_distance = (path.vertices.back() - goal).norm();
  if (!path.reaches_goal) {
    const double progress = (s - goal).norm() - path.goal_distance;
    if (problem.goal_on_grid || progress < options.min_progress) {
      return NotFound(
          std::string("road map: ") +
          (problem.goal_on_grid ? "no connected path reaches the goal anchor " +
                                      FormatPoint(problem.goal_anchor)
                                : "no connected path gets " + FormatNumber(options.min_progress, 3) +
                                      " m nearer the goal " + FormatPoint(goal)) +
          " (" + std::to_string(n) + " axis cells kept, " + std::to_string(road.dropped) +
          " dropped; the best path ends " + FormatNumber(path.goal_distance, 4) + " m from it)");
    }
  }
  return path;
}

}  // namespace rover::apl::roaman
