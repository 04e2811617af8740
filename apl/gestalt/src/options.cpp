#include "rover/apl/gestalt/options.hpp"

#include <cmath>
#include <string>

#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"
#include "rover/hwconfig/rover_description.hpp"

namespace rover::apl::gestalt {
namespace {

using G = GestaltOptions;

// "<a> = x must be below <b> = y" for ordered pairs of thresholds.
Status CheckBelow(const char* a, double va, const char* b, double vb, const char* unit) {
  if (va < vb) return Status::Ok();
  return InvalidArgument(Describe(a, va, unit) + " must be below " + Describe(b, vb, unit));
}

Status CheckByte(const char* name, int v) { return CheckIntRange(name, v, 0, 255); }

}  // namespace

int GestaltOptions::grid_cells() const {
  return static_cast<int>(std::lround(map_size / cell_size));
}

Status GestaltOptions::Validate() const {
  // Grid.
  ROVER_RETURN_IF_ERROR(CheckRange("cell_size", cell_size, Bounds::OpenLow(0.0, 1.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("map_size", map_size, Bounds::OpenLow(0.0, 100.0), "m"));
  if (grid_cells() > 1000) {
    return InvalidArgument(Describe("map_size", map_size, "m") + " at cell_size " +
                           FormatNumber(cell_size) + " m is " + std::to_string(grid_cells()) +
                           " cells across (at most 1000)");
  }
  ROVER_RETURN_IF_ERROR(CheckPositive("forget_radius", forget_radius, "m"));
  ROVER_RETURN_IF_ERROR(CheckPositive("max_point_distance", max_point_distance, "m"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("min_cell_points", min_cell_points, 1, 1000000));
  ROVER_RETURN_IF_ERROR(CheckRange("min_coverage", min_coverage, Bounds::OpenLow(0.0, 1.0)));
  // Filters.
  ROVER_RETURN_IF_ERROR(CheckPositive("rover_disc_diameter", rover_disc_diameter, "m"));
  if (rover_disc_diameter < 2.0 * cell_size) {
    return InvalidArgument(Describe("rover_disc_diameter", rover_disc_diameter, "m") +
                           " must span at least two cells of " + FormatNumber(cell_size) + " m");
  }
  if (rover_disc_diameter + 2.0 * cell_size > map_size) {
    return InvalidArgument(Describe("rover_disc_diameter", rover_disc_diameter, "m") +
                           " does not fit in map_size = " + FormatNumber(map_size) +
                           " m with a cell to spare on each side");
  }
  ROVER_RETURN_IF_ERROR(CheckRange("step_disc_diameter", step_disc_diameter,
                                   Bounds::OpenLow(0.0, rover_disc_diameter), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("step_sigma_k", step_sigma_k, 0.0, 10.0));
  ROVER_RETURN_IF_ERROR(CheckRange("stereo_noise_coeff", stereo_noise_coeff, 0.0, 1.0, "1/m"));
  ROVER_RETURN_IF_ERROR(CheckRange("step_noise_sigmas", step_noise_sigmas, 0.0, 10.0));
  ROVER_RETURN_IF_ERROR(CheckPositive("max_step", max_step, "m"));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("step_safe", step_safe, "m"));
  ROVER_RETURN_IF_ERROR(CheckBelow("step_safe", step_safe, "max_step", max_step, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("max_tilt", max_tilt, Bounds::OpenLow(0.0, 80.0 * kDegree), "rad"));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("tilt_safe", tilt_safe, "rad"));
  ROVER_RETURN_IF_ERROR(CheckBelow("tilt_safe", tilt_safe, "max_tilt", max_tilt, "rad"));
  ROVER_RETURN_IF_ERROR(CheckPositive("max_roughness", max_roughness, "m"));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("roughness_safe", roughness_safe, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckBelow("roughness_safe", roughness_safe, "max_roughness", max_roughness, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("eigen_ratio", eigen_ratio, 1.0, 1e6));
  // Merging.
  ROVER_RETURN_IF_ERROR(CheckIntRange("fov_edge_band_px", fov_edge_band_px, 0, 64));
  ROVER_RETURN_IF_ERROR(CheckIntRange("fov_edge_margin_cells", fov_edge_margin_cells, 0, 10));
  ROVER_RETURN_IF_ERROR(CheckIntRange("num_layers", num_layers, 1, 16));
  ROVER_RETURN_IF_ERROR(CheckByte("unknown_goodness", unknown_goodness));
  ROVER_RETURN_IF_ERROR(CheckByte("unknown_certainty", unknown_certainty));
  ROVER_RETURN_IF_ERROR(CheckByte("border_goodness", border_goodness));
  ROVER_RETURN_IF_ERROR(CheckByte("border_certainty", border_certainty));
  // Arcs and votes.
  ROVER_RETURN_IF_ERROR(
      CheckRange("max_curvature", max_curvature, Bounds::OpenLow(0.0, 10.0), "1/m"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("num_forward_arcs", num_forward_arcs, 1, 99));
  ROVER_RETURN_IF_ERROR(CheckIntRange("num_backward_arcs", num_backward_arcs, 0, 99));
  ROVER_RETURN_IF_ERROR(CheckIntRange("num_point_turns", num_point_turns, 0, 359));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("plan_min_dist", plan_min_dist, "m"));
  ROVER_RETURN_IF_ERROR(CheckPositive("plan_max_dist", plan_max_dist, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckBelow("plan_min_dist", plan_min_dist, "plan_max_dist", plan_max_dist, "m"));
  if (plan_max_dist > 0.5 * map_size) {
    return InvalidArgument(
        Describe("plan_max_dist", plan_max_dist, "m") +
        " reaches beyond the map (half of map_size = " + FormatNumber(0.5 * map_size) + " m)");
  }
  ROVER_RETURN_IF_ERROR(
      CheckRange("path_half_width", path_half_width, Bounds::OpenLow(0.0, 2.0), "m"));
  if (path_half_width < cell_size / std::sqrt(2.0)) {
    return InvalidArgument(
        Describe("path_half_width", path_half_width, "m") +
        " must be at least cell_size / sqrt(2) = " + FormatNumber(cell_size / std::sqrt(2.0)) +
        " m so that every point of a path lies on a path cell");
  }
  ROVER_RETURN_IF_ERROR(CheckRange("near_weight", near_weight, 1.0, 100.0));
  ROVER_RETURN_IF_ERROR(CheckByte("min_allowed_goodness", min_allowed_goodness));
  ROVER_RETURN_IF_ERROR(CheckByte("min_vote_goodness", min_vote_goodness));
  ROVER_RETURN_IF_ERROR(CheckByte("waypoint_certainty", waypoint_certainty));
  ROVER_RETURN_IF_ERROR(CheckByte("waypoint_peak_toward", waypoint_peak_toward));
  ROVER_RETURN_IF_ERROR(CheckByte("waypoint_peak_away", waypoint_peak_away));
  ROVER_RETURN_IF_ERROR(CheckPositive("arc_vote_variance", arc_vote_variance, "1/m^2"));
  ROVER_RETURN_IF_ERROR(CheckPositive("turn_vote_variance", turn_vote_variance, "rad^2"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("backup_vote_scale", backup_vote_scale, Bounds::OpenLow(0.0, 1.0)));
  ROVER_RETURN_IF_ERROR(CheckRange("direction_hysteresis", direction_hysteresis,
                                   Bounds::Closed(0.0, 90.0 * kDegree), "rad"));
  ROVER_RETURN_IF_ERROR(CheckByte("min_fwd_threshold", min_fwd_threshold));
  ROVER_RETURN_IF_ERROR(CheckByte("skip_imaging_goodness", skip_imaging_goodness));
  // Footprint check.
  ROVER_RETURN_IF_ERROR(CheckRange("footprint_min_x", footprint_min_x, Bounds{-10.0, 0.0, false, true}, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("footprint_max_x", footprint_max_x, Bounds::OpenLow(0.0, 10.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("footprint_min_y", footprint_min_y, Bounds{-10.0, 0.0, false, true}, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("footprint_max_y", footprint_max_y, Bounds::OpenLow(0.0, 10.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("footprint_margin", footprint_margin, 0.0, 2.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("footprint_forbid_dist", footprint_forbid_dist,
                                   Bounds::OpenLow(0.0, 50.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("footprint_hazard_height", footprint_hazard_height,
                                   Bounds::OpenLow(0.0, 5.0), "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("footprint_tall_height", footprint_tall_height, Bounds::OpenLow(0.0, 5.0), "m"));
  if (footprint_straddle && !footprint_check) {
    return InvalidArgument("footprint_straddle = true needs footprint_check = true");
  }
  if (footprint_straddle && contact_parts.empty()) {
    return InvalidArgument("footprint_straddle = true needs the rover's contact parts (none set)");
  }
  if (cost_to_go && !footprint_check) {
    return InvalidArgument("cost_to_go = true needs footprint_check = true (it plans around the "
                           "footprint check's hazard cells)");
  }
  ROVER_RETURN_IF_ERROR(CheckRange("cost_vote_sigma", cost_vote_sigma, Bounds::OpenLow(0.0, 100.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("cost_goodness_weight", cost_goodness_weight, 0.0, 100.0));
  ROVER_RETURN_IF_ERROR(CheckRange("cost_unknown_factor", cost_unknown_factor, 1.0, 100.0));
  return Status::Ok();
}

void GestaltOptions::BindParams(ParamBinder<GestaltOptions>& b) {
  // MER's goodness and certainty values are 8-bit.
  auto byte = [&b](const char* key, int G::*member, const char* doc) {
    b.Bind(key, member, "", doc).Range(0, 255);
  };
  b.Bind("cell_size_m", &G::cell_size, "m", "grid cell side (MER 0.2)").Range(0.01, 1.0);
  b.Bind("map_size_m", &G::map_size, "m", "side of the square grid that follows the rover (MER 10)")
      .Range(1.0, 100.0);
  b.Bind("forget_radius_m", &G::forget_radius, "m",
         "data farther than this from the rover is forgotten (MER 5)")
      .Min(0.1);
  b.Bind("max_point_distance_m", &G::max_point_distance, "m",
         "range points farther from the rover (horizontally) are not used (MER 5)")
      .Min(0.1);
  b.Bind("min_cell_points", &G::min_cell_points, "",
         "points a cell needs to count as covered (MER 2)")
      .Range(1, 1000000);
  b.Bind("min_coverage", &G::min_coverage, "",
         "share of a rover disc's cells that must be covered for a plane fit (MER 0.5)")
      .Range(0.01, 1.0);
  b.Bind("rover_disc_diameter_m", &G::rover_disc_diameter, "m",
         "rover modelled as its turn-in-place disc (MER 2.6)")
      .Range(0.1, 20.0);
  b.Bind("step_disc_diameter_m", &G::step_disc_diameter, "m",
         "belly-sized disc in which steps are searched")
      .Range(0.05, 20.0);
  b.Bind("step_sigma_k", &G::step_sigma_k, "", "cell top = mean + k sigma (tall thin obstacles)")
      .Range(0.0, 10.0);
  b.Bind("stereo_noise_coeff", &G::stereo_noise_coeff, "1/m",
         "height noise sigma = coeff * d^2 of a point d m from the rover (0 = none; ours)")
      .Range(0.0, 1.0);
  b.Bind("step_noise_sigmas", &G::step_noise_sigmas, "",
         "cell means count for the step beyond this many standard errors of noise (ours)")
      .Range(0.0, 10.0);
  b.Bind("step_safe_m", &G::step_safe, "m", "steps up to this are perfect (MER 1/3 of max_step)")
      .Min(0.0);
  b.Bind("max_step_m", &G::max_step, "m", "tallest traversable step (MER 0.20)").Range(0.001, 5.0);
  b.BindDegrees("tilt_safe_deg", &G::tilt_safe, "tilts up to this are perfect").Range(0.0, 80.0);
  b.BindDegrees("max_tilt_deg", &G::max_tilt, "tilts from this on are obstacles (MER 20)")
      .Range(0.1, 80.0);
  b.Bind("roughness_safe_m", &G::roughness_safe, "m",
         "plane-fit residuals up to this are perfect (MER 1/3 of max_roughness)")
      .Min(0.0);
  b.Bind("max_roughness_m", &G::max_roughness, "m",
         "plane-fit residuals from this on are obstacles (MER 0.07)")
      .Range(0.001, 5.0);
  b.Bind("eigen_ratio", &G::eigen_ratio, "",
         "middle / smallest eigenvalue of a valid plane fit (MER 2)")
      .Range(1.0, 1e6);
  b.Bind("fit_from_scan_only", &G::fit_from_scan_only,
         "fit planes to the latest scan only (MER's per-image assessment) instead of the map");
  b.Bind("fov_edge_band_px", &G::fov_edge_band_px, "px",
         "band inside the outline of the image footprint that counts as the FOV edge")
      .Range(0, 64);
  b.Bind("fov_edge_margin_cells", &G::fov_edge_margin_cells, "",
         "cells around FOV-edge cells whose goodness is merged as min(old, new)")
      .Range(0, 10);
  b.Bind("num_layers", &G::num_layers, "", "layered goodness maps (MER 7; 1 = no layering)")
      .Range(1, 16);
  byte("unknown_goodness", &G::unknown_goodness, "goodness of an unknown cell (MER 11)");
  byte("unknown_certainty", &G::unknown_certainty, "certainty of an unknown cell (MER 0)");
  byte("border_goodness", &G::border_goodness,
       "goodness cap of a cell next to an unknown one (MER 250)");
  byte("border_certainty", &G::border_certainty, "certainty of a border cell (MER 128)");
  b.Bind("max_curvature", &G::max_curvature, "1/m", "tightest arc (MER 1)").Range(0.01, 10.0);
  b.Bind("num_forward_arcs", &G::num_forward_arcs, "", "forward arcs (MER 23)").Range(1, 99);
  b.Bind("num_backward_arcs", &G::num_backward_arcs, "", "backward arcs (MER 23)").Range(0, 99);
  b.Bind("num_point_turns", &G::num_point_turns, "",
         "turns in place, evenly spaced over the circle (MER 0..46)")
      .Range(0, 359);
  b.Bind("plan_min_dist_m", &G::plan_min_dist, "m", "paths are evaluated from here (MER 0.3)")
      .Min(0.0);
  b.Bind("plan_max_dist_m", &G::plan_max_dist, "m", "paths are evaluated up to here (MER 3)")
      .Range(0.01, 50.0);
  b.Bind("path_half_width_m", &G::path_half_width, "m",
         "cells whose centre lies this close to the rover-centre path are on it")
      .Range(0.001, 2.0);
  b.Bind("near_weight", &G::near_weight, "",
         "weight of a path cell next to the rover relative to one at plan_max_dist")
      .Range(1.0, 100.0);
  byte("min_allowed_goodness", &G::min_allowed_goodness,
       "a path over a cell below this is forbidden (MER 10)");
  byte("min_vote_goodness", &G::min_vote_goodness,
       "below this either vote wins by minimum when merging (MER 26)");
  byte("waypoint_certainty", &G::waypoint_certainty, "certainty of waypoint votes (MER 192)");
  byte("waypoint_peak_toward", &G::waypoint_peak_toward,
       "waypoint vote of the arc through the goal, driving toward it (MER 255)");
  byte("waypoint_peak_away", &G::waypoint_peak_away,
       "... driving away from it, and of turns in place normally (MER 128)");
  b.Bind("arc_vote_variance", &G::arc_vote_variance, "1/m^2",
         "variance of the waypoint Gaussian over curvature (MER 3.2)")
      .Range(1e-6, 1e6);
  b.BindScaled("turn_vote_variance_deg2", &G::turn_vote_variance, kDegree * kDegree, "deg^2",
               "variance of the waypoint Gaussian over turn angle (MER 97)")
      .Range(1e-6, 1e8)
      .Field("turn_vote_variance");
  b.Bind("backup_vote_scale", &G::backup_vote_scale, "",
         "scale of the back-up (K-turn) votes (MER 0.5: halved)")
      .Range(0.001, 1.0);
  b.BindDegrees("direction_hysteresis_deg", &G::direction_hysteresis,
                "after an arc, its direction stays the goal's until the goal is this far past "
                "abeam (MER 0: flips at abeam)")
      .Range(0.0, 90.0);
  byte("min_fwd_threshold", &G::min_fwd_threshold,
       "best forward vote below this advises imaging the rear (MER 180)");
  byte("skip_imaging_goodness", &G::skip_imaging_goodness,
       "every path's hazard vote at or above this (on known cells): imaging may be skipped");
  b.Bind("footprint_check", &G::footprint_check,
         "check the rover's footprint rectangle against hazard cells along each path instead of "
         "forbidding by the rover disc's step (ours, after ENav; false = MER)");
  b.Bind("footprint_min_x_m", &G::footprint_min_x, "m", "footprint rear edge, rover frame")
      .Range(-10.0, 0.0);
  b.Bind("footprint_max_x_m", &G::footprint_max_x, "m", "footprint front edge").Range(0.0, 10.0);
  b.Bind("footprint_min_y_m", &G::footprint_min_y, "m", "footprint right edge").Range(-10.0, 0.0);
  b.Bind("footprint_max_y_m", &G::footprint_max_y, "m", "footprint left edge").Range(0.0, 10.0);
  b.Bind("footprint_margin_m", &G::footprint_margin, "m",
         "footprint grown by this for the check (cell half diagonal + tracking error)")
      .Range(0.0, 2.0);
  b.Bind("footprint_forbid_dist_m", &G::footprint_forbid_dist, "m",
         "a footprint hit within this arc length forbids a path; farther, it scales its vote")
      .Range(0.001, 50.0);
  b.Bind("footprint_hazard_height_m", &G::footprint_hazard_height, "m",
         "a cell this high above the belly disc's lowest ground is a hazard cell")
      .Range(0.001, 5.0);
  b.Bind("footprint_straddle", &G::footprint_straddle,
         "sweep the rover's contact parts (wheels, suspension, body) instead of its footprint "
         "rectangle, so hazards lower than the belly may pass between the wheels (ours)");
  b.Bind("footprint_tall_height_m", &G::footprint_tall_height, "m",
         "a hazard cell this high reaches the body and rocker links (footprint_straddle)")
      .Range(0.001, 5.0);
  b.Bind("cost_to_go", &G::cost_to_go,
         "waypoint vote by drive cost + cost-to-go over the map (ours, after MER's 2006 Field "
         "D*; needs footprint_check) instead of by the arc through the goal (MER)");
  b.Bind("cost_vote_sigma_m", &G::cost_vote_sigma, "m",
         "width of the waypoint Gaussian over a candidate's cost above the best")
      .Range(0.001, 100.0);
  b.Bind("cost_goodness_weight", &G::cost_goodness_weight, "",
         "extra cost-to-go per metre over a goodness-0 cell (linear in 255 - goodness)")
      .Range(0.0, 100.0);
  b.Bind("cost_unknown_factor", &G::cost_unknown_factor, "",
         "cost-to-go factor of unknown cells")
      .Range(1.0, 100.0);
}

Result<GestaltOptions> ReadGestaltOptionsForRover(const ParamSet& params, const std::string& prefix,
                                                  const std::string& geometry_prefix) {
  ROVER_ASSIGN_OR_RETURN(const hwconfig::RoverDescription rover,
                         ReadParams<hwconfig::RoverDescription>(params, geometry_prefix));
  ROVER_ASSIGN_OR_RETURN(GestaltOptions g, ReadParams<GestaltOptions>(params, prefix));
  g.contact_parts = rover.ContactParts();
  if (params.Origin(prefix + "rover_disc_diameter_m").source == "default") {
    g.rover_disc_diameter = rover.TurnInPlaceCircle().Diameter();
    if (Status s = g.Validate(); !s.ok()) {
      return InvalidArgument("the rover description's turn-in-place disc (" +
                             FormatNumber(g.rover_disc_diameter, 3) +
                             " m) does not suit GESTALT: " + s.message());
    }
  }
  const bool footprint_given = params.Origin(prefix + "footprint_min_x_m").source != "default" ||
                               params.Origin(prefix + "footprint_max_x_m").source != "default" ||
                               params.Origin(prefix + "footprint_min_y_m").source != "default" ||
                               params.Origin(prefix + "footprint_max_y_m").source != "default";
  if (!footprint_given) {
    const hwconfig::Footprint f = rover.GroundFootprint();
    g.footprint_min_x = f.min_x;
    g.footprint_max_x = f.max_x;
    g.footprint_min_y = f.min_y;
    g.footprint_max_y = f.max_y;
    if (Status s = g.Validate(); !s.ok()) {
      return InvalidArgument("the rover description's ground footprint does not suit GESTALT: " +
                             s.message());
    }
  }
  return g;
}

}  // namespace rover::apl::gestalt
