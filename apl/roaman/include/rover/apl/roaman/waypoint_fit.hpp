#pragma once
/// @file
/// From a path to waypoints and legs (seed 004 §3.1: "a least squares fit is done to the
/// longest connected path in order to determine waypoints"; FIDO drives each leg as a turn in
/// place followed by a straight drive).
///
/// Turn safety: at an interior waypoint the rover turns in place by the angle between the legs
/// before and after it; that needs Footprint::TurnClearance(angle) of clearance there (W/2 for
/// no turn, the turn radius for 30° or more at the sim rover's size).
///
/// 1. SelectWaypoints: Douglas-Peucker over the path's vertices (whose turns the road map made
///    safe): a chord replaces the vertices between its ends when no point of the path between
///    them lies farther than fit_tolerance from it AND the rover can drive it straight (every
///    cell under it has half the footprint width of clearance); otherwise it splits at the
///    farthest vertex (at the middle one when only the drive test failed). A kept waypoint whose
///    (now sharper) turn is not safe gets back the path's vertices on either side of it, until
///    every turn is safe (the whole path is).
/// 2. FitWaypoints: the interior waypoints w_1 .. w_{M-1} (the ends stay fixed) move to
///    minimise the least-squares error of the path against the polyline,
///        E(w) = sum_k d(p_k, polyline(w))^2     (p_k: the path sampled every cell),
///    subject to: every leg w_i w_{i+1} a clear straight drive (min clearance under it >= half
///    the footprint width) and every interior waypoint a safe turn (clearance >=
///    TurnClearance of its turn). NLopt's COBYLA (derivative-free, inequality constraints) does the
///    minimisation from the Douglas-Peucker waypoints, which satisfy the constraints; the best
///    point that satisfies them (checked exactly as the constraints are stated) is returned, so the
///    fit never makes a plan unsafe or worse than its start.
/// 3. MakeLegs: each pair of consecutive waypoints is one leg: turn in place to its heading,
///    drive straight its length.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "rover/apl/roaman/options.hpp"
#include "rover/apl/roaman/planning_grid.hpp"

namespace rover::apl::roaman {

struct Leg {
  Eigen::Vector2d from = Eigen::Vector2d::Zero();  ///< [m] site
  Eigen::Vector2d to = Eigen::Vector2d::Zero();    ///< [m] site
  double heading = 0.0;  ///< [rad] site yaw of the drive (0 = +x north, pi/2 = +y west)
  /// [rad] turn in place before the drive, from the previous leg's heading, in (-pi, pi]; 0 for
  /// the first leg (its turn depends on the rover's heading, which a plan does not know).
  double turn = 0.0;
  double length = 0.0;  ///< [m]
};

/// Legs through `waypoints` (site, in driving order).
std::vector<Leg> MakeLegs(const std::vector<Eigen::Vector2d>& waypoints);

/// `vertices` sampled every `step` metres along each segment (each vertex included once), and
/// in *vertex_index the index of every vertex in the result.
std::vector<Eigen::Vector2d> SamplePath(const std::vector<Eigen::Vector2d>& vertices, double step,
                                        std::vector<int>* vertex_index);

/// [rad] signed turn at b from the direction a->b to b->c, in (-pi, pi].
double TurnAngle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c);
/// The turn at b (arriving from a, leaving for c) is safe on the grid.
bool TurnSafe(const PlanningGrid& grid, const Footprint& footprint, const Eigen::Vector2d& a,
              const Eigen::Vector2d& b, const Eigen::Vector2d& c);

/// Step 1: indices into `vertices` of the waypoints kept (first and last always).
std::vector<int> SelectWaypoints(const PlanningGrid& grid,
                                 const std::vector<Eigen::Vector2d>& vertices, double tolerance,
                                 const Footprint& footprint);

/// E(w) for the polyline `waypoints` against `points`.
double FitError(const std::vector<Eigen::Vector2d>& points,
                const std::vector<Eigen::Vector2d>& waypoints);

/// The polyline's legs are clear straight drives and its interior vertices safe turns.
bool PolylineSafe(const PlanningGrid& grid, const std::vector<Eigen::Vector2d>& waypoints,
                  const Footprint& footprint);

struct FitResult {
  std::vector<Eigen::Vector2d> waypoints;
  double error_before = 0.0;  ///< [m^2] E at the start
  double error_after = 0.0;   ///< [m^2] E of the result
  int evaluations = 0;
  std::string outcome;  ///< NLopt's result, or why it did not run
};

/// Step 2. `initial` must satisfy PolylineSafe (then so does the result).
FitResult FitWaypoints(const PlanningGrid& grid, const std::vector<Eigen::Vector2d>& points,
                       const std::vector<Eigen::Vector2d>& initial, const Footprint& footprint,
                       int max_evaluations);

}  // namespace rover::apl::roaman
