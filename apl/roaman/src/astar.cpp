#include "rover/apl/roaman/astar.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <string>

#include "rover/base/format.hpp"

namespace rover::apl::roaman {
namespace {

constexpr int kMoves[8][2] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {1, -1}, {-1, 1}, {-1, -1}};

bool InGraph(const PlanningGrid& g, int i, int j, double min_clearance) {
  return g.Contains(i, j) && g.clearance.at(i, j) >= min_clearance;
}

bool MoveAllowed(const PlanningGrid& g, int i, int j, int di, int dj, double min_clearance) {
  if (!InGraph(g, i + di, j + dj, min_clearance)) return false;
  if (di != 0 && dj != 0) {
    return InGraph(g, i + di, j, min_clearance) && InGraph(g, i, j + dj, min_clearance);
  }
  return true;
}

double Penalty(const PlanningGrid& g, int i, int j, const SearchCost& c) {
  return std::max(0.0, 1.0 - g.clearance.at(i, j) / c.clearance_ref);
}

struct Open {
  double f;
  double g;
  int index;
  // Smallest f first; among equals the deeper node (larger g), then the lower index.
  bool operator>(const Open& o) const {
    if (f != o.f) return f > o.f;
    if (g != o.g) return g < o.g;
    return index > o.index;
  }
};

Result<GridPath> Search(const PlanningGrid& grid, Eigen::Vector2i from, Eigen::Vector2i to,
                        const SearchCost& cost, bool heuristic) {
  for (const auto& [name, c] : {std::pair{"from", from}, std::pair{"to", to}}) {
    if (!grid.Contains(c.x(), c.y())) {
      return InvalidArgument(std::string("grid search: ") + name + " cell (" +
                             std::to_string(c.x()) + ", " + std::to_string(c.y()) +
                             ") is outside the " + std::to_string(grid.width) + " x " +
                             std::to_string(grid.height) + " grid");
    }
    if (!InGraph(grid, c.x(), c.y(), cost.min_clearance)) {
      return InvalidArgument(std::string("grid search: ") + name + " cell (" +
                             std::to_string(c.x()) + ", " + std::to_string(c.y()) +
                             ") has clearance " + FormatNumber(grid.clearance.at(c.x(), c.y()), 3) +
                             " m, below the " + FormatNumber(cost.min_clearance, 3) + " m needed");
    }
  }
  const int w = grid.width;
  const std::size_t n = static_cast<std::size_t>(w) * grid.height;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> g(n, inf);
  std::vector<double> len(n, 0.0);
  std::vector<int> parent(n, -1);
  std::vector<std::uint8_t> closed(n, 0);
  const auto h = [&](int i, int j) {
    if (!heuristic) return 0.0;
    const double dx = std::abs(i - to.x()), dy = std::abs(j - to.y());
    return grid.cell * (std::max(dx, dy) + (std::sqrt(2.0) - 1.0) * std::min(dx, dy));
  };
  std::priority_queue<Open, std::vector<Open>, std::greater<>> open;
  const int start = from.y() * w + from.x();
  const int goal = to.y() * w + to.x();
  g[start] = 0.0;
  open.push({h(from.x(), from.y()), 0.0, start});
  GridPath path;
  while (!open.empty()) {
    const Open top = open.top();
    open.pop();
    if (closed[top.index]) continue;
    closed[top.index] = 1;
    ++path.expanded;
    if (top.index == goal) break;
    const int i = top.index % w, j = top.index / w;
    const double pi = Penalty(grid, i, j, cost);
    for (const auto& m : kMoves) {
      if (!MoveAllowed(grid, i, j, m[0], m[1], cost.min_clearance)) continue;
      const int ni = i + m[0], nj = j + m[1];
      const int k = nj * w + ni;
      if (closed[k]) continue;
      const double step = grid.cell * ((m[0] != 0 && m[1] != 0) ? std::sqrt(2.0) : 1.0);
      const double c =
          step * (1.0 + cost.clearance_weight * 0.5 * (pi + Penalty(grid, ni, nj, cost)));
      if (g[top.index] + c < g[k]) {
        g[k] = g[top.index] + c;
        len[k] = len[top.index] + step;
        parent[k] = top.index;
        open.push({g[k] + h(ni, nj), g[k], k});
      }
    }
  }
  if (!closed[goal]) {
    return NotFound("grid search: no path from cell (" + std::to_string(from.x()) + ", " +
                    std::to_string(from.y()) + ") to cell (" + std::to_string(to.x()) + ", " +
                    std::to_string(to.y()) +
                    ") over cells with clearance >= " + FormatNumber(cost.min_clearance, 3) + " m");
  }
  path.cost = g[goal];
  path.length = len[goal];
  for (int k = goal; k >= 0; k = parent[k]) path.cells.emplace_back(k % w, k / w);
  std::reverse(path.cells.begin(), path.cells.end());
  return path;
}

}  // namespace

Result<GridPath> AStarSearch(const PlanningGrid& grid, Eigen::Vector2i from, Eigen::Vector2i to,
                             const SearchCost& cost) {
  return Search(grid, from, to, cost, true);
}

Result<GridPath> DijkstraSearch(const PlanningGrid& grid, Eigen::Vector2i from, Eigen::Vector2i to,
                                const SearchCost& cost) {
  return Search(grid, from, to, cost, false);
}

Layer<std::uint8_t> ReachableCells(const PlanningGrid& grid, Eigen::Vector2i from,
                                   double min_clearance) {
  Layer<std::uint8_t> out(grid.width, grid.height, 0);
  if (!InGraph(grid, from.x(), from.y(), min_clearance)) return out;
  std::vector<Eigen::Vector2i> stack{from};
  out.at(from.x(), from.y()) = 1;
  while (!stack.empty()) {
    const Eigen::Vector2i c = stack.back();
    stack.pop_back();
    for (const auto& m : kMoves) {
      if (!MoveAllowed(grid, c.x(), c.y(), m[0], m[1], min_clearance)) continue;
      const int ni = c.x() + m[0], nj = c.y() + m[1];
      if (out.at(ni, nj)) continue;
      out.at(ni, nj) = 1;
      stack.emplace_back(ni, nj);
    }
  }
  return out;
}

std::vector<Eigen::Vector2d> PullString(const PlanningGrid& grid,
                                        const std::vector<Eigen::Vector2d>& points,
                                        const Footprint& footprint) {
  std::vector<Eigen::Vector2d> out;
  if (points.empty()) return out;
  const double leg = footprint.leg_clearance(), turn = footprint.turn_radius();
  out.push_back(points.front());
  std::size_t a = 0;
  while (a + 1 < points.size()) {
    std::size_t b = a + 1;
    while (b + 1 < points.size() && grid.SegmentClear(points[a], points[b + 1], leg)) ++b;
    if (b + 1 < points.size()) {
      for (std::size_t q = b; q > a; --q) {
        if (grid.ClearanceAt(points[q]) >= turn) {
          b = q;
          break;
        }
      }
    }
    out.push_back(points[b]);
    a = b;
  }
  return out;
}

double PolylineLength(const std::vector<Eigen::Vector2d>& points) {
  double l = 0.0;
  for (std::size_t k = 1; k < points.size(); ++k) l += (points[k] - points[k - 1]).norm();
  return l;
}

}  // namespace rover::apl::roaman
