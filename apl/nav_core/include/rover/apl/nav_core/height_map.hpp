#pragma once
/// @file
/// HeightMap: a site-frame elevation grid as planners that check wheels, suspension and belly
/// read it (an ENav-class planner; MER's GESTALT needs only goodness). Free of DDS.
///
/// Grid: the layout of GoodnessMap (cell (i, j) covers x in [origin_x + i r, origin_x + (i+1) r),
/// y in [origin_y + j r, origin_y + (j+1) r); row-major with row = j, index = j * width + i; site
/// frame x north, y west, z up; metres). Per cell, from the freshest scan that saw it: the mean,
/// lowest and highest point height, how many points and from what range. Cells nothing has seen
/// hold count 0 and NaN heights.
///
/// `step` is derived: the cell's mean height above the local ground (the lowest mean height of
/// the known cells within the assessor's ground radius), NaN when unknown; `hazard` holds the
/// HazardClass bits of cells whose step is tall enough to touch a part of the rover (wheels,
/// rocker links, body), after allowing for range noise.

#include <Eigen/Core>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "rover/base/time.hpp"

namespace rover::apl::nav_core {

/// Bits of HeightMap::hazard: which parts a cell's step would touch.
enum HazardClass : std::uint8_t {
  kHazardWheel = 1,   ///< above what a wheel (and the bogie link, clearance 0) may meet
  kHazardRocker = 2,  ///< above the rocker link's clearance
  kHazardBody = 4,    ///< above the belly clearance
};

struct HeightMap {
  double origin_x = 0.0;    ///< [m] site x of the corner of cell (0, 0)
  double origin_y = 0.0;    ///< [m] site y of the corner of cell (0, 0)
  double resolution = 0.1;  ///< [m] cell side
  int width = 0;            ///< cells along x
  int height = 0;           ///< cells along y
  std::vector<float> z_mean;         ///< [m] site z, NaN = unknown
  std::vector<float> z_min;          ///< [m]
  std::vector<float> z_max;          ///< [m]
  std::vector<std::uint16_t> count;  ///< points of the scan that set the cell (0 = unknown)
  std::vector<float> range;          ///< [m] mean horizontal range of those points from the camera
  std::vector<float> step;           ///< [m] derived: z_mean above the local ground, NaN unknown
  std::vector<std::uint8_t> hazard;  ///< derived: HazardClass bits
  Time stamp;                        ///< capture time of the newest scan merged
  std::uint64_t revision = 0;        ///< incremented by every change

  std::size_t cell_count() const {
    return static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  }
  bool Contains(int i, int j) const { return i >= 0 && j >= 0 && i < width && j < height; }
  std::size_t Index(int i, int j) const { return static_cast<std::size_t>(j) * width + i; }
  void CellOf(double x, double y, int* i, int* j) const {
    *i = static_cast<int>(std::floor((x - origin_x) / resolution));
    *j = static_cast<int>(std::floor((y - origin_y) / resolution));
  }
  Eigen::Vector2d CellCenter(int i, int j) const {
    return {origin_x + (i + 0.5) * resolution, origin_y + (j + 0.5) * resolution};
  }
  bool Known(std::size_t k) const { return count[k] > 0; }
};

}  // namespace rover::apl::nav_core
