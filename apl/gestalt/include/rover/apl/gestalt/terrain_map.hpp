#pragma once
/// @file
/// TerrainMap: GESTALT terrain assessment (nav_core::TerrainAssessor).
///
/// Data flow of one Update(scan):
///   1. Follow the rover: the square grid (map_size, cell_size; site-frame aligned, cell (i, j)
///      covers [origin + i r, origin + (i + 1) r)) scrolls by whole cells so the rover's cell is
///      at its centre; cells farther than forget_radius from the rover are forgotten.
///   2. Points: every valid pixel's point p_site = site_from_rover * p_rover within
///      max_point_distance (horizontally) of the rover is binned into its cell. The outline of
///      the footprint in the image (fov_edge.hpp) marks the cells at the edge of the field of view.
///   3. Moments: each touched cell's moments (moments.hpp) are replaced by the scan's (new data
///      overrides old: newer data is nearer, and immune to earlier pose error) except at
///      FOV-edge cells that already had data, where the scan's are added to them (a partial view
///      must not erase what a full one saw).
///   4. Assessment, incrementally: only cells whose rover disc contains a touched cell are
///      re-assessed (filters.hpp). Disc sums come from row prefix sums of the moment grid
///      (disc.hpp), 2 (2R + 1) lookups per cell instead of one per cell of the disc or one per
///      point. The fit source is the merged map (default) or the scan alone (fit_from_scan_only).
///   5. Merge: the fresh goodness goes into the layered goodness maps (layered_map.hpp); cells
///      within fov_edge_margin_cells of a FOV-edge cell keep min(old, new).
///   6. Publish: the combined layers become the goodness map; known cells next to an unknown
///      cell are border cells (goodness capped at border_goodness, certainty border_certainty),
///      unknown cells read (unknown_goodness, unknown_certainty); assessed cells have certainty
///      255. With footprint_check, known cells whose latest assessment's cell_height is at or
///      above footprint_hazard_height carry kCellHazard.
///
/// Internally moments are kept relative to a fixed origin (the rover's position at the first
/// update) so their sums stay well conditioned; Clear() drops it.

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "rover/apl/gestalt/disc.hpp"
#include "rover/apl/gestalt/filters.hpp"
#include "rover/apl/gestalt/grid.hpp"
#include "rover/apl/gestalt/layered_map.hpp"
#include "rover/apl/gestalt/moments.hpp"
#include "rover/apl/gestalt/options.hpp"
#include "rover/apl/nav_core/terrain_assessor.hpp"

namespace rover::apl::gestalt {

class TerrainMap final : public nav_core::TerrainAssessor {
 public:
  /// Errors: InvalidArgument naming the field when options.Validate() fails.
  static Result<TerrainMap> Create(const GestaltOptions& options);

  Result<nav_core::AssessmentStats> Update(const nav_core::RangeScan& scan) override;
  void Follow(const Eigen::Isometry3d& site_from_rover) override;
  const nav_core::GoodnessMap& goodness_map() const override { return map_; }
  void Clear() override;

  const GestaltOptions& options() const { return options_; }
  /// Latest assessment of each cell (same grid as goodness_map()).
  const Grid<CellAssessment>& assessments() const { return assessments_; }
  const LayeredGoodness& layers() const { return layers_; }
  /// Cell moments, coordinates relative to moment_origin() (site frame).
  const Grid<Moments>& moments() const { return moments_; }
  const Eigen::Vector3d& moment_origin() const { return moment_origin_; }
  /// Cells that the latest update marked at the edge of its field of view.
  const Grid<std::uint8_t>& fov_edge_cells() const { return scan_edge_; }

 private:
  explicit TerrainMap(const GestaltOptions& options);
  // Recentre and forget; returns whether anything changed (not yet published).
  bool Move(const Eigen::Isometry3d& site_from_rover);
  // Scrolls the grids so the rover's cell is the centre one; returns whether anything moved.
  bool Recentre(const Eigen::Vector2d& rover_xy);
  // Forgets cells farther than forget_radius; returns whether anything was forgotten.
  bool ForgetFar(const Eigen::Vector2d& rover_xy);
  void Publish();

  GestaltOptions options_;
  DiscAssessor assessor_;
  DiscSpans edge_margin_disc_;
  int cells_ = 0;          ///< grid side
  bool anchored_ = false;  ///< origin and grid placed (first update or Follow)
  int i0_ = 0, j0_ = 0;    ///< global index (floor(x / r), floor(y / r)) of cell (0, 0)
  Eigen::Vector3d moment_origin_ = Eigen::Vector3d::Zero();

  Grid<Moments> moments_;
  Grid<CellAssessment> assessments_;
  LayeredGoodness layers_;
  Grid<std::uint8_t> edge_merged_;  ///< last merge at the cell was conservative
  nav_core::GoodnessMap map_;

  // Per-update scratch (kept to avoid reallocation).
  Grid<Moments> scan_moments_;
  Grid<std::uint8_t> scan_edge_;
  Grid<std::uint8_t> touched_;
  std::vector<std::size_t> touched_list_;
  std::vector<std::uint8_t> used_px_, edge_px_;
  std::vector<std::int32_t> cell_of_px_;
  std::vector<Eigen::Vector3d> point_of_px_;
  std::vector<double> noise_of_px_;  // expected height-noise variance of each used pixel [m²]
  Grid<std::uint8_t> dirty_, conservative_;
  Grid<CellStats> cell_stats_;
  Grid<int> covered_;
  RowPrefix<Moments> moment_sums_;
  RowPrefix<int> covered_sums_;
  Grid<std::int16_t> fresh_;
};

}  // namespace rover::apl::gestalt
