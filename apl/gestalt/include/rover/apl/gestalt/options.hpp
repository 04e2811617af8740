#pragma once
/// @file
/// GestaltOptions: every parameter of terrain assessment and path selection, with MER's values
/// as defaults where the seeds give one (seed 002 Table 1 "Example GESTALT Parameters", seed
/// 000's MER flight values, seed 003's nominal hazard limits); README.md has the table with the
/// source of each. Declared once for parameter files with BindParams (keys carry their unit:
/// `max_tilt_deg`, `cell_size_m`); Validate() checks ranges and cross-field rules and its
/// messages start with the member's name (so ReadParams reports them against the key).
///
/// Units: metres, radians in members (degrees in keys that say `_deg`), goodness and certainty
/// 0..255 (MER's 8-bit values).

#include <numbers>
#include <vector>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/base/units.hpp"
#include "rover/hwconfig/rover_description.hpp"

namespace rover::apl::gestalt {

struct GestaltOptions {
  // ---- grid ------------------------------------------------------------------------------
  double cell_size = 0.2;           ///< [m] cell side (MER 0.2 m, the size of a hazardous rock)
  double map_size = 10.0;           ///< [m] side of the square grid that follows the rover
  double forget_radius = 5.0;       ///< [m] data farther than this from the rover is dropped
  double max_point_distance = 5.0;  ///< [m] points farther (horizontally) from the rover unused
  int min_cell_points = 2;          ///< points a cell needs to count as covered
  double min_coverage = 0.5;        ///< share of a rover disc's cells that must be covered

  // ---- filters -----------------------------------------------------------------------------
  double rover_disc_diameter = 2.6;    ///< [m] the rover modelled by its turn-in-place disc
  double step_disc_diameter = 0.8;     ///< [m] belly-sized disc the step search runs in
  double step_sigma_k = 1.0;           ///< cell top = mean + k sigma (tall thin obstacles)
  double step_safe = 0.2 / 3.0;        ///< [m] steps up to this are perfect (255)
  double max_step = 0.20;              ///< [m] steps from this on are obstacles (0)
  double tilt_safe = 5.0 * kDegree;    ///< [rad] tilts up to this are perfect
  double max_tilt = 20.0 * kDegree;    ///< [rad] tilts from this on are obstacles
  double roughness_safe = 0.07 / 3.0;  ///< [m] fit residuals up to this are perfect
  double max_roughness = 0.07;         ///< [m] fit residuals from this on are obstacles
  double eigen_ratio = 2.0;            ///< middle / smallest eigenvalue a planar fit needs
  /// Stereo noise model: a range point d metres (horizontally) from the rover at capture has
  /// height noise sigma = stereo_noise_coeff d² [m] (stereo depth error grows with range²).
  /// The filters judge terrain, not noise: the expected noise variance is taken out of each
  /// cell's height spread (the k sigma of the step filter) and of the disc's fit residual, and
  /// cell means count for the step only beyond step_noise_sigmas standard errors of their
  /// noise. 0 = no noise model (exact data).
  double stereo_noise_coeff = 0.0;  ///< [1/m]
  double step_noise_sigmas = 2.0;   ///< cell means are trusted to this many standard errors
  /// Fit discs to the latest scan's points only (MER's per-image assessment) instead of the
  /// merged map (newest data per cell, older data where the scan has none).
  bool fit_from_scan_only = false;

  // ---- merging -----------------------------------------------------------------------------
  int fov_edge_band_px = 2;       ///< [px] band inside the image footprint's outline = FOV edge
  int fov_edge_margin_cells = 1;  ///< goodness within this many cells of an edge cell is merged
                                  ///< conservatively (min of old and new)
  int num_layers = 7;             ///< layered goodness maps (1 = a single map, no layering)
  int unknown_goodness = 11;      ///< value of an unknown cell
  int unknown_certainty = 0;
  int border_goodness = 250;  ///< cap on a known cell next to an unknown one
  int border_certainty = 128;

  // ---- arcs and votes ----------------------------------------------------------------------
  double max_curvature = 1.0;  ///< [1/m] tightest arc (1 m turning radius)
  int num_forward_arcs = 23;
  int num_backward_arcs = 23;
  int num_point_turns = 23;       ///< turns in place, evenly spaced over the full circle
  double plan_min_dist = 0.3;     ///< [m] paths are evaluated from this arc length on
  double plan_max_dist = 3.0;     ///< [m] ... up to this (or the goal distance, if shorter)
  double path_half_width = 0.15;  ///< [m] cells whose centre is this close to the path count
  double near_weight = 2.0;       ///< weight of a path cell at the rover / at plan_max_dist
  int min_allowed_goodness = 10;  ///< a path over a cell below this is forbidden
  int min_vote_goodness = 26;     ///< below this, merging takes the minimum of the two votes
  int waypoint_certainty = 192;
  int waypoint_peak_toward = 255;  ///< waypoint vote of the best arc in the goal's direction
  int waypoint_peak_away = 128;    ///< ... in the other direction (and of turns normally)
  double arc_vote_variance = 3.2;  ///< [1/m^2] variance of the waypoint Gaussian over curvature
  double turn_vote_variance = 97.0 * kDegree * kDegree;  ///< [rad^2] ... over turn angle
  double backup_vote_scale = 0.5;                  ///< back-up (K-turn) votes are scaled by this
  /// [rad] Drive-direction hysteresis: after a forward arc, forward stays the goal's direction
  /// until the goal is this far behind abeam (|bearing| > 90 deg + h), and after a backward arc
  /// backward stays it until the goal is this far ahead of abeam. 0 = MER (the direction flips
  /// at abeam, which makes a rover skirting an obstacle with the goal abeam drive forward and
  /// back over the same half metre).
  double direction_hysteresis = 0.0;
  int min_fwd_threshold = 180;      ///< best forward vote below this: image the rear as well
  int skip_imaging_goodness = 200;  ///< all paths' hazard votes at or above: imaging may skip

