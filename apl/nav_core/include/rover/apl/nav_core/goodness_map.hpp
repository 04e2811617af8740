#pragma once
/// @file
/// GoodnessMap: a configuration-space traversability grid in the site frame, free of DDS.
///
/// Each cell says how safe the rover would be with its centre on that cell, in any heading
/// (MER models the rover by its 2.6 m turn-in-place disc), as an 8-bit goodness (0 = obstacle,
/// 255 = perfect) and an 8-bit certainty (0 = nothing known). A path is safe when the 1-cell-wide
/// track of the rover centre is.
///
/// Grid: cell (i, j) covers x in [origin_x + i r, origin_x + (i + 1) r), y in [origin_y + j r,
/// origin_y + (j + 1) r) (r = resolution, site frame x north, y west, metres); i runs along x
/// (0..width-1), j along y (0..height-1); arrays are row-major with row = j:
/// index = j * width + i (the layout of the apl/goodness_map topic).

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "rover/base/time.hpp"
#include "rover/msg/navigation.hpp"

namespace rover::apl::nav_core {

inline constexpr int kGoodnessPerfect = 255;
inline constexpr int kGoodnessObstacle = 0;

/// Bits of GoodnessMap::flags.
enum CellFlag : std::uint8_t {
  kCellKnown = 1,    ///< assessed from range data (else the map's unknown value)
  kCellBorder = 2,   ///< known, next to an unknown cell (goodness capped by the border value)
  kCellFovEdge = 4,  ///< last updated at the edge of a field of view (merged conservatively)
  /// The cell itself holds a step (a rock) that the rover's footprint must not cover; set only
  /// by assessors that support footprint checks (GESTALT's footprint_check).
  kCellHazard = 8,
  /// A hazard cell whose step is tall enough to reach the body or the rocker links (GESTALT's
  /// footprint_tall_height); with footprint_straddle, lower hazards may pass between the wheels.
  kCellTall = 16,
};

/// The value of one cell.
struct CellValue {
  int goodness = 0;   ///< 0..255
  int certainty = 0;  ///< 0..255
  std::uint8_t flags = 0;
  bool known() const { return (flags & kCellKnown) != 0; }
};

struct GoodnessMap {
  double origin_x = 0.0;               ///< [m] site x of the corner of cell (0, 0) (its smallest x)
  double origin_y = 0.0;               ///< [m] site y of the corner of cell (0, 0)
  double resolution = 0.2;             ///< [m] cell side
  int width = 0;                       ///< cells along x
  int height = 0;                      ///< cells along y
  std::vector<std::uint8_t> goodness;  ///< 0..255 per cell
  std::vector<std::uint8_t> certainty;  ///< 0..255 per cell
  std::vector<std::uint8_t> flags;      ///< CellFlag bits per cell
  /// Value reported for cells outside the grid (and stored in unknown cells).
  int unknown_goodness = 0;
  int unknown_certainty = 0;
  Time stamp;                  ///< capture time of the newest range data merged
  std::uint64_t revision = 0;  ///< incremented by every change

  std::size_t cell_count() const {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
  bool Contains(int i, int j) const { return i >= 0 && j >= 0 && i < width && j < height; }
  std::size_t Index(int i, int j) const { return static_cast<std::size_t>(j) * width + i; }
  /// The cell containing site point (x, y) (it may lie outside the grid).
  void CellOf(double x, double y, int* i, int* j) const {
    *i = static_cast<int>(std::floor((x - origin_x) / resolution));
    *j = static_cast<int>(std::floor((y - origin_y) / resolution));
  }
  /// [m] site coordinates of the centre of cell (i, j).
  Eigen::Vector2d CellCenter(int i, int j) const {
    return {origin_x + (i + 0.5) * resolution, origin_y + (j + 0.5) * resolution};
  }
  /// Cell (i, j); outside the grid: the unknown value with no flags.
  CellValue At(int i, int j) const {
    if (!Contains(i, j)) return {unknown_goodness, unknown_certainty, 0};
    const std::size_t k = Index(i, j);
    return {goodness[k], certainty[k], flags[k]};
  }
  /// The cell under site point (x, y).
  CellValue AtPoint(double x, double y) const {
    int i = 0, j = 0;
    CellOf(x, y, &i, &j);
    return At(i, j);
  }
};

/// The apl/goodness_map value of a map (the cells copied; unknown_certainty and revision are not
/// carried).
inline msg::GoodnessMap GoodnessMapToMessage(const GoodnessMap& map) {
  msg::GoodnessMap m;
  m.stamp = map.stamp;
  m.origin_x = map.origin_x;
  m.origin_y = map.origin_y;
  m.resolution = map.resolution;
  m.width = map.width;
  m.height = map.height;
  m.unknown_goodness = map.unknown_goodness;
  m.goodness = map.goodness;
  m.certainty = map.certainty;
  m.flags = map.flags;
  return m;
}

}  // namespace rover::apl::nav_core
