#include "rover/apl/roaman/options.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::apl::roaman {

const char* AlgorithmName(Algorithm a) {
  switch (a) {
    case Algorithm::kRoaman:
      return "roaman";
    case Algorithm::kAStar:
      return "astar";
  }
  return "?";
}

double Footprint::turn_radius() const { return 0.5 * std::hypot(length, width); }

double Footprint::TurnClearance(double turn) const {
  const double a = std::abs(turn);
  if (a >= 0.5 * std::numbers::pi) return turn_radius();
  return std::min(turn_radius(), 0.5 * width + 0.5 * length * std::sin(a));
}

int RoamanOptions::map_cells() const { return static_cast<int>(std::lround(map_size / cell_size)); }

int RoamanOptions::normal_half_cells() const {
  return std::max(1, static_cast<int>(std::lround(0.5 * (normal_window / cell_size - 1.0))));
}

Status RoamanOptions::Validate() const {
  using B = Bounds;
  // Rover.
  ROVER_RETURN_IF_ERROR(CheckRange("rover_length", rover_length, B::OpenLow(0.0, 10.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("rover_width", rover_width, B::OpenLow(0.0, 10.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("body_clearance", body_clearance, B::OpenLow(0.0, 2.0), "m"));
  // Map memory.
  ROVER_RETURN_IF_ERROR(CheckRange("cell_size", cell_size, B::OpenLow(0.0, 0.5), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("map_size", map_size, B::OpenLow(0.0, 200.0), "m"));
  if (map_cells() < 16 || map_cells() > 2000) {
    return InvalidArgument(Describe("map_size", map_size, "m") + " at cell_size " +
                           FormatNumber(cell_size) + " m is " + std::to_string(map_cells()) +
                           " cells across (allowed 16 to 2000)");
  }
  ROVER_RETURN_IF_ERROR(
      CheckRange("recenter_distance", recenter_distance, B::OpenLow(0.0, 0.5 * map_size), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("max_range", max_range, B::OpenLow(0.0, 0.5 * map_size), "m"));
  ROVER_RETURN_IF_ERROR(CheckPositive("new_panorama_distance", new_panorama_distance, "m"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("min_cell_points", min_cell_points, 1, 1000000));
  // The seven steps.
  ROVER_RETURN_IF_ERROR(CheckRange("max_fill_gap", max_fill_gap, 0.0, 2.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("min_fill_directions", min_fill_directions, 1, 4));
  ROVER_RETURN_IF_ERROR(CheckRange("height_sigma_k", height_sigma_k, 0.0, 10.0));
  ROVER_RETURN_IF_ERROR(
      CheckRange("normal_window", normal_window, 3.0 * cell_size - 1e-9, 2.0, "m"));
  const int window = 2 * normal_half_cells() + 1;
  ROVER_RETURN_IF_ERROR(CheckIntRange("min_fit_cells", min_fit_cells, 3, window * window));
  ROVER_RETURN_IF_ERROR(
      CheckRange("region_tolerance", region_tolerance, B::OpenLow(0.0, 90.0 * kDegree), "rad"));
  ROVER_RETURN_IF_ERROR(CheckRange("region_max_jump", region_max_jump, B::OpenLow(0.0, 2.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("max_slope", max_slope, B::OpenLow(0.0, 89.0 * kDegree), "rad"));
  ROVER_RETURN_IF_ERROR(CheckRange("min_steep_area", min_steep_area, 0.0, 100.0, "m^2"));
  ROVER_RETURN_IF_ERROR(CheckRange("step_baseline", step_baseline, cell_size, 2.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("min_missing_area", min_missing_area, 0.0, 100.0, "m^2"));
  ROVER_RETURN_IF_ERROR(CheckRange("hazard_border", hazard_border, 0.0, 2.0, "m"));
  // Planning grid.
  ROVER_RETURN_IF_ERROR(CheckRange("plan_length", plan_length, B::OpenLow(0.0, map_size), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("plan_width", plan_width, B::OpenLow(0.0, map_size), "m"));
  if (plan_width < 2.0 * turn_radius() + 2.0 * cell_size) {
    return InvalidArgument(Describe("plan_width", plan_width, "m") +
                           " leaves no room to turn: it must exceed twice the turn radius " +
                           FormatNumber(turn_radius()) + " m plus a cell on each side");
  }
  ROVER_RETURN_IF_ERROR(CheckRange("plan_back", plan_back, 0.0, plan_length, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("goal_margin", goal_margin, 0.0, 20.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("start_clear_radius", start_clear_radius, 0.0, 5.0, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("start_search_radius", start_search_radius, B::OpenLow(0.0, 10.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("min_progress", min_progress, 0.0, 10.0, "m"));
  // Road map.
  ROVER_RETURN_IF_ERROR(CheckRange("lookahead", lookahead, cell_size, 10.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("connect_radius", connect_radius, 0.0, 20.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("fit_tolerance", fit_tolerance, B::OpenLow(0.0, 5.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("fit_max_evaluations", fit_max_evaluations, 0, 100000));
  ROVER_RETURN_IF_ERROR(CheckRange("turn_cost", turn_cost, 0.0, 100.0, "m/rad"));
  // A*.
  ROVER_RETURN_IF_ERROR(CheckRange("clearance_weight", clearance_weight, 0.0, 100.0));
  ROVER_RETURN_IF_ERROR(CheckRange("clearance_ref", clearance_ref, B::OpenLow(0.0, 20.0), "m"));
  return Status::Ok();
}

void RoamanOptions::BindParams(ParamBinder<RoamanOptions>& b) {
  using O = RoamanOptions;
  // Rover geometry.
  b.Bind("rover_length_m", &O::rover_length, "m", "footprint length (wheelbase + 2 wheel radii)")
      .Range(0.1, 10.0);
  b.Bind("rover_width_m", &O::rover_width, "m", "footprint width (track + wheel width)")
      .Range(0.1, 10.0);
  b.Bind("body_clearance_m", &O::body_clearance, "m", "belly above flat ground").Range(0.01, 2.0);
  // Map memory.
  b.Bind("cell_size_m", &O::cell_size, "m", "map cell side (FIDO 5 cm)").Range(0.005, 0.5);
  b.Bind("map_size_m", &O::map_size, "m", "side of the site-frame map memory").Range(1.0, 200.0);
  b.Bind("recenter_distance_m", &O::recenter_distance, "m",
         "rover this far from the map centre: the map recentres")
      .Min(0.01);
  b.Bind("max_range_m", &O::max_range, "m", "points farther from the rover are unused (FIDO 12 m)")
      .Min(0.1);
  b.Bind("new_panorama_distance_m", &O::new_panorama_distance, "m",
         "rover moved this far since the last scan: a new panorama replaces older cells")
      .Min(0.001);
  b.Bind("min_cell_points", &O::min_cell_points, "", "points a cell needs for a height").Min(1);
  // The seven steps.
  b.Bind("max_fill_gap_m", &O::max_fill_gap, "m", "1: widest gap of missing cells interpolated")
      .Range(0.0, 2.0);
  b.Bind("min_fill_directions", &O::min_fill_directions, "",
         "1: line directions (of 4) that must bracket a hole cell")
      .Range(1, 4);
  b.Bind("height_sigma_k", &O::height_sigma_k, "", "2: cell top/bottom = mean +- k sigma")
      .Range(0.0, 10.0);
  b.Bind("normal_window_m", &O::normal_window, "m", "3: side of the plane-fit window")
      .Range(0.01, 2.0);
  b.Bind("min_fit_cells", &O::min_fit_cells, "", "3: cells with heights a plane fit needs").Min(3);
  b.BindDegrees("region_tolerance_deg", &O::region_tolerance,
                "4: normal angle to a region's mean normal that still joins it")
      .Range(0.1, 90.0);
  b.Bind("region_max_jump_m", &O::region_max_jump, "m", "4: height jump that ends a region")
      .Range(0.001, 2.0);
  b.BindDegrees("max_slope_deg", &O::max_slope, "5: steeper regions are hazards (FIDO 45)")
      .Range(1.0, 89.0);
  b.Bind("min_steep_area_m2", &O::min_steep_area, "m^2",
         "5: steep regions smaller than this are left to the step test")
      .Range(0.0, 100.0)
      .Field("min_steep_area");
  b.Bind("step_baseline_m", &O::step_baseline, "m",
         "5: a rise above the body clearance within this distance is a discontinuity")
      .Range(0.005, 2.0);
  b.Bind("min_missing_area_m2", &O::min_missing_area, "m^2",
         "5: regions of missing data smaller than this are no hazard (a wheel cannot hide there)")
      .Range(0.0, 100.0)
      .Field("min_missing_area");
  b.Bind("hazard_border_m", &O::hazard_border, "m", "6: border grown around hazards")
      .Range(0.0, 2.0);
  // Planning grid.
  b.BindEnum("algorithm", &O::algorithm,
             {{"roaman", Algorithm::kRoaman}, {"astar", Algorithm::kAStar}},
             "planner: FIDO's road map or the A* baseline");
  b.Bind("fallback", &O::fallback, "try the other algorithm before reporting every route blocked");
  b.Bind("plan_width_m", &O::plan_width, "m", "planning grid across the goal direction (FIDO 6)")
      .Range(0.5, 200.0);
  b.Bind("plan_length_m", &O::plan_length, "m", "planning grid toward the goal (FIDO 12)")
      .Range(0.5, 200.0);
  b.Bind("plan_back_m", &O::plan_back, "m", "planning rows behind the rover").Range(0.0, 200.0);
  b.Bind("goal_margin_m", &O::goal_margin, "m", "planning rows beyond a goal").Range(0.0, 20.0);
  b.Bind("start_clear_radius_m", &O::start_clear_radius, "m",
         "unknown or border cells this close to the rover count as safe")
      .Range(0.0, 5.0);
  b.Bind("start_search_radius_m", &O::start_search_radius, "m",
         "farthest turn-safe cell a first leg may reach")
      .Range(0.01, 10.0);
  b.Bind("min_progress_m", &O::min_progress, "m",
         "a partial plan must end this much nearer the goal")
      .Range(0.0, 10.0);
  // Road map.
  b.Bind("lookahead_m", &O::lookahead, "m", "rows ahead an axis cell connects to")
      .Range(0.005, 10.0);
  b.Bind("connect_radius_m", &O::connect_radius, "m",
         "axis cells the start and the goal connect to directly")
      .Range(0.0, 20.0);
  b.Bind("fit_tolerance_m", &O::fit_tolerance, "m", "path deviation before a waypoint is added")
      .Range(0.001, 5.0);
  b.Bind("fit_max_evaluations", &O::fit_max_evaluations, "",
         "NLopt evaluations of the least-squares waypoint fit")
      .Range(0, 100000);
  b.Bind("turn_cost_m_per_rad", &O::turn_cost, "m/rad", "plan cost of turning in place")
      .Range(0.0, 100.0)
      .Field("turn_cost");
  // A*.
  b.Bind("clearance_weight", &O::clearance_weight, "", "A* cost weight of low clearance")
      .Range(0.0, 100.0);
  b.Bind("clearance_ref_m", &O::clearance_ref, "m", "A* clearance that costs nothing extra")
      .Range(0.01, 20.0);
}

}  // namespace rover::apl::roaman
