#pragma once
/// @file
/// SiteMap: ROAMAN's map memory, a square site-frame grid (x north, y west; cells of
/// RoamanOptions::cell_size, map_size on a side) that accumulates range points across scans and
/// panoramas, and the corridors reported blocked.
///
/// Each cell keeps the running count, sum and sum of squares of the heights (site z) of the
/// points that fell in it and their minimum and maximum: step 2's height distribution is read
/// from these (traversability.hpp).
///
/// Panoramas: scans taken from one stand belong to one panorama. A scan whose rover position is
/// more than new_panorama_distance from the previous scan's (or a call to BeginPanorama())
/// starts a new one; the first point of a newer panorama to land in a cell replaces what older
/// panoramas left there (their data are misregistered by the localisation drift accumulated
/// since), cells the new panorama does not see keep their older data.
///
/// Recentring: the map is centred on the first scan's rover position; when a scan's rover
/// position is more than recenter_distance from the centre the grid moves by whole cells so that
/// it is centred on it again; data that fall off the grid are dropped. Blocked corridors are
/// kept as segments and re-rasterised, so they survive recentring.

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "rover/apl/nav_core/range_scan.hpp"
#include "rover/apl/roaman/grid.hpp"
#include "rover/apl/roaman/options.hpp"
#include "rover/base/status.hpp"

namespace rover::apl::roaman {

/// Height statistics of the points in one cell (site z, metres).
struct CellStats {
  std::uint32_t count = 0;
  std::uint32_t panorama = 0;  ///< panorama that last wrote the cell
  double sum = 0.0;
  double sum_sq = 0.0;
  float min = std::numeric_limits<float>::infinity();
  float max = -std::numeric_limits<float>::infinity();

  double mean() const { return sum / count; }
  /// Population variance (>= 0). Preconditions: count > 0.
  double variance() const;
};

/// What AddScan did with a scan's pixels.
struct ScanStats {
  std::size_t pixels = 0;        ///< width x height
  std::size_t valid = 0;         ///< pixels marked valid
  std::size_t used = 0;          ///< points binned
  std::size_t non_finite = 0;    ///< valid pixels with a NaN or infinite coordinate (skipped)
  std::size_t out_of_range = 0;  ///< beyond max_range from the rover (skipped)
  std::size_t off_map = 0;       ///< outside the map after recentring (skipped)
  int panorama = 0;              ///< panorama the scan was merged into
  bool recentred = false;        ///< the map moved for this scan
};

/// A corridor reported blocked: cells within half_width of the segment from -> to.
struct BlockedCorridor {
  Eigen::Vector2d from = Eigen::Vector2d::Zero();  ///< [m] site
  Eigen::Vector2d to = Eigen::Vector2d::Zero();    ///< [m] site
  double half_width = 0.0;                         ///< [m]
};

class SiteMap {
 public:
  /// Preconditions: options.Validate() is ok.
  explicit SiteMap(const RoamanOptions& options);

  /// Bins a scan's valid, finite points within max_range of the rover. Errors: InvalidArgument
  /// for a malformed scan (RangeScan::Validate) or a scan with no usable point, naming the
  /// camera and how many pixels were invalid, non-finite, out of range or off the map; such a
  /// scan changes nothing.
  Result<ScanStats> AddScan(const nav_core::RangeScan& scan);
  /// Bins site-frame points seen from `rover_xy` (the same rules as AddScan, without a scan:
  /// no panorama detection or recentring). Non-finite points are counted and skipped.
  ScanStats AddPoints(std::span<const Eigen::Vector3d> site_points,
                      const Eigen::Vector2d& rover_xy);

  /// Starts a new panorama: later points replace older panoramas' data cell by cell.
  void BeginPanorama() { ++panorama_; }
  /// Moves the grid by whole cells so that its centre is the cell corner nearest to `xy`.
  void Recenter(const Eigen::Vector2d& xy);

  /// Marks a corridor blocked; returns the number of map cells it covers now. Errors:
  /// InvalidArgument for a non-finite point or half_width not in (0, map_size].
  Result<int> MarkBlocked(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                          double half_width);
  void ClearBlocked();
  /// Forgets everything (data, panoramas, blocked corridors); the next scan recentres.
  void Clear();

  const GridGeometry& geometry() const { return geometry_; }
  const Layer<CellStats>& cells() const { return cells_; }
  /// 1 where a blocked corridor covers the cell.
  const Layer<std::uint8_t>& blocked() const { return blocked_; }
  const std::vector<BlockedCorridor>& corridors() const { return corridors_; }
  /// [m] site x, y of the grid's centre.
  Eigen::Vector2d center() const;
  int panorama() const { return panorama_; }
  /// Incremented by every change of data or blocked cells.
  std::uint64_t revision() const { return revision_; }
  /// Cells holding data.
  std::size_t data_cells() const { return data_cells_; }
  /// Smallest box of cells [i0, i1] x [j0, j1] holding all data; false when there is none.
  bool DataBounds(int* i0, int* j0, int* i1, int* j1) const;

 private:
  void AddPoint(const Eigen::Vector3d& p);
  void RasterizeBlocked();
  template <class F>
  void ForEachCorridorCell(const BlockedCorridor& c, F&& f) const;
  void ExtendBounds(int i, int j);  // a cell gets its first point: count it, grow the bounds
  void RecomputeBounds();

  RoamanOptions options_;
  GridGeometry geometry_;
  Layer<CellStats> cells_;
  Layer<std::uint8_t> blocked_;
  std::vector<BlockedCorridor> corridors_;
  int panorama_ = 1;
  bool has_last_scan_ = false;
  Eigen::Vector2d last_scan_xy_ = Eigen::Vector2d::Zero();
  std::uint64_t revision_ = 0;
  std::size_t data_cells_ = 0;
  int bound_i0_ = 0, bound_j0_ = 0, bound_i1_ = -1, bound_j1_ = -1;
};

}  // namespace rover::apl::roaman
