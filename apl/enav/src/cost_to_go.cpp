#include "rover/apl/enav/cost_to_go.hpp"

#include "rover/apl/enav/clearance.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <queue>
#include <utility>

namespace rover::apl::enav {
namespace {
constexpr float kUnreached = std::numeric_limits<float>::infinity();
}  // namespace

bool CostToGoField::Cell(const Eigen::Vector2d& xy, int* i, int* j) const {
  *i = static_cast<int>(std::floor((xy.x() - origin_.x()) / resolution_));
  *j = static_cast<int>(std::floor((xy.y() - origin_.y()) / resolution_));
  return *i >= 0 && *j >= 0 && *i < width_ && *j < height_;
}

double CostToGoField::Cost(const Eigen::Vector2d& xy) const {
  int i = 0, j = 0;
  if (!Cell(xy, &i, &j)) return kUnreached;
  return cost_[static_cast<std::size_t>(j) * width_ + i];
}

double CostToGoField::Factor(const Eigen::Vector2d& xy) const {
  int i = 0, j = 0;
  if (!Cell(xy, &i, &j)) return unknown_factor_;
  return factor_[static_cast<std::size_t>(j) * width_ + i];
}

bool CostToGoField::Update(const HeightTerrain& terrain, const Eigen::Vector2d& goal,
                           double tolerance) {
  const nav_core::HeightMap& m = *terrain.height_map();
  if (m.revision == revision_ && goal == goal_ && tolerance == tolerance_) return false;
  revision_ = m.revision;
  goal_ = goal;
  tolerance_ = tolerance;
  searches_ += 1;
  const EnavOptions& o = terrain.options();
  const int f = static_cast<int>(std::lround(o.cost_cell_size / m.resolution));
  resolution_ = m.resolution * f;
  unknown_factor_ = o.unknown_cost_factor;
  origin_ = {m.origin_x, m.origin_y};
  width_ = m.width / f;
  height_ = m.height / f;
  const std::size_t cells = static_cast<std::size_t>(width_) * height_;
  factor_.assign(cells, 1.0F);
  cost_.assign(cells, kUnreached);
  const std::vector<float>& dw = terrain.distance(HazardLayer::kWheel);
  const std::vector<float>& db = terrain.distance(HazardLayer::kBody);
  const ClearanceChecker checker(terrain);
  double reach = 0.0;  // farthest point of any part disc from the rover's origin, padded
  for (const PartDisc& d : checker.discs()) reach = std::max(reach, d.centre.norm() + d.radius);
  reach += o.planar_margin + o.cell_size;
  for (int j = 0; j < height_; ++j) {
    for (int i = 0; i < width_; ++i) {
      bool known = false;
      float w = kUnreached, b = kUnreached;
      for (int dj = 0; dj < f; ++dj) {
        for (int di = 0; di < f; ++di) {
          const std::size_t k = m.Index(i * f + di, j * f + dj);
          known = known || m.count[k] > 0;
          w = std::min(w, dw[k]);
          b = std::min(b, db[k]);
        }
      }
      float& fac = factor_[static_cast<std::size_t>(j) * width_ + i];
      if (b < o.blocked_radius) {
        fac = kUnreached;
        continue;
      }
      // Configuration space: blocked when the rover fits here in none of the headings tried
      // (only near hazards: farther than every part's reach nothing can touch).
      const Eigen::Vector2d centre = origin_ + resolution_ * Eigen::Vector2d(i + 0.5, j + 0.5);
      if (cspace_ && o.cspace_headings > 0 && std::min(w, b) < reach) {
        bool fits = false;
        for (int h = 0; h < o.cspace_headings && !fits; ++h) {
          const double heading = std::numbers::pi * h / o.cspace_headings;
          fits = checker.CheckPose({centre.x(), centre.y(), heading}, false).ok;
        }
        if (!fits) {
          fac = kUnreached;
          continue;
        }
      }
      double v = known ? 1.0 : o.unknown_cost_factor;
      if (o.hazard_cost_radius > 0.0 && w < o.hazard_cost_radius) {
        v *= 1.0 + o.hazard_cost_factor * (1.0 - w / o.hazard_cost_radius);
      }
      fac = static_cast<float>(v);
    }
  }
  using Item = std::pair<float, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  auto seed = [&](int i, int j, float c) {
    const std::size_t k = static_cast<std::size_t>(j) * width_ + i;
    if (!std::isfinite(factor_[k]) || c >= cost_[k]) return;
    cost_[k] = c;
    open.push({c, k});
  };
  int gi = 0, gj = 0;
  bool seeded = false;
  if (Cell(goal, &gi, &gj)) {
    // The goal's cell and every cell whose centre lies within the tolerance.
    const int r = static_cast<int>(std::ceil(tolerance / resolution_));
    for (int j = std::max(0, gj - r); j <= std::min(height_ - 1, gj + r); ++j) {
      for (int i = std::max(0, gi - r); i <= std::min(width_ - 1, gi + r); ++i) {
        const Eigen::Vector2d c = origin_ + resolution_ * Eigen::Vector2d(i + 0.5, j + 0.5);
        if ((i != gi || j != gj) && (c - goal).norm() > tolerance) continue;
        if (!std::isfinite(factor_[static_cast<std::size_t>(j) * width_ + i])) continue;
        seed(i, j, 0.0F);
        seeded = true;
      }
    }
  }
  if (!seeded) {
    for (int j = 0; j < height_; ++j) {
      for (int i = 0; i < width_; ++i) {
        if (i != 0 && j != 0 && i != width_ - 1 && j != height_ - 1) continue;
        const Eigen::Vector2d c = origin_ + resolution_ * Eigen::Vector2d(i + 0.5, j + 0.5);
        seed(i, j, static_cast<float>((c - goal).norm() * o.unknown_cost_factor));
      }
    }
  }
  static constexpr int kDi[8] = {1, -1, 0, 0, 1, 1, -1, -1};
  static constexpr int kDj[8] = {0, 0, 1, -1, 1, -1, 1, -1};
  const float diag = static_cast<float>(std::sqrt(2.0) * resolution_);
  const float straight = static_cast<float>(resolution_);
  while (!open.empty()) {
    const auto [c, k] = open.top();
    open.pop();
    if (c > cost_[k]) continue;
    const int i = static_cast<int>(k % width_), j = static_cast<int>(k / width_);
    for (int n = 0; n < 8; ++n) {
      const int ni = i + kDi[n], nj = j + kDj[n];
      if (ni < 0 || nj < 0 || ni >= width_ || nj >= height_) continue;
      const std::size_t nk = static_cast<std::size_t>(nj) * width_ + ni;
      if (!std::isfinite(factor_[nk])) continue;
      const float len = n < 4 ? straight : diag;
      const float nc = c + len * 0.5F * (factor_[k] + factor_[nk]);
      if (nc < cost_[nk]) {
        cost_[nk] = nc;
        open.push({nc, nk});
      }
    }
  }
  return true;
}

}  // namespace rover::apl::enav
