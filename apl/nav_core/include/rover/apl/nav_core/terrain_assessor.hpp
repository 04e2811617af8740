#pragma once
/// @file
/// TerrainAssessor: turns range scans into a goodness map around the rover (MER's Terrain
/// Assessment, GESTALT's first half). The mobility manager owns one and calls it from its step
/// loop; it never needs to know how goodness is computed.
///
/// Contract:
///  - Update() merges one scan (points in the rover frame plus the pose at capture) into the map
///    and returns what it did; a malformed scan is an InvalidArgument naming the field and leaves
///    the map unchanged. Scans may arrive in any order of capture time; each is merged as "the
///    newest" (callers drop stale ones).
///  - Follow() moves the map with the rover without new data (data far behind is forgotten),
///    e.g. on steps where imaging was skipped.
///  - goodness_map() is valid until the next non-const call; Clear() forgets everything.
/// Implementations are not thread-safe; one caller at a time.

#include <Eigen/Geometry>
#include <cstdint>

#include "rover/apl/nav_core/goodness_map.hpp"
#include "rover/apl/nav_core/height_map.hpp"
#include "rover/apl/nav_core/range_scan.hpp"
#include "rover/base/status.hpp"

namespace rover::apl::nav_core {

/// What one Update() did (counts, for logs and tests).
struct AssessmentStats {
  int points_total = 0;    ///< pixels marked valid
  int points_used = 0;     ///< finite, inside the range limits and the map
  int cells_touched = 0;   ///< map cells that received points
  int cells_fov_edge = 0;  ///< of those, cells at the edge of the field of view
  int cells_assessed = 0;  ///< cells whose goodness was recomputed
  int cells_obstacle = 0;  ///< of those, cells with goodness 0
  int cells_unknown = 0;   ///< of those, cells without enough data for a plane fit
};

class TerrainAssessor {
 public:
  virtual ~TerrainAssessor() = default;

  /// Merges one range scan. Errors: InvalidArgument for a malformed scan (the map is unchanged).
  virtual Result<AssessmentStats> Update(const RangeScan& scan) = 0;
  /// Recentres the map on the rover at `site_from_rover` and forgets data out of range.
  virtual void Follow(const Eigen::Isometry3d& site_from_rover) = 0;
  /// The current goodness map (site frame).
  virtual const GoodnessMap& goodness_map() const = 0;
  /// The cell under a site-frame point (the unknown value outside the map).
  virtual CellValue GoodnessAt(const Eigen::Vector2d& site_xy) const {
    return goodness_map().AtPoint(site_xy.x(), site_xy.y());
  }
  /// The elevation grid behind the goodness map, for planners that check wheels, suspension
  /// and belly (an ENav-class path tree); nullptr when the assessor keeps none (GESTALT).
  virtual const HeightMap* height_map() const { return nullptr; }
  /// Forgets all data (e.g. after a pose jump the map cannot be trusted).
  virtual void Clear() = 0;
};

}  // namespace rover::apl::nav_core
