#pragma once
/// @file
/// Geometry of MER's drive primitives as paths of the rover centre, and the goodness-map cells
/// each path sweeps.
///
/// Rover frame (x forward, y left); an arc of signed curvature k (positive = turning left when
/// driving forward) driven in direction d (+1 forward, -1 backward) for arc length s >= 0 ends at
///   x(s) = d sin(k s) / k,   y(s) = (1 - cos(k s)) / k,   heading change d k s
/// (x = d s, y = 0 as k -> 0): driving backward mirrors the forward path in x. The circle through
/// the rover and a goal (g_x, g_y) tangent to the heading has k* = 2 g_y / (g_x² + g_y²), the same
/// for both directions; it cannot be driven when |k*| exceeds the tightest curvature (the goal
/// lies inside a tightest turning circle).
///
/// A path's cells are the cells whose centre lies within `half_width` of the path (the exact
/// distance to the circle arc or segment, not a sampling of it). Since the goodness map is in
/// configuration space (a cell's goodness already covers the whole rover centred there), the
/// band only has to absorb the tracking error of the rover centre; half_width >= cell / sqrt(2)
/// guarantees every point of the path is on a path cell. A turn in place sweeps the cells within
/// half_width of the rover centre (its disc is the configuration-space cell itself).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

#include "rover/apl/nav_core/goodness_map.hpp"

namespace rover::apl::gestalt {

/// Position and heading in the site frame's x-y plane.
struct Pose2 {
  double x = 0.0, y = 0.0;  ///< [m]
  double yaw = 0.0;         ///< [rad] heading of the rover's x axis from site +x toward +y
};
/// The planar part of a 3-D pose: position x, y and the heading of the projected x axis.
Pose2 PlanarPose(const Eigen::Isometry3d& site_from_rover);

/// The rover-centre path of an arc between two arc lengths.
struct ArcPath {
  double curvature = 0.0;  ///< [1/m]
  int direction = 1;       ///< +1 forward, -1 backward
  double s_min = 0.0;      ///< [m] start of the evaluated part, >= 0
  double s_max = 0.0;      ///< [m] end, >= s_min (capped at one full circle)
};

/// [m] rover-frame position after arc length s.
Eigen::Vector2d ArcPoint(double curvature, int direction, double s);

struct ArcProjection {
  double distance = 0.0;  ///< [m] from the point to the nearest point of the path
  double s = 0.0;         ///< [m] arc length of that nearest point
};
/// The nearest point of `path` to rover-frame point p.
ArcProjection ProjectOntoArc(const ArcPath& path, const Eigen::Vector2d& p);

/// A cell on a path.
struct PathCell {
  int i = 0, j = 0;  ///< grid indices of the map (may lie outside it)
  double s = 0.0;    ///< [m] arc length of the nearest path point
};

/// The cells of `map`'s grid (geometry only; cells outside the grid included) within
/// `half_width` of `path` driven from `pose`. `cells` is cleared first; order is unspecified.
void SweptCells(const nav_core::GoodnessMap& map, const Pose2& pose, const ArcPath& path,
                double half_width, std::vector<PathCell>* cells);
/// The cells within `half_width` of the rover centre (s = 0).
void TurnCells(const nav_core::GoodnessMap& map, const Pose2& pose, double half_width,
               std::vector<PathCell>* cells);

}  // namespace rover::apl::gestalt
