#include "rover/apl/roaman/planning_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rover/apl/roaman/distance_transform.hpp"

namespace rover::apl::roaman {

GoalFrame GoalFrame::Toward(const Eigen::Vector2d& start, const Eigen::Vector2d& goal) {
  const Eigen::Vector2d d = goal - start;
  ROVER_DEMAND(d.norm() > 0.0);
  GoalFrame f;
  f.origin = start;
  f.u = d.normalized();
  f.w = Eigen::Vector2d(-f.u.y(), f.u.x());
  return f;
}

bool PlanningGrid::CellOf(const Eigen::Vector2d& p, int* i, int* j) const {
  const Eigen::Vector2d q = frame.ToFrame(p);
  *i = static_cast<int>(std::floor((q.y() - across0) / cell));
  *j = static_cast<int>(std::floor((q.x() - along0) / cell));
  return Contains(*i, *j);
}

double PlanningGrid::ClearanceAt(const Eigen::Vector2d& p) const {
  int i = 0, j = 0;
  return CellOf(p, &i, &j) ? clearance.at(i, j) : 0.0;
}

CellClass PlanningGrid::ClassAt(const Eigen::Vector2d& p) const {
  int i = 0, j = 0;
  return CellOf(p, &i, &j) ? cls.at(i, j) : CellClass::kMissing;
}

bool PlanningGrid::SegmentClear(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                                double min_clearance) const {
  const double len = (b - a).norm();
  const int n = std::max(1, static_cast<int>(std::ceil(len / (0.5 * cell))));
  for (int k = 0; k <= n; ++k) {
    if (ClearanceAt(a + (b - a) * (static_cast<double>(k) / n)) < min_clearance) return false;
  }
  return true;
}

double PlanningGrid::MinClearanceAlong(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const {
  const double len = (b - a).norm();
  const int n = std::max(1, static_cast<int>(std::ceil(len / (0.5 * cell))));
  double m = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= n; ++k) {
    m = std::min(m, ClearanceAt(a + (b - a) * (static_cast<double>(k) / n)));
  }
  return m;
}

void ComputeClearance(PlanningGrid* grid) {
  Layer<std::uint8_t> blocked(grid->width, grid->height, 0);
  for (std::size_t k = 0; k < blocked.size(); ++k) {
    blocked[k] = grid->cls[k] != CellClass::kSafe ? 1 : 0;
  }
  const Layer<float> d = DistanceTransform(blocked);
  grid->clearance = Layer<float>(grid->width, grid->height, 0.0f);
  for (int j = 0; j < grid->height; ++j) {
    for (int i = 0; i < grid->width; ++i) {
      if (blocked.at(i, j)) continue;
      const double to_hazard = (static_cast<double>(d.at(i, j)) - 0.5) * grid->cell;
      const double to_edge =
          std::min({i + 0.5, grid->width - i - 0.5, j + 0.5, grid->height - j - 0.5}) * grid->cell;
      grid->clearance.at(i, j) = static_cast<float>(std::min(to_hazard, to_edge));
    }
  }
}

PlanningGrid BuildPlanningGrid(const TraversabilityMap& map, const Eigen::Vector2d& start,
                               const Eigen::Vector2d& goal, double along_max,
                               const RoamanOptions& options) {
  PlanningGrid g;
  g.frame = GoalFrame::Toward(start, goal);
  g.cell = options.cell_size;
  g.width = std::max(1, static_cast<int>(std::lround(options.plan_width / g.cell)));
  g.across0 = -0.5 * g.width * g.cell;
  g.along0 = -options.plan_back;
  g.height = std::max(1, static_cast<int>(std::ceil((along_max - g.along0) / g.cell - 1e-9)));
  g.cls = Layer<CellClass>(g.width, g.height, CellClass::kMissing);

  const GridGeometry& s = map.geometry;
  const double clear2 = options.start_clear_radius * options.start_clear_radius;
  for (int j = 0; j < g.height; ++j) {
    for (int i = 0; i < g.width; ++i) {
      const Eigen::Vector2d p = g.Center(i, j);
      CellClass c = CellClass::kSafe;
      if (s.width == 0) {
        c = CellClass::kMissing;
      } else {
        // The site cells whose centres surround p.
        const int si = static_cast<int>(std::floor((p.x() - s.origin_x) / s.cell - 0.5));
        const int sj = static_cast<int>(std::floor((p.y() - s.origin_y) / s.cell - 0.5));
        for (int dj = 0; dj <= 1; ++dj) {
          for (int di = 0; di <= 1; ++di) {
            const CellClass q = map.cls.Get(si + di, sj + dj, CellClass::kMissing);
            if (q > c) c = q;
          }
        }
      }
      if ((c == CellClass::kMissing || c == CellClass::kBorder) &&
          (p - start).squaredNorm() <= clear2) {
        c = CellClass::kSafe;
      }
      g.cls.at(i, j) = c;
    }
  }
  ComputeClearance(&g);
  return g;
}

}  // namespace rover::apl::roaman
