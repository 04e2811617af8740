#pragma once
/// @file
/// RoamanOptions: every parameter of ROAMAN (seed 004 §3.1): the site-frame map memory, the
/// seven-step traversability map, the goal-aligned planning grid, the road map (medial axis,
/// virtual drive, depth-first search, least-squares waypoint fit) and the A* baseline.
/// FIDO's values are the defaults where the seed gives one (5 cm cells, 6 m x 12 m grid, ~12 m
/// usable range, 45° tip-over slope, steps above the body clearance); the rover geometry follows
/// the simulated rover (sim/physics rover_model.hpp). README.md has the table with the source
/// of each value.
///
/// Declared once for parameter files with BindParams (keys carry their unit: `cell_size_m`,
/// `max_slope_deg`); Validate() checks ranges and cross-field rules, its messages start with
/// the member's name so that ReadParams reports them against the key.
///
/// Units: metres and radians in members (degrees in keys that say `_deg`).

#include <numbers>
#include <string>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/base/units.hpp"

namespace rover::apl::roaman {

/// Which planner MakePlan runs on the traversability map.
enum class Algorithm {
  kRoaman,  ///< FIDO's road map: medial axis, virtual drive, DFS, least-squares waypoints
  kAStar,   ///< A* over the 8-connected grid with a clearance cost (the baseline)
};
/// "roaman" | "astar".
const char* AlgorithmName(Algorithm a);

/// The rover footprint as the planners test it: a length x width rectangle about its centre.
struct Footprint {
  double length = 1.5;  ///< [m]
  double width = 1.16;  ///< [m]

  /// [m] radius of the disc the footprint sweeps turning in place: half its diagonal.
  double turn_radius() const;
  /// [m] clearance a straight drive needs along its centre line: half the width.
  double leg_clearance() const { return 0.5 * width; }
  /// [m] clearance (radius of the hazard-free disc about the turn point) a turn in place of
  /// `turn` radians between two straight legs needs: the footprint's reach across the legs,
  /// W/2 + (L/2) sin|turn| (a corner swings out by (L/2) sin|turn|; along the legs the legs'
  /// own clearance covers it), at most the turn radius, which any turn is safe with (and which
  /// turns of 90° or more need).
  double TurnClearance(double turn) const;
};

struct RoamanOptions {
  // ---- rover geometry (to come from core/hwconfig's rover description) -------------------
  /// [m] footprint length: wheelbase 1.25 m + 2 x wheel radius 0.125 m (sim rover).
  double rover_length = 1.5;
  /// [m] footprint width: track 1.0 m + wheel width 0.16 m (sim rover).
  double rover_width = 1.16;
  /// [m] belly above flat ground: chassis box centre 0.50 m - half height 0.15 m (sim rover).
  double body_clearance = 0.35;

  // ---- map memory (site frame) -------------------------------------------------------------
  double cell_size = 0.05;             ///< [m] cell side (FIDO: 5 cm)
  double map_size = 30.0;              ///< [m] side of the square site-frame map
  double recenter_distance = 6.0;      ///< [m] rover this far from the map centre: recentre
  double max_range = 12.0;             ///< [m] points farther (horizontally) unused (FIDO ~12 m)
  double new_panorama_distance = 0.5;  ///< [m] rover moved this far since the last scan: a new
                                       ///< panorama, whose cells replace older data
  int min_cell_points = 1;             ///< points a cell needs to have a measured height

  // ---- the seven steps ---------------------------------------------------------------------
  double max_fill_gap = 0.2;    ///< [m] 1: widest gap between measured cells filled
  int min_fill_directions = 2;  ///< 1: of 4 line directions that must bracket a hole cell
  double height_sigma_k = 2.0;  ///< 2: cell top/bottom = mean +- k sigma (within min..max)
  double normal_window = 0.25;  ///< [m] 3: side of the plane-fit window (odd cells)
  int min_fit_cells = 6;        ///< 3: cells with heights a plane fit needs
  double region_tolerance = 10.0 * kDegree;  ///< [rad] 4: normal angle to the region's mean normal
  double region_max_jump = 0.1;    ///< [m] 4: height jump between neighbours that ends a region
  double max_slope = 45.0 * kDegree;  ///< [rad] 5: steeper regions are hazards (FIDO: 45°)
  double min_steep_area = 0.25;    ///< [m^2] 5: smaller steep regions are left to the step test
  double step_baseline = 0.15;     ///< [m] 5: a rise over this distance is a discontinuity
  double min_missing_area = 0.04;  ///< [m^2] 5: smaller regions of missing data are no hazard
  double hazard_border = 0.15;     ///< [m] 6: border grown around hazards (slip, heading)

  // ---- planning grid (goal-aligned) --------------------------------------------------------
  Algorithm algorithm = Algorithm::kRoaman;
  bool fallback = true;              ///< the other algorithm is tried before declaring blocked
  double plan_width = 6.0;           ///< [m] across the goal direction (FIDO: 6 m)
  double plan_length = 12.0;         ///< [m] toward the goal from the rover (FIDO: 12 m)
  double plan_back = 1.5;            ///< [m] rows behind the rover (backing out)
  double goal_margin = 1.5;          ///< [m] rows beyond a goal inside the grid
  double start_clear_radius = 2.0;   ///< [m] missing and border cells this close to the rover
                                     ///< count as safe: it stands there, and the mast cannot
                                     ///< see the ground next to it (HAZCAMs cover it)
  double start_search_radius = 2.0;  ///< [m] farthest turn-safe cell a first leg may reach
  double min_progress = 0.5;         ///< [m] partial plans must end this much nearer the goal

  // ---- road map ----------------------------------------------------------------------------
  double lookahead = 2.0;         ///< [m] rows ahead an axis cell connects to (>= 2 turn
                                  ///< radii: the axis cells before an obstacle are dropped)
  double connect_radius = 3.0;    ///< [m] axis cells the start and goal connect to directly
  double fit_tolerance = 0.25;    ///< [m] path deviation before a waypoint is added
  int fit_max_evaluations = 400;  ///< NLopt (COBYLA) evaluations of the least-squares fit
  double turn_cost = 0.2;         ///< [m/rad] plan cost of turning in place

  // ---- A* ------------------------------------------------------------------------------------
  double clearance_weight = 1.0;  ///< step cost x (1 + w max(0, 1 - clearance / ref))
  double clearance_ref = 2.0;     ///< [m] clearance above which a cell costs its length

  Footprint footprint() const { return {rover_length, rover_width}; }
  /// [m] radius of the disc the footprint sweeps turning in place: half its diagonal.
  double turn_radius() const { return footprint().turn_radius(); }
  /// [m] clearance a straight drive needs along its centre line: half the footprint width.
  double leg_clearance() const { return footprint().leg_clearance(); }
  /// Cells along each side of the site-frame map.
  int map_cells() const;
  /// Half-width in cells of the plane-fit window (window = 2 k + 1 cells).
  int normal_half_cells() const;

  Status Validate() const;
  static void BindParams(ParamBinder<RoamanOptions>& b);
};

}  // namespace rover::apl::roaman
