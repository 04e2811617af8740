#pragma once
/// @file
/// EnavOptions: every parameter of the ENav-class planner (height map, hazard classes,
/// cost-to-go, path tree, clearance check), declared once (BindParams, keys carry their unit)
/// and checked by Validate() (messages start with the member's name). README.md has the table.
///
/// The rover's own geometry (wheels, links, body and their clearances, the curvature limit) is
/// not here: it comes from core/hwconfig's RoverDescription (ContactParts(), MaxCurvature()),
/// read with the same parameter set (ReadEnavOptionsForRover).
///
/// Units: metres, radians in members (degrees in keys that say `_deg`).

#include <string>
#include <vector>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/base/units.hpp"
#include "rover/hwconfig/rover_description.hpp"

namespace rover::apl::enav {

struct EnavOptions {
  // ---- height map -------------------------------------------------------------------------
  double cell_size = 0.1;          ///< [m] height-map cell side (half GESTALT's 0.2 m)
  double map_size = 40.0;          ///< [m] side of the remembered square map
  double recentre_distance = 8.0;  ///< [m] the map scrolls when the rover is this far off centre
  double max_point_distance = 6.0; ///< [m] points farther (horizontally) from the camera unused
  /// A fresh scan overwrites a cell unless the stored data were taken this much closer [m]
  /// (nearer data are more accurate; stale data are replaced only by data about as good).
  double overwrite_range_slack = 0.5;
  int min_cell_points = 2;          ///< points a cell needs to count as known
  /// Points within the rover's ground footprint grown by this [m] (rover frame at capture) are
  /// not merged: they lie on the rover itself (wheels, body) where the stereo mask leaks, or on
  /// ground it hides; merged, they become rocks the rear wheels then meet.
  double self_margin = 0.1;
  bool drop_self_points = true;  ///< false: merge them too (synthetic scans without a rover)
  double ground_radius = 0.35;      ///< [m] the local ground is taken from the means within this
  /// The local ground is this quantile of the known means within ground_radius (0 = the
  /// lowest). Above 0, a few cells that stereo mismatches put below the ground (dl-stereo's
  /// HAZCAM images hold such holes 0.1-0.3 m deep at 1.5-3 m) no longer lower the ground of
  /// every cell around them, which would make flat ground read as steps.
  double ground_quantile = 0.2;
  /// Stereo noise: height sigma = stereo_noise_coeff · r² at horizontal range r [m]; a step
  /// counts as a hazard only above its class's limit plus step_noise_sigmas of that noise.
  double stereo_noise_coeff = 0.0;  ///< [1/m]
  double step_noise_sigmas = 2.0;
  /// Steps above this reach a wheel or the bogie link [m] (the judge's traversable rock
  /// height is 0.2 m; a margin below it).
  double wheel_step = 0.17;
  /// A hazard's outline: from its cells the hazard grows into neighbouring cells whose step
  /// (noise allowed for) still exceeds flank_step, up to flank_reach [m] (a rock's flank
  /// below the part's limit is still the rock: the judge counts its whole outline).
  double flank_step = 0.05;
  double flank_reach = 0.2;
  /// [m] A hazard also grows this far into unseen cells beside it (its unseen side, more
  /// likely rock than ground, until the cameras see it); 0 = off.
  double shadow_reach = 0.0;
  /// Height margin below the rocker links' and the belly's clearances (from the rover
  /// description) for articulation and map error [m].
  double clearance_margin = 0.05;

  // ---- cost-to-go -------------------------------------------------------------------------
  double cost_cell_size = 0.2;        ///< [m] cells of the cost-to-go field
  double unknown_cost_factor = 1.5;   ///< step cost factor of unseen cells (priced, not forbidden)
  double hazard_cost_radius = 0.9;    ///< [m] cells nearer a wheel hazard than this cost more
  double hazard_cost_factor = 2.0;    ///< ... up to 1 + this at the hazard
  double blocked_radius = 0.3;        ///< [m] cells this near a body hazard are blocked
  /// Cells where the rover's parts (clearance check, no ACE) fit in none of this many headings
  /// over half a turn are blocked (a configuration-space cost-to-go: gaps narrower than the
  /// rover are not routes). 0 = off.
  int cspace_headings = 8;

  // ---- route search (RouteSearch) ----------------------------------------------------------
  /// Poses a route search may expand per decision; 0 = no route search (the tree alone).
  int route_max_expansions = 0;
  /// true: every decision drives along the route when a step along it passes the check (the
  /// tree only when none does); false: the route is tried only when no path of the tree passes
  /// (before the escape pass).
  bool route_first = false;
  double route_margin = 0.03;           ///< [m] the route keeps this beyond planar_margin
  double route_backward_factor = 2.0;   ///< backward lattice moves cost this many times more
  /// [m-equivalent] the route followed is kept unless a new search finds one this much cheaper
  double route_switch = 1.0;
  /// [m] along the route: the farthest route pose a step's straight line may aim at.
  double route_lookahead = 3.0;

  // ---- path tree --------------------------------------------------------------------------
  int num_turns = 24;            ///< headings of the leading turn in place over the full circle
  int num_curvatures = 9;        ///< curvatures per arc segment in [-max, +max]
  double first_length = 1.5;     ///< [m] first arc segment
  double second_length = 4.0;    ///< [m] second arc segment
  double sample_spacing = 0.1;   ///< [m] poses along a path for the checks
  double turn_cost = 1.0;        ///< [m/rad] cost of turning in place, in metres of driving
  double curvature_cost = 0.2;   ///< [m per 1/m] cost of |curvature| per metre driven
  double commit_bonus = 0.5;     ///< [m] off the cost of continuing the previous choice

  // ---- clearance check --------------------------------------------------------------------
  double planar_margin = 0.04;   ///< [m] parts grown by this (tracking and map error)
  int max_checks = 300;          ///< paths checked in rank order before giving up (NOPATH)
  /// Each path's clearance is checked over its first check_length [m]; beyond, only its cost
  /// (hazard proximity in the cost-to-go factor) counts: the far part is replanned from closer
  /// and better data long before it is driven.
  double check_length = 3.0;
  /// When no path passes, the checks run again ignoring hazard cells within this of the rover's
  /// own ground footprint [m] (an escape from beside a rock the map now shows too close).
  double escape_margin = 0.3;
  double ace_length = 2.0;       ///< [m] suspension, tilt and belly checked this far along
  double max_tilt = 20.0 * kDegree;  ///< [rad]
  double suspension_margin = 0.1;    ///< [rad] below the rocker and bogie stops
  /// Unknown cells under the wheels within this far along the path make it fail [m] (the
  /// first stretch is driven next and must have been seen); beyond, unknown passes.
  double known_length = 1.0;
  double max_unknown_fraction = 0.3;  ///< of the wheel samples in known_length

  // ---- from the rover description (ReadEnavOptionsForRover) -----------------------------
  std::vector<hwconfig::ContactPart> contact_parts;  ///< empty = RoverDescription's defaults
  hwconfig::RoverDescription rover;                  ///< wheel layout, pivots, stops

  /// Ranges and cross-field rules; messages start with the field.
  Status Validate() const;
  static void BindParams(ParamBinder<EnavOptions>& b);
  int map_cells() const;
};

/// Reads `prefix` keys (default "enav.") and the rover description under `geometry_prefix`
/// (default "geometry."), and takes the contact parts, suspension and curvature limit from it.
Result<EnavOptions> ReadEnavOptionsForRover(const ParamSet& params,
                                            const std::string& prefix = "enav.",
                                            const std::string& geometry_prefix = "geometry.");

}  // namespace rover::apl::enav
