#include "rover/apl/roaman/road_map.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "rover/apl/roaman/waypoint_fit.hpp"
#include "rover/base/format.hpp"

namespace rover::apl::roaman {

RoadMap BuildRoadMap(const PlanningGrid& grid, const RoamanOptions& options) {
  RoadMap road;
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
      r.kept = grid.clearance.at(r.axis, j) >= leg;
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
  for (int k = 0; k < road.nodes(); ++k)
    node_of_run[static_cast<std::size_t>(road.node_run[k])] = k;
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

// The best continuation after arriving somewhere: reaches the goal, then ends nearer to it (in
// whole cells), then is shorter.
struct Best {
  bool reach = false;
  long end_cells = std::numeric_limits<long>::max();
  double length = 0.0;
  int next = -1;  // connection to take next, kGoalNext for the goal, -1 to stop here
};
constexpr int kGoalNext = -2;

bool Better(const Best& a, const Best& b) {
  if (a.reach != b.reach) return a.reach;
  if (a.end_cells != b.end_cells) return a.end_cells < b.end_cells;
  return a.length < b.length;
}

}  // namespace

Result<RoadPath> LongestRoadPath(const RoadMap& road, const PlanProblem& problem,
                                 const RoamanOptions& options) {
  const PlanningGrid& grid = problem.grid;
  const Footprint& fp = problem.footprint;
  const Eigen::Vector2d goal = problem.request.goal;
  const int n = road.nodes();
  const std::size_t edges = road.edge_to.size();
  std::vector<Eigen::Vector2d> pos(static_cast<std::size_t>(n));
  std::vector<double> clearance(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2i c = road.NodeCell(k);
    pos[static_cast<std::size_t>(k)] = grid.Center(c.x(), c.y());
    clearance[static_cast<std::size_t>(k)] = grid.clearance.at(c.x(), c.y());
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
  // The head node of every connection.
  std::vector<int> head(edges), tail(edges);
  for (int k = 0; k < n; ++k) {
    for (int e = road.edge_first[k]; e < road.edge_first[k + 1]; ++e) {
      tail[static_cast<std::size_t>(e)] = k;
      head[static_cast<std::size_t>(e)] = road.edge_to[static_cast<std::size_t>(e)];
    }
  }

  // The best continuation from node b having arrived from point `from`, given the results of
  // all b's connections.
  std::vector<Best> after(edges);
  const auto turn_ok = [&](const Eigen::Vector2d& from, int b, const Eigen::Vector2d& to) {
    return clearance[static_cast<std::size_t>(b)] >=
           fp.TurnClearance(TurnAngle(from, pos[static_cast<std::size_t>(b)], to));
  };
  const auto continue_from = [&](const Eigen::Vector2d& from, int b) {
    const Eigen::Vector2d& p = pos[static_cast<std::size_t>(b)];
    Best best;
    best.end_cells = end_cells(p);  // stopping here
    if (to_goal[static_cast<std::size_t>(b)] && turn_ok(from, b, problem.goal_anchor)) {
      best = {true, 0, (p - problem.goal_anchor).norm(), kGoalNext};
    }
    for (int f = road.edge_first[b]; f < road.edge_first[b + 1]; ++f) {
      const int c = head[static_cast<std::size_t>(f)];
      const Eigen::Vector2d& q = pos[static_cast<std::size_t>(c)];
      if (!turn_ok(from, b, q)) continue;
      Best cand = after[static_cast<std::size_t>(f)];
      cand.length += (q - p).norm();
      cand.next = f;
      if (Better(cand, best)) best = cand;
    }
    return best;
  };

  // Depth-first search over connections, iteratively (post-order), memoised.
  std::vector<std::uint8_t> state(edges, 0);  // 0 new, 1 open, 2 done
  std::size_t expanded = 0;
  const auto visit_out = [&](int b) {        // makes every connection out of node b done
    std::vector<std::pair<int, int>> stack;  // (connection, next connection of its head)
    for (int root = road.edge_first[b]; root < road.edge_first[b + 1]; ++root) {
      if (state[static_cast<std::size_t>(root)] != 0) continue;
      state[static_cast<std::size_t>(root)] = 1;
      ++expanded;
      stack.emplace_back(root, road.edge_first[head[static_cast<std::size_t>(root)]]);
      while (!stack.empty()) {
        auto& [e, f] = stack.back();
        const int h = head[static_cast<std::size_t>(e)];
        if (f < road.edge_first[h + 1]) {
          const int g = f++;
          if (state[static_cast<std::size_t>(g)] == 0) {
            state[static_cast<std::size_t>(g)] = 1;
            ++expanded;
            stack.emplace_back(g, road.edge_first[head[static_cast<std::size_t>(g)]]);
          }
          continue;
        }
        after[static_cast<std::size_t>(e)] =
            continue_from(pos[static_cast<std::size_t>(tail[static_cast<std::size_t>(e)])], h);
        state[static_cast<std::size_t>(e)] = 2;
        stack.pop_back();
      }
    }
  };

  // The start anchor: any heading is safe there (it has the turn radius); straight to the goal,
  // or to axis cells within connect_radius.
  const Eigen::Vector2d s = problem.start_anchor;
  Best start;
  start.end_cells = end_cells(s);
  if (problem.goal_on_grid && (s - problem.goal_anchor).norm() <= options.connect_radius &&
      grid.SegmentClear(s, problem.goal_anchor, problem.leg_clearance)) {
    start = {true, 0, (s - problem.goal_anchor).norm(), kGoalNext};
  }
  int first = -1;
  for (int k = 0; k < n; ++k) {
    const Eigen::Vector2d& p = pos[static_cast<std::size_t>(k)];
    if ((p - s).norm() > options.connect_radius) continue;
    if (!grid.SegmentClear(s, p, problem.leg_clearance)) continue;
    visit_out(k);
    Best c = continue_from(s, k);
    c.length += (p - s).norm();
    if (Better(c, start)) {
      start = c;
      first = k;
    }
  }

  RoadPath path;
  path.expanded = expanded;
  path.vertices.push_back(s);
  if (first >= 0) {
    path.nodes.push_back(first);
    path.vertices.push_back(pos[static_cast<std::size_t>(first)]);
    for (int e = start.next; e >= 0; e = after[static_cast<std::size_t>(e)].next) {
      const int h = head[static_cast<std::size_t>(e)];
      path.nodes.push_back(h);
      path.vertices.push_back(pos[static_cast<std::size_t>(h)]);
    }
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
          (problem.goal_on_grid
               ? "no connected path reaches the goal anchor " + FormatPoint(problem.goal_anchor)
               : "no connected path gets " + FormatNumber(options.min_progress, 3) +
                     " m nearer the goal " + FormatPoint(goal)) +
          " (" + std::to_string(n) + " axis cells kept, " + std::to_string(road.dropped) +
          " dropped; the best path ends " + FormatNumber(path.goal_distance, 4) + " m from it)");
    }
  }
  return path;
}

}  // namespace rover::apl::roaman
