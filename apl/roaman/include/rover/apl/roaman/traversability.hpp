#pragma once
/// @file
/// The seven-step traversability map of ROAMAN (seed 004 §3.1), computed on the site-frame map
/// memory (site_map.hpp) at its cell size (FIDO: 5 cm). Each step is a function of its own so
/// that tests can run it on synthetic heightfields; ComputeTraversability() runs all seven.
///
///  1. Elevation map (BinElevation, FillHoles): a cell's height is the mean z of its points;
///     a missing cell is interpolated when, along at least min_fill_directions of the four
///     lines through it (the two axes and the two diagonals), measured cells bracket it with a
///     gap no wider than max_fill_gap and a rise between them no steeper than max_slope (so an
///     occlusion edge, where the far side is much lower, is never bridged). Its height is the
///     mean over those lines of the linear interpolation between the bracketing cells, weighted
///     by 1 / (their distance). Larger holes stay missing.
///  2. Height distribution (BinElevation): count n, mean m, standard deviation s, min, max of
///     the points; the cell's top is min(max, m + k s) and its bottom max(min, m - k s),
///     k = height_sigma_k (outliers of a noisy stereo point clipped). Filled cells: top =
///     bottom = mean.
///  3. Surface normals (FitNormals): the least-squares plane z = a x + b y + c over the cell
///     and its neighbours with heights in a (2h + 1)^2 window (side normal_window), from
///     summed-area tables of the moments; the normal is (-a, -b, 1) / |(-a, -b, 1)|, the slope
///     atan(sqrt(a^2 + b^2)), the residual the RMS of the fit. Cells with fewer than
///     min_fit_cells heights in the window, or collinear ones, get no normal.
///  4. Regions of similar slope (GrowRegions): seeds in raster order; a region grows over the 8
///     neighbours of its cells while the neighbour's normal is within region_tolerance of the
///     region's mean normal (the normalised sum of its members' normals) and its height within
///     region_max_jump of the cell it is reached from. A region's slope is that of its mean
///     normal.
///  5. Hazards (MarkHazards): steep: a region steeper than max_slope (FIDO: 45°, the tip-over
///     limit) and at least min_steep_area in area (smaller steep patches are rock faces, left
///     to the step test); step: a cell whose top stands more than body_clearance above the
///     lowest bottom within step_baseline (the square window of half-side round(step_baseline /
///     cell)); missing: an 8-connected region of cells without a height or a normal (large
///     holes, shadows behind rocks, unseen terrain) of at least min_missing_area (smaller ones
///     cannot hide anything the rover could not cross: they stay safe); blocked: a corridor
///     reported blocked (site_map.hpp).
///  6. Border (GrowBorder): every other cell within hazard_border of a hazard cell (centre to
///     centre) becomes border, a margin for wheel slip and heading error.
///  7. Safe: the rest.
///
/// Frames: site frame (x north, y west, z up), metres. The map covers the part of the site map
/// that holds data, grown by the windows of steps 3, 5 and 6; outside it every cell is missing.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "rover/apl/roaman/grid.hpp"
#include "rover/apl/roaman/options.hpp"
#include "rover/apl/roaman/site_map.hpp"

namespace rover::apl::roaman {

/// What a cell is, in increasing severity (a cell covered by two takes the more severe).
enum class CellClass : std::uint8_t {
  kSafe = 0,     ///< 7: traversable
  kBorder = 1,   ///< 6: margin around a hazard
  kMissing = 2,  ///< 5: in a large region without heights or normals (unseen, shadow, hole)
  kSteep = 3,    ///< 5: region steeper than max_slope
  kStep = 4,     ///< 5: discontinuity higher than the body clearance
  kBlocked = 5,  ///< a corridor reported blocked
};
/// "safe", "border", "missing data", "steep slope", "step", "blocked".
const char* CellClassName(CellClass c);
/// Hazards proper (missing, steep, step, blocked): what borders grow around.
inline bool IsHazard(CellClass c) { return c >= CellClass::kMissing; }

/// Where a cell's height came from.
enum class HeightSource : std::uint8_t { kNone = 0, kMeasured = 1, kFilled = 2 };

/// Steps 1 and 2: heights and their distribution per cell.
struct ElevationMap {
  GridGeometry geometry;
  Layer<float> mean;    ///< [m] site z (NaN where kNone)
  Layer<float> top;     ///< [m] mean + k sigma, clipped to the maximum
  Layer<float> bottom;  ///< [m] mean - k sigma, clipped to the minimum
  Layer<float> sigma;   ///< [m] standard deviation of the points (0 for filled cells)
  Layer<std::uint32_t> count;  ///< points
  Layer<HeightSource> source;
  int measured = 0;  ///< cells with kMeasured
  int filled = 0;    ///< cells with kFilled
};

/// Step 3.
struct NormalMap {
  Layer<Eigen::Vector3f> normal;  ///< unit, z >= 0 (zero vector where there is none)
  Layer<float> slope;             ///< [rad] NaN where there is no normal
  Layer<float> residual;          ///< [m] RMS of the plane fit (NaN where none)
  bool has(int i, int j) const { return !std::isnan(slope.at(i, j)); }
};

/// Step 4.
struct SlopeRegion {
  int cells = 0;
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit mean normal
  double slope = 0.0;                                 ///< [rad]
};
struct RegionMap {
  Layer<std::int32_t> id;  ///< index into regions, -1 where there is no normal
  std::vector<SlopeRegion> regions;
};

/// Steps 5-7 and everything before them.
struct TraversabilityMap {
  GridGeometry geometry;
  ElevationMap elevation;
  NormalMap normals;
  RegionMap regions;
  Layer<float> step;  ///< [m] top above the lowest bottom within step_baseline (NaN: no height)
  Layer<CellClass> cls;
  std::uint64_t revision = 0;  ///< SiteMap::revision() it was computed from

  /// Class of the cell under site (x, y); kMissing outside the map.
  CellClass ClassAt(double x, double y) const;
  /// Cells of each class, indexed by CellClass.
  std::vector<int> ClassCounts() const;
};

/// Step 1 (binning) and step 2 for the cells [i0, i0 + width) x [j0, j0 + height) of `cells`
/// (whose geometry is `geometry`); cells outside `cells` have no height. Returns the map of
/// that window.
ElevationMap BinElevation(const Layer<CellStats>& cells, const GridGeometry& geometry, int i0,
                          int j0, int width, int height, const RoamanOptions& options);
/// Step 1 (interpolating small holes); returns the cells filled.
int FillHoles(ElevationMap* map, const RoamanOptions& options);
/// Step 3.
NormalMap FitNormals(const ElevationMap& map, const RoamanOptions& options);
/// Step 4.
RegionMap GrowRegions(const ElevationMap& map, const NormalMap& normals,
                      const RoamanOptions& options);
/// Step 5: classes (safe, missing, steep, step, blocked) and step heights. `blocked` (1 =
/// blocked) has the map's size, or is empty.
void MarkHazards(const ElevationMap& map, const NormalMap& normals, const RegionMap& regions,
                 const Layer<std::uint8_t>& blocked, const RoamanOptions& options,
                 Layer<CellClass>* cls, Layer<float>* step);
/// Step 6 (and 7: what is left stays safe); returns the cells made border.
int GrowBorder(Layer<CellClass>* cls, double border_cells);

/// All seven steps over the part of `map` that holds data.
TraversabilityMap ComputeTraversability(const SiteMap& map, const RoamanOptions& options);

}  // namespace rover::apl::roaman
