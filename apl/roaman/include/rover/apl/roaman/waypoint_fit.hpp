#pragma once
/// @file
/// From a path to waypoints and legs (seed 004 §3.1: "a least squares fit is done to the
/// longest connected path in order to determine waypoints"; FIDO drives each leg as a turn in
/// place followed by a straight drive).
///
/// 1. SelectWaypoints: Douglas-Peucker over the path's vertices (the road-map nodes, all of
///    which the rover can turn on): a chord replaces the vertices between its ends when no point
///    of the path between them lies farther than fit_tolerance from it AND the rover can drive
///    it straight (every cell under it has half the footprint width of clearance); otherwise it
///    splits at the farthest vertex (at the middle one when only the drive test failed).
/// 2. FitWaypoints: the interior waypoints w_1 .. w_{M-1} (the ends stay fixed) move to
///    minimise the least-squares error of the path against the polyline,
///        E(w) = sum_k d(p_k, polyline(w))^2     (p_k: the path sampled every cell),
///    subject to: every leg w_i w_{i+1} a clear straight drive (min clearance under it >= half
///    the footprint width) and every interior waypoint a safe turn (clearance >= the turn
///    radius). NLopt's COBYLA (derivative-free, inequality constraints) does the minimisation
///    from the Douglas-Peucker waypoints, which satisfy the constraints; the best point that
///    satisfies them (checked exactly as the constraints are stated) is returned, so the fit
///    never makes a plan unsafe or worse than its start.
/// 3. MakeLegs: each pair of consecutive waypoints is one leg: turn in place to its heading,
///    drive straight its length.

#include <Eigen/Core>
#include <string>
#include <vector>

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

/// Step 1: indices into `vertices` of the waypoints kept (first and last always).
std::vector<int> SelectWaypoints(const PlanningGrid& grid, const std::vector<Eigen::Vector2d>& vertices,
                                 double tolerance, double leg_clearance);

/// E(w) for the polyline `waypoints` against `points`.
double FitError(const std::vector<Eigen::Vector2d>& points,
                const std::vector<Eigen::Vector2d>& waypoints);

/// The polyline's legs are clear straight drives and its interior vertices safe turns.
bool PolylineSafe(const PlanningGrid& grid, const std::vector<Eigen::Vector2d>& waypoints,
                  double turn_clearance, double leg_clearance);

struct FitResult {
  std::vector<Eigen::Vector2d> waypoints;
  double error_before = 0.0;  ///< [m^2] E at the start
  double error_after = 0.0;   ///< [m^2] E of the result
  int evaluations = 0;
  std::string outcome;  ///< NLopt's result, or why it did not run
};

/// Step 2. `initial` must satisfy PolylineSafe (then so does the result).
FitResult FitWaypoints(const PlanningGrid& grid, const std::vector<Eigen::Vector2d>& points,
                       const std::vector<Eigen::Vector2d>& initial, double turn_clearance,
                       double leg_clearance, int max_evaluations);

}  // namespace rover::apl::roaman
