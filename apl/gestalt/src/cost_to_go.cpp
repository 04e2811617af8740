#include "rover/apl/gestalt/cost_to_go.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "rover/base/check.hpp"

namespace rover::apl::gestalt {
namespace {

constexpr float kUnreached = std::numeric_limits<float>::infinity();

}  // namespace

CostToGo::CostToGo(const nav_core::GoodnessMap& map, const Eigen::Vector2d& goal,
                   const CostToGoOptions& options)
    : cost_(map.cell_count(), kUnreached), blocked_(map.cell_count(), 0) {
  // Preconditions (the options come from a validated GestaltOptions).
  ROVER_DEMAND(map.resolution > 0.0);
  ROVER_DEMAND(options.clearance >= 0.0 && options.goodness_weight >= 0.0);
  ROVER_DEMAND(options.unknown_cost_factor >= 1.0 && options.straddle_cost_factor >= 1.0);
  std::vector<std::uint8_t> near_low(options.straddle ? map.cell_count() : 0, 0);
  grid_.resolution = map.resolution;
  grid_.origin_x = map.origin_x;
  grid_.origin_y = map.origin_y;
  grid_.width = map.width;
  grid_.height = map.height;
  const int w = map.width, h = map.height;
  if (w <= 0 || h <= 0) return;
  // Blocked cells: near a hazard cell, or known and below the allowed goodness.
  const int reach = static_cast<int>(std::ceil(options.clearance / map.resolution));
  const double r2 = options.clearance * options.clearance;
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      const std::size_t k = map.Index(i, j);
      if ((map.flags[k] & nav_core::kCellKnown) != 0 &&
          map.goodness[k] < options.min_allowed_goodness) {
        blocked_[k] = 1;
      }
      if ((map.flags[k] & nav_core::kCellHazard) == 0) continue;
      std::uint8_t* mark = blocked_.data();
      if (options.straddle && (map.flags[k] & nav_core::kCellTall) == 0) mark = near_low.data();
      for (int dj = -reach; dj <= reach; ++dj) {
        for (int di = -reach; di <= reach; ++di) {
          if (!map.Contains(i + di, j + dj)) continue;
          const double d2 = (di * di + dj * dj) * map.resolution * map.resolution;
          if (d2 <= r2) mark[map.Index(i + di, j + dj)] = 1;
        }
      }
    }
  }
  using Item = std::pair<float, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  auto seed = [&](int i, int j, float c) {
    const std::size_t k = map.Index(i, j);
    if (blocked_[k] != 0 || c >= cost_[k]) return;
    cost_[k] = c;
    open.push({c, k});
  };
  int gi = 0, gj = 0;
  map.CellOf(goal.x(), goal.y(), &gi, &gj);
  if (map.Contains(gi, gj)) {
    seed(gi, gj, 0.0F);
  } else {
    for (int j = 0; j < h; ++j) {
      for (int i = 0; i < w; ++i) {
        if (i != 0 && j != 0 && i != w - 1 && j != h - 1) continue;
        seed(i, j, static_cast<float>((map.CellCenter(i, j) - goal).norm()));
      }
    }
  }
  auto step_factor = [&](std::size_t k) {
    double f = 1.0 + options.goodness_weight * (255.0 - map.goodness[k]) / 255.0;
    if ((map.flags[k] & nav_core::kCellKnown) == 0) f *= options.unknown_cost_factor;
    if (!near_low.empty() && near_low[k] != 0) f *= options.straddle_cost_factor;
    return f;
  };
  while (!open.empty()) {
    const auto [c, k] = open.top();
    open.pop();
    if (c > cost_[k]) continue;
    any_reachable_ = true;
    const int i = static_cast<int>(k % static_cast<std::size_t>(w));
    const int j = static_cast<int>(k / static_cast<std::size_t>(w));
    for (int dj = -1; dj <= 1; ++dj) {
      for (int di = -1; di <= 1; ++di) {
        if ((di == 0 && dj == 0) || !map.Contains(i + di, j + dj)) continue;
        const std::size_t n = map.Index(i + di, j + dj);
        if (blocked_[n] != 0) continue;
        const double len = map.resolution * ((di != 0 && dj != 0) ? std::sqrt(2.0) : 1.0);
        // A step costs the mean of its two cells' factors.
        const float nc =
            c + static_cast<float>(len * 0.5 * (step_factor(k) + step_factor(n)));
        if (nc < cost_[n]) {
          cost_[n] = nc;
          open.push({nc, n});
        }
      }
    }
  }
}

double CostToGo::Cost(double x, double y) const {
  int i = 0, j = 0;
  grid_.CellOf(x, y, &i, &j);
  if (!grid_.Contains(i, j)) return std::numeric_limits<double>::infinity();
  return cost_[grid_.Index(i, j)];
}

bool CostToGo::Blocked(double x, double y) const {
  int i = 0, j = 0;
  grid_.CellOf(x, y, &i, &j);
  return grid_.Contains(i, j) && blocked_[grid_.Index(i, j)] != 0;
}

}  // namespace rover::apl::gestalt
