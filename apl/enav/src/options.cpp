#include "rover/apl/enav/options.hpp"

#include <cmath>

#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::apl::enav {

int EnavOptions::map_cells() const { return static_cast<int>(std::lround(map_size / cell_size)); }

Status EnavOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckRange("cell_size", cell_size, Bounds::OpenLow(0.0, 0.5), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("map_size", map_size, Bounds::OpenLow(0.0, 200.0), "m"));
  if (map_cells() > 2000) {
    return InvalidArgument(Describe("map_size", map_size, "m") + " at cell_size " +
                           FormatNumber(cell_size) + " m is " + std::to_string(map_cells()) +
                           " cells across (at most 2000)");
  }
  ROVER_RETURN_IF_ERROR(CheckPositive("max_point_distance", max_point_distance, "m"));
  if (recentre_distance <= 0.0 || recentre_distance + max_point_distance + 1.0 > 0.5 * map_size) {
    return InvalidArgument(Describe("recentre_distance", recentre_distance, "m") +
                           " must be > 0 and leave max_point_distance + 1 m inside half of "
                           "map_size = " + FormatNumber(map_size) + " m");
  }
  ROVER_RETURN_IF_ERROR(CheckNonNegative("overwrite_range_slack", overwrite_range_slack, "m"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("min_cell_points", min_cell_points, 1, 10000));
  ROVER_RETURN_IF_ERROR(CheckRange("self_margin", self_margin, 0.0, 2.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("ground_radius", ground_radius,
                                   Bounds::Closed(cell_size, 2.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("ground_quantile", ground_quantile, 0.0, 0.5));
  ROVER_RETURN_IF_ERROR(CheckRange("stereo_noise_coeff", stereo_noise_coeff, 0.0, 1.0, "1/m"));
  ROVER_RETURN_IF_ERROR(CheckRange("step_noise_sigmas", step_noise_sigmas, 0.0, 10.0));
  ROVER_RETURN_IF_ERROR(CheckRange("wheel_step", wheel_step, Bounds::OpenLow(0.0, 2.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("flank_step", flank_step, 0.0, wheel_step, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("flank_reach", flank_reach, 0.0, 2.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("shadow_reach", shadow_reach, 0.0, 2.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("clearance_margin", clearance_margin, 0.0, 1.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("cost_cell_size", cost_cell_size,
                                   Bounds::Closed(cell_size, 2.0), "m"));
  const double ratio = cost_cell_size / cell_size;
  if (std::abs(ratio - std::round(ratio)) > 1e-6) {
    return InvalidArgument(Describe("cost_cell_size", cost_cell_size, "m") +
                           " must be a whole multiple of cell_size = " + FormatNumber(cell_size) +
                           " m");
  }
  ROVER_RETURN_IF_ERROR(CheckRange("unknown_cost_factor", unknown_cost_factor, 1.0, 100.0));
  ROVER_RETURN_IF_ERROR(CheckRange("hazard_cost_radius", hazard_cost_radius, 0.0, 5.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("hazard_cost_factor", hazard_cost_factor, 0.0, 100.0));
  ROVER_RETURN_IF_ERROR(CheckRange("blocked_radius", blocked_radius, 0.0, 5.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("cspace_headings", cspace_headings, 0, 64));
  ROVER_RETURN_IF_ERROR(CheckIntRange("route_max_expansions", route_max_expansions, 0, 50000000));
  ROVER_RETURN_IF_ERROR(CheckRange("route_margin", route_margin, 0.0, 1.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("route_backward_factor", route_backward_factor, 1.0, 100.0));
  ROVER_RETURN_IF_ERROR(CheckRange("route_switch", route_switch, 0.0, 100.0, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("route_lookahead", route_lookahead, Bounds::OpenLow(0.0, 20.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("num_turns", num_turns, 1, 360));
  ROVER_RETURN_IF_ERROR(CheckIntRange("num_curvatures", num_curvatures, 1, 101));
  ROVER_RETURN_IF_ERROR(CheckRange("first_length", first_length, Bounds::OpenLow(0.0, 20.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("second_length", second_length, 0.0, 20.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("sample_spacing", sample_spacing,
                                   Bounds::OpenLow(0.0, first_length), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("turn_cost", turn_cost, 0.0, 100.0, "m/rad"));
  ROVER_RETURN_IF_ERROR(CheckRange("curvature_cost", curvature_cost, 0.0, 100.0, "m2"));
  ROVER_RETURN_IF_ERROR(CheckRange("commit_bonus", commit_bonus, 0.0, 100.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("planar_margin", planar_margin, 0.0, 1.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("max_checks", max_checks, 1, 100000));
  ROVER_RETURN_IF_ERROR(CheckRange("check_length", check_length, Bounds::OpenLow(0.0, 20.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("escape_margin", escape_margin, 0.0, 2.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("ace_length", ace_length, 0.0, 20.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("max_tilt", max_tilt, Bounds::OpenLow(0.0, 1.4), "rad"));
  ROVER_RETURN_IF_ERROR(CheckRange("suspension_margin", suspension_margin, 0.0, 0.5, "rad"));
  ROVER_RETURN_IF_ERROR(CheckRange("known_length", known_length, 0.0, 20.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("max_unknown_fraction", max_unknown_fraction, 0.0, 1.0));
  return rover.Validate();
}

void EnavOptions::BindParams(ParamBinder<EnavOptions>& b) {
  using O = EnavOptions;
  b.Bind("cell_size_m", &O::cell_size, "m", "height-map cell side (GESTALT: 0.2)")
      .Range(0.01, 0.5);
  b.Bind("map_size_m", &O::map_size, "m", "side of the remembered square height map")
      .Range(1.0, 200.0);
  b.Bind("recentre_distance_m", &O::recentre_distance, "m",
         "the map scrolls when the rover is this far from its centre")
      .Range(0.1, 100.0);
  b.Bind("max_point_distance_m", &O::max_point_distance, "m",
         "range points farther (horizontally) from the camera are not used")
      .Range(0.1, 100.0);
  b.Bind("overwrite_range_slack_m", &O::overwrite_range_slack, "m",
         "a fresh scan overwrites a cell unless the stored data were taken this much closer")
      .Range(0.0, 100.0);
  b.Bind("min_cell_points", &O::min_cell_points, "", "points a cell needs to count as known")
      .Range(1, 10000);
  b.Bind("self_margin_m", &O::self_margin, "m",
         "points within the rover's footprint grown by this are the rover's own: not merged")
      .Range(0.0, 2.0);
  b.Bind("drop_self_points", &O::drop_self_points,
         "drop range points within the footprint grown by self_margin_m (false: keep them)");
  b.Bind("ground_radius_m", &O::ground_radius, "m",
         "a cell's ground is taken from the known mean heights within this (see ground_quantile)")
      .Range(0.01, 2.0);
  b.Bind("ground_quantile", &O::ground_quantile, "",
         "a cell's ground is this quantile of the known mean heights within ground_radius_m "
         "(0 = the lowest; higher ignores stereo mismatches below the ground)")
      .Range(0.0, 0.5);
  b.Bind("stereo_noise_coeff", &O::stereo_noise_coeff, "1/m",
         "height noise sigma = coeff * r^2 of a point r m from the camera (0 = exact data)")
      .Range(0.0, 1.0);
  b.Bind("step_noise_sigmas", &O::step_noise_sigmas, "",
         "a step is a hazard only above its limit plus this many sigmas of that noise")
      .Range(0.0, 10.0);
  b.Bind("wheel_step_m", &O::wheel_step, "m",
         "steps above this reach a wheel or a bogie link (judge: rocks above 0.2 m)")
      .Range(0.001, 2.0);
  b.Bind("flank_step_m", &O::flank_step, "m",
         "a hazard grows into neighbouring cells whose step exceeds this (its flank)")
      .Range(0.0, 2.0);
  b.Bind("flank_reach_m", &O::flank_reach, "m", "... up to this far from its cells")
      .Range(0.0, 2.0);
  b.Bind("shadow_reach_m", &O::shadow_reach, "m",
         "a hazard also grows this far into unseen cells beside it (0 = off)")
      .Range(0.0, 2.0);
  b.Bind("clearance_margin_m", &O::clearance_margin, "m",
         "below the rocker links' and the belly's clearances, for articulation and map error")
      .Range(0.0, 1.0);
  b.Bind("cost_cell_size_m", &O::cost_cell_size, "m",
         "cell of the cost-to-go field (a whole multiple of cell_size)")
      .Range(0.01, 2.0);
  b.Bind("unknown_cost_factor", &O::unknown_cost_factor, "",
         "cost factor of a step over an unseen cell (priced, not forbidden)")
      .Range(1.0, 100.0);
  b.Bind("hazard_cost_radius_m", &O::hazard_cost_radius, "m",
         "cost-to-go cells nearer a wheel hazard than this cost more")
      .Range(0.0, 5.0);
  b.Bind("hazard_cost_factor", &O::hazard_cost_factor, "",
         "extra step cost factor at a wheel hazard, falling linearly to 0 at the radius")
      .Range(0.0, 100.0);
  b.Bind("blocked_radius_m", &O::blocked_radius, "m",
         "cost-to-go cells this near a hazard to the body are blocked")
      .Range(0.0, 5.0);
  b.Bind("cspace_headings", &O::cspace_headings, "",
         "cost-to-go cells where the rover fits in none of this many headings are blocked "
         "(0 = off)")
      .Range(0, 64);
  b.Bind("route_max_expansions", &O::route_max_expansions, "",
         "poses the route search (x, y, heading lattice to the goal) may expand per decision; "
         "0 = the path tree alone")
      .Range(0, 50000000);
  b.Bind("route_first", &O::route_first,
         "true: drive along the route whenever a step along it passes the check; false: only "
         "when no path of the tree passes");
  b.Bind("route_margin_m", &O::route_margin, "m",
         "the route keeps this much room beyond the clearance check's planar margin")
      .Range(0.0, 1.0);
  b.Bind("route_backward_factor", &O::route_backward_factor, "",
         "backward moves of a route cost this many times forward ones")
      .Range(1.0, 100.0);
  b.Bind("route_switch_m", &O::route_switch, "m",
         "the route followed is kept unless a new search finds one this much cheaper")
      .Range(0.0, 100.0);
  b.Bind("route_lookahead_m", &O::route_lookahead, "m",
         "a step drives straight at a route pose at most this far along the route")
      .Range(0.01, 20.0);
  b.Bind("num_turns", &O::num_turns, "",
         "headings of the leading turn in place, evenly over the full circle (1 = none)")
      .Range(1, 360);
  b.Bind("num_curvatures", &O::num_curvatures, "",
         "curvatures per arc segment, evenly in [-max, +max] of the rover description")
      .Range(1, 101);
  b.Bind("first_length_m", &O::first_length, "m", "first arc segment of each path")
      .Range(0.01, 20.0);
  b.Bind("second_length_m", &O::second_length, "m", "second arc segment (0 = one segment)")
      .Range(0.0, 20.0);
  b.Bind("sample_spacing_m", &O::sample_spacing, "m", "poses along a path for the checks")
      .Range(0.01, 5.0);
  b.Bind("turn_cost_m_per_rad", &O::turn_cost, "m/rad",
         "cost of turning in place, in metres of driving per radian")
      .Range(0.0, 100.0);
  b.Bind("curvature_cost", &O::curvature_cost, "m2",
         "cost of |curvature| per metre driven (prefers straight paths)")
      .Range(0.0, 100.0);
  b.Bind("commit_bonus_m", &O::commit_bonus, "m",
         "taken off the cost of continuing the previous choice (hysteresis against dithering)")
      .Range(0.0, 100.0);
  b.Bind("planar_margin_m", &O::planar_margin, "m",
         "the rover's parts grown by this in the clearance check (tracking and map error)")
      .Range(0.0, 1.0);
  b.Bind("max_checks", &O::max_checks, "",
         "paths clearance-checked in rank order before the step gives up (NOPATH)")
      .Range(1, 100000);
  b.Bind("check_length_m", &O::check_length, "m",
         "clearance is checked over this first stretch of each path; beyond, only its cost")
      .Range(0.01, 20.0);
  b.Bind("escape_margin_m", &O::escape_margin, "m",
         "when nothing passes, hazards this near the rover's footprint are ignored once")
      .Range(0.0, 2.0);
  b.Bind("ace_length_m", &O::ace_length, "m",
         "suspension angles, tilt and belly are checked this far along each path")
      .Range(0.0, 20.0);
  b.BindDegrees("max_tilt_deg", &O::max_tilt, "largest predicted tilt (MER 20)").Range(0.1, 80.0);
  b.BindDegrees("suspension_margin_deg", &O::suspension_margin,
                "predicted rocker and bogie angles stay this far inside their stops")
      .Range(0.0, 30.0);
  b.Bind("known_length_m", &O::known_length, "m",
         "this first stretch of a path must lie mostly on seen cells")
      .Range(0.0, 20.0);
  b.Bind("max_unknown_fraction", &O::max_unknown_fraction, "",
         "share of unseen wheel samples allowed in known_length")
      .Range(0.0, 1.0);
}

Result<EnavOptions> ReadEnavOptionsForRover(const ParamSet& params, const std::string& prefix,
                                            const std::string& geometry_prefix) {
  ROVER_ASSIGN_OR_RETURN(const hwconfig::RoverDescription rover,
                         ReadParams<hwconfig::RoverDescription>(params, geometry_prefix));
  ROVER_ASSIGN_OR_RETURN(EnavOptions o, ReadParams<EnavOptions>(params, prefix));
  o.rover = rover;
  o.contact_parts = rover.ContactParts();
  ROVER_RETURN_IF_ERROR(o.Validate());
  return o;
}

}  // namespace rover::apl::enav
