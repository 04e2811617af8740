#pragma once
/// @file
/// Grid<T>: a dense width x height array of cells, row-major with row = j (index j * width + i),
/// that can scroll: Shift() moves the contents by whole cells so that a map can follow the rover
/// without resampling. Header-only.

#include <algorithm>
#include <cstddef>
#include <cstdlib>
#include <vector>

#include "rover/base/check.hpp"

namespace rover::apl::gestalt {

template <class T>
class Grid {
 public:
  Grid() = default;
  /// Preconditions: width, height >= 0.
  Grid(int width, int height, const T& fill = T{})
      : width_(width), height_(height), cells_(static_cast<std::size_t>(width) * height, fill) {
    ROVER_DEMAND(width >= 0 && height >= 0);
  }

  int width() const { return width_; }
  int height() const { return height_; }
  std::size_t size() const { return cells_.size(); }
  bool Contains(int i, int j) const { return i >= 0 && j >= 0 && i < width_ && j < height_; }
  std::size_t Index(int i, int j) const { return static_cast<std::size_t>(j) * width_ + i; }

  /// Preconditions: Contains(i, j) (checked only by the vector in debug builds).
  T& at(int i, int j) { return cells_[Index(i, j)]; }
  const T& at(int i, int j) const { return cells_[Index(i, j)]; }
  T& operator[](std::size_t k) { return cells_[k]; }
  const T& operator[](std::size_t k) const { return cells_[k]; }
  std::vector<T>& cells() { return cells_; }
  const std::vector<T>& cells() const { return cells_; }

  void Fill(const T& v) { std::fill(cells_.begin(), cells_.end(), v); }

  /// Scrolls the contents: afterwards cell (i, j) holds what cell (i + di, j + dj) held; cells
  /// whose source lies outside the grid become `fill`. (Used when the grid's origin moves by
  /// (di, dj) cells.)
  void Shift(int di, int dj, const T& fill) {
    if (di == 0 && dj == 0) return;
    if (std::abs(di) >= width_ || std::abs(dj) >= height_) {
      Fill(fill);
      return;
    }
    std::vector<T> moved(cells_.size(), fill);
    const int i_lo = std::max(0, -di), i_hi = std::min(width_, width_ - di);
    for (int j = std::max(0, -dj); j < std::min(height_, height_ - dj); ++j) {
      const std::size_t dst = Index(i_lo, j);
      const std::size_t src = Index(i_lo + di, j + dj);
      std::copy(cells_.begin() + static_cast<std::ptrdiff_t>(src),
                cells_.begin() + static_cast<std::ptrdiff_t>(src + (i_hi - i_lo)),
                moved.begin() + static_cast<std::ptrdiff_t>(dst));
    }
    cells_.swap(moved);
  }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<T> cells_;
};

}  // namespace rover::apl::gestalt
