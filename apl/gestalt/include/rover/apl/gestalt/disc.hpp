#pragma once
/// @file
/// Discs of cells and the fast sums and filters over them that make GESTALT incremental.
///
/// A disc of radius r (in cells) about cell (i, j) is the set of cells (i + dx, j + dy) with
/// dx² + dy² <= r², stored as row spans: for dy in [-R, R] (R = floor(r)), dx in [-w(dy), w(dy)]
/// with w(dy) = floor(sqrt(r² - dy²)). MER's 2.6 m rover disc at 0.2 m cells is r = 6.5: 13 rows,
/// 137 cells.
///
/// Disc sums use row prefix sums: P(j, i) = Σ_{i' < i} v(j, i'), so a disc's sum is
/// Σ_dy P(j + dy, i + w(dy) + 1) - P(j + dy, i - w(dy)), 2 (2R + 1) lookups whatever the disc's
/// size, instead of one per cell. Cells outside the grid count as empty.
///
/// Disc filters (grey-level morphology): DiscMax / DiscMin replace each cell by the largest /
/// smallest value in its disc, skipping cells that hold `absent`. They run as a 1-D sliding
/// extreme along each row per distinct half-width (van Herk / Gil-Werman: three comparisons per
/// cell whatever the width), then a column combination over the disc's rows.

#include <cstdint>
#include <vector>

#include "rover/apl/gestalt/grid.hpp"

namespace rover::apl::gestalt {

class DiscSpans {
 public:
  DiscSpans() = default;
  /// Preconditions: radius >= 0.
  explicit DiscSpans(double radius_cells);

  int radius() const { return radius_; }  ///< R: rows span dy in [-R, R]
  int half_width(int dy) const { return half_widths_[static_cast<std::size_t>(dy + radius_)]; }
  int cell_count() const { return cell_count_; }
  bool Contains(int dx, int dy) const {
    return dy >= -radius_ && dy <= radius_ && dx >= -half_width(dy) && dx <= half_width(dy);
  }

 private:
  int radius_ = 0;
  int cell_count_ = 1;
  std::vector<int> half_widths_{0};
};

/// Row prefix sums of a grid of additive values (Moments, counts).
template <class T>
class RowPrefix {
 public:
  void Build(const Grid<T>& g) {
    width_ = g.width();
    height_ = g.height();
    sums_.assign(static_cast<std::size_t>(width_ + 1) * height_, T{});
    for (int j = 0; j < height_; ++j) {
      T* row = &sums_[static_cast<std::size_t>(j) * (width_ + 1)];
      for (int i = 0; i < width_; ++i) row[i + 1] = row[i] + g.at(i, j);
    }
  }
  /// Σ of the row-j cells i in [lo, hi], clipped to the grid.
  T RowSum(int j, int lo, int hi) const {
    if (j < 0 || j >= height_) return T{};
    lo = lo < 0 ? 0 : lo;
    hi = hi >= width_ ? width_ - 1 : hi;
    if (lo > hi) return T{};
    const T* row = &sums_[static_cast<std::size_t>(j) * (width_ + 1)];
    return row[hi + 1] - row[lo];
  }
  /// Σ over the disc about (i, j), clipped to the grid.
  T DiscSum(int i, int j, const DiscSpans& disc) const {
    T s{};
    for (int dy = -disc.radius(); dy <= disc.radius(); ++dy) {
      const int w = disc.half_width(dy);
      s += RowSum(j + dy, i - w, i + w);
    }
    return s;
  }

 private:
  int width_ = 0;
  int height_ = 0;
  std::vector<T> sums_;
};

/// out(i, j) = 1 where any cell of the disc about (i, j) is nonzero in `mask` (binary dilation).
void DilateMask(const Grid<std::uint8_t>& mask, const DiscSpans& disc, Grid<std::uint8_t>* out);

/// out(c) = max over the disc about c of v, skipping `absent` cells; `absent` when the whole
/// disc is absent.
void DiscMax(const Grid<std::int16_t>& v, const DiscSpans& disc, std::int16_t absent,
             Grid<std::int16_t>* out);
/// The same with the minimum.
void DiscMin(const Grid<std::int16_t>& v, const DiscSpans& disc, std::int16_t absent,
             Grid<std::int16_t>* out);

}  // namespace rover::apl::gestalt
