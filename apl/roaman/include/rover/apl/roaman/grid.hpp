#pragma once
/// @file
/// Layer<T> (one value per cell of a width x height grid) and GridGeometry (where an
/// axis-aligned grid lies in the site frame). Header-only.
///
/// Indexing: cell (i, j), i = 0..width-1 (the first axis), j = 0..height-1 (the second);
/// storage row-major with row = j: index = j * width + i. In the site-frame map the first axis
/// is site x (north) and the second site y (west), as in nav_core::GoodnessMap; in the
/// goal-aligned planning grid (planning_grid.hpp) i runs across the goal direction and j toward
/// the goal, so a row (constant j) runs across the direction to the goal, as in FIDO.

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "rover/base/check.hpp"

namespace rover::apl::roaman {

template <class T>
class Layer {
 public:
  Layer() = default;
  /// Preconditions: width, height >= 0.
  Layer(int width, int height, const T& fill = T{})
      : width_(width), height_(height), v_(static_cast<std::size_t>(width) * height, fill) {
    ROVER_DEMAND(width >= 0 && height >= 0);
  }
  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t size() const { return v_.size(); }
  bool Contains(int i, int j) const { return i >= 0 && j >= 0 && i < width_ && j < height_; }
  std::size_t Index(int i, int j) const { return static_cast<std::size_t>(j) * width_ + i; }
  /// Preconditions: Contains(i, j).
  T& at(int i, int j) { return v_[Index(i, j)]; }
  const T& at(int i, int j) const { return v_[Index(i, j)]; }
  T& operator[](std::size_t k) { return v_[k]; }
  const T& operator[](std::size_t k) const { return v_[k]; }
  /// Cell (i, j), or `outside` when it is not in the grid.
  T Get(int i, int j, const T& outside) const { return Contains(i, j) ? at(i, j) : outside; }
  void Fill(const T& v) { std::fill(v_.begin(), v_.end(), v); }
  std::vector<T>& values() { return v_; }
  const std::vector<T>& values() const { return v_; }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<T> v_;
};

/// An axis-aligned grid in the site frame: cell (i, j) covers x in [origin_x + i c,
/// origin_x + (i + 1) c), y in [origin_y + j c, origin_y + (j + 1) c), c = cell (metres).
struct GridGeometry {
  double origin_x = 0.0;  ///< [m] site x of the corner of cell (0, 0)
  double origin_y = 0.0;  ///< [m] site y of the corner of cell (0, 0)
  double cell = 0.05;     ///< [m] cell side
  int width = 0;          ///< cells along x
  int height = 0;         ///< cells along y

  bool Contains(int i, int j) const { return i >= 0 && j >= 0 && i < width && j < height; }
  /// The cell containing site point (x, y) (possibly outside the grid).
  void CellOf(double x, double y, int* i, int* j) const {
    *i = static_cast<int>(std::floor((x - origin_x) / cell));
    *j = static_cast<int>(std::floor((y - origin_y) / cell));
  }
  /// [m] site coordinates of the centre of cell (i, j).
  Eigen::Vector2d Center(int i, int j) const {
    return {origin_x + (i + 0.5) * cell, origin_y + (j + 0.5) * cell};
  }
  double area_per_cell() const { return cell * cell; }
};

/// [m] distance from point p to the segment a-b (to a when a == b).
inline double DistanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                                const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

}  // namespace rover::apl::roaman
