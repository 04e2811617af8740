#pragma once
/// @file
/// The goal-aligned planning grid both planners run on, resampled from the site-frame
/// traversability map for one plan request.
///
/// Frame (GoalFrame): origin at the rover, axis u along the direction to the goal, axis w to
/// its left (u turned +90° about site z), so (u, w, z) is right-handed like the site frame.
/// Grid: cell (i, j) covers w in [w0 + i c, w0 + (i + 1) c) and u in [u0 + j c, u0 + (j + 1) c)
/// (c = cell size): i runs ACROSS the goal direction (columns, width = plan_width / c), j runs
/// TOWARD the goal (rows, from u0 = -plan_back to the far end). A row (constant j) therefore
/// runs across the direction to the goal, as FIDO's do (seed 004 Fig. 3: 6 m wide, 12 m high).
///
/// Resampling: a planning cell takes the most severe class of the (up to) four site cells
/// around its centre (the bilinear support), so a hazard is never lost to the rotation; cells
/// outside the traversability map are missing. Near the rover (start_clear_radius) missing
/// and border cells count as safe: the mast does not see the ground the rover stands on.
///
/// Clearance: for every cell, the distance from its centre to the nearest non-safe cell (centre
/// to centre, less half a cell) or to the grid's edge, whichever is nearer: beyond the grid
/// nothing is known. A rover centred on a cell can turn in place there when its clearance is at
/// least the turn radius (half the footprint diagonal); it can drive straight along a segment
/// when every cell under the segment has at least half the footprint width.

#include <Eigen/Core>

#include "rover/apl/roaman/grid.hpp"
#include "rover/apl/roaman/options.hpp"
#include "rover/apl/roaman/traversability.hpp"

namespace rover::apl::roaman {

struct GoalFrame {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  ///< [m] site: the rover
  Eigen::Vector2d u = Eigen::Vector2d::UnitX();      ///< unit, toward the goal
  Eigen::Vector2d w = Eigen::Vector2d::UnitY();      ///< unit, u turned +90°

  /// Preconditions: goal != start.
  static GoalFrame Toward(const Eigen::Vector2d& start, const Eigen::Vector2d& goal);
  /// Site point of frame coordinates (along u, across w).
  Eigen::Vector2d ToSite(double along, double across) const { return origin + along * u + across * w; }
  /// Frame coordinates (along, across) of a site point.
  Eigen::Vector2d ToFrame(const Eigen::Vector2d& p) const {
    const Eigen::Vector2d d = p - origin;
    return {d.dot(u), d.dot(w)};
  }
};

struct PlanningGrid {
  GoalFrame frame;
  double cell = 0.05;    ///< [m]
  double across0 = 0.0;  ///< [m] w of the edge of column 0
  double along0 = 0.0;   ///< [m] u of the edge of row 0
  int width = 0;         ///< columns (across)
  int height = 0;        ///< rows (toward the goal)
  Layer<CellClass> cls;
  Layer<float> clearance;  ///< [m]

  bool Contains(int i, int j) const { return i >= 0 && j >= 0 && i < width && j < height; }
  /// [m] site point at the centre of cell (i, j).
  Eigen::Vector2d Center(int i, int j) const {
    return frame.ToSite(along0 + (j + 0.5) * cell, across0 + (i + 0.5) * cell);
  }
  /// The cell under site point p; false when it is outside the grid.
  bool CellOf(const Eigen::Vector2d& p, int* i, int* j) const;
  /// [m] clearance of the cell under p; 0 outside the grid.
  double ClearanceAt(const Eigen::Vector2d& p) const;
  /// Class of the cell under p; kMissing outside the grid.
  CellClass ClassAt(const Eigen::Vector2d& p) const;
  /// Every cell the segment a-b passes over (sampled every half cell, both ends included) has
  /// at least `min_clearance`.
  bool SegmentClear(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double min_clearance) const;
  /// [m] the least clearance over the cells the segment a-b passes over (same sampling).
  double MinClearanceAlong(const Eigen::Vector2d& a, const Eigen::Vector2d& b) const;
};

/// Builds the grid for a rover at `start` heading for `goal` (preconditions: goal != start):
/// rows from -plan_back to `along_max` (metres along u), plan_width across.
PlanningGrid BuildPlanningGrid(const TraversabilityMap& map, const Eigen::Vector2d& start,
                               const Eigen::Vector2d& goal, double along_max,
                               const RoamanOptions& options);

/// (Re)computes grid->clearance from grid->cls.
void ComputeClearance(PlanningGrid* grid);

}  // namespace rover::apl::roaman