  // ---- footprint check (ours, after Mars 2020's ENav; off = MER) ----------------------------
  /// MER's disc grows every rock by the turn-in-place radius in every heading, which closes the
  /// gaps of a dense field (VL-2) that the rover's rectangle fits through. With the check on:
  /// cells whose own top stands footprint_hazard_height or more above the lowest ground of the
  /// belly disc about them are hazard cells (GoodnessMap kCellHazard); the step and roughness filters no
  /// longer forbid on their own (their goodness is floored at min_allowed_goodness, so they
  /// still steer the vote away from rocks) while tilt still does; and a path is forbidden when
  /// the footprint rectangle, grown by footprint_margin and swept along it from the rover's
  /// pose, covers a hazard cell's centre within footprint_forbid_dist of arc length (any part
  /// of a turn in place). A hit farther along scales the path's hazard vote by s_hit / L.
  /// Hazard cells already under the grown footprint at the start are ignored (the rover is on
  /// them: moving off must stay possible).
  bool footprint_check = false;
  double footprint_min_x = -0.75;  ///< [m] rover frame; set from the rover description
  double footprint_max_x = 0.75;   ///< [m]
  double footprint_min_y = -0.58;  ///< [m]
  double footprint_max_y = 0.58;   ///< [m]
  double footprint_margin = 0.15;  ///< [m] about a cell's half diagonal plus tracking error
  double footprint_forbid_dist = 1.0;  ///< [m] hits within this arc length forbid the path
  /// [m] a cell whose top stands this high above the lowest ground of the belly disc about it
  /// is a hazard cell. Below max_step: a cell's top is its points' mean + k sigma over 20 cm,
  /// which reads a rock's peak low (a 21 cm dome's centre cell reads ~18 cm).
  double footprint_hazard_height = 0.15;
  /// Straddling (ours): instead of the whole footprint rectangle, the rover's contact parts
  /// (hwconfig ContactParts(): wheel discs, bogie and rocker bands, body box) grown by
  /// footprint_margin are swept along each path; a hazard cell counts against a part of zero
  /// clearance (wheels, bogies), and against the rocker and body only when it is also tall
  /// (kCellTall: cell_height >= footprint_tall_height). So a rock lower than the belly may pass
  /// between the wheels, as MER's rover was allowed to straddle what its belly cleared.
  bool footprint_straddle = false;
  /// [m] a hazard cell this high is tall (body 0.35 m and rocker 0.33 m up, less articulation
  /// and a cell's reading low)
  double footprint_tall_height = 0.22;
  /// The contact parts for footprint_straddle (not a parameter): the rover description's, set
  /// by ReadGestaltOptionsForRover.
  std::vector<hwconfig::ContactPart> contact_parts = hwconfig::RoverDescription{}.ContactParts();
  /// With footprint_check: the waypoint vote ranks candidates by the cost of driving them plus
  /// the cost-to-go from their end over the map (cost_to_go.hpp) instead of by closeness to the
  /// arc through the goal (MER). See arc_evaluator.hpp.
  bool cost_to_go = false;
  double cost_vote_sigma = 1.0;      ///< [m] width of the vote's Gaussian over cost excess
  double cost_goodness_weight = 1.0;  ///< extra step cost over a goodness-0 cell
  double cost_unknown_factor = 1.5;   ///< step cost factor of unknown cells

  /// Cells from a cell's centre to the edge of its rover disc (6.5 at MER's values).
  double rover_disc_radius_cells() const { return 0.5 * rover_disc_diameter / cell_size; }
  double step_disc_radius_cells() const { return 0.5 * step_disc_diameter / cell_size; }
  /// Cells along each side of the grid.
  int grid_cells() const;

  Status Validate() const;
  static void BindParams(ParamBinder<GestaltOptions>& b);
};

/// GESTALT's options for the rover described under `geometry_prefix` (core/hwconfig's
/// RoverDescription, declared in `params` with DeclareParams): the options under `prefix`, with
/// the rover disc set to the rover's turn-in-place circle (1.90 m for the default rover) unless
/// `<prefix>rover_disc_diameter_m` was given, and the footprint rectangle set to the rover's
/// ground footprint unless any `<prefix>footprint_m{in,ax}_{x,y}_m` was given. A disc larger than the rover grows every rock's
/// obstacle and spreads each tall rock's step over more of the map. Errors name the key.
Result<GestaltOptions> ReadGestaltOptionsForRover(const ParamSet& params,
                                                  const std::string& prefix = "gestalt.",
                                                  const std::string& geometry_prefix = "geometry.");

}  // namespace rover::apl::gestalt
