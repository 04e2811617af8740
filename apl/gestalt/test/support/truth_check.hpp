#pragma once
/// @file
/// Test support: how well a goodness map matches the terrain's truth rocks (the hazard-map
/// quality figures the judge will report, in their simplest form).
///
///  - recall: of the truth hazards (rocks at least `hazard_height` tall) whose centre lies within
///    `radius` of the rover, whose centre cell is known in the map and which the rover saw (the
///    `seen` predicate; by default every hazard with a known centre cell), the share whose
///    centre cell is an obstacle (goodness below min_allowed_goodness: no path may cross it);
///  - false obstacles: of the known cells within `radius` marked obstacle, the share with no
///    reason to be: no rock at least `excuse_height` tall whose footprint reaches into the
///    cell's rover disc, and a bare-ground slope under max_tilt there.

#include <Eigen/Geometry>
#include <functional>

#include "rover/apl/gestalt/options.hpp"
#include "rover/apl/nav_core/goodness_map.hpp"
#include "rover/sim/terrain/terrain.hpp"

namespace rover::apl::gestalt::testing {

struct HazardQuality {
  int hazards_seen = 0;     ///< truth hazards with a known centre cell
  int hazards_marked = 0;   ///< ... whose centre cell is an obstacle
  int obstacle_cells = 0;   ///< known obstacle cells within the radius
  int false_obstacles = 0;  ///< ... with no truth reason
  double recall() const { return hazards_seen > 0 ? double(hazards_marked) / hazards_seen : 1.0; }
  double false_rate() const {
    return obstacle_cells > 0 ? double(false_obstacles) / obstacle_cells : 0.0;
  }
};

struct TruthCheckOptions {
  double radius = 5.0;          ///< [m] around the rover
  double hazard_height = 0.25;  ///< [m] rocks this tall must be marked
  double excuse_height = 0.10;  ///< [m] rocks this tall may cause an obstacle around them
  /// Whether the rover saw a rock (empty: every rock with a known centre cell counts).
  std::function<bool(const sim::terrain::Rock&)> seen;
};

HazardQuality CompareWithTruth(const nav_core::GoodnessMap& map,
                               const sim::terrain::Terrain& terrain,
                               const Eigen::Vector2d& rover_xy, const GestaltOptions& options,
                               const TruthCheckOptions& check = {});

}  // namespace rover::apl::gestalt::testing
