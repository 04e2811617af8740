#pragma once
/// @file
/// Planar poses in the site frame's x-y plane (x north, y west; heading counter-clockwise from
/// +x seen from above, radians; metres), and the rover's motion primitives in that plane: an arc
/// of constant curvature (positive = centre of the turn on the left, heading grows when driving
/// forward; 0 = straight) and a turn in place. Header-only.

#include <Eigen/Geometry>
#include <cmath>

#include "rover/geometry/transforms.hpp"

namespace rover::geometry {

struct Pose2 {
  double x = 0.0;        ///< [m]
  double y = 0.0;        ///< [m]
  double heading = 0.0;  ///< [rad]
  Eigen::Vector2d xy() const { return {x, y}; }
  /// A rover-frame plan-view point (x forward, y left) in the site frame.
  Eigen::Vector2d ToSite(const Eigen::Vector2d& p) const {
    const double c = std::cos(heading), s = std::sin(heading);
    return {x + c * p.x() - s * p.y(), y + s * p.x() + c * p.y()};
  }
  /// A site-frame plan-view point in the rover frame (x forward, y left): ToSite's inverse.
  Eigen::Vector2d ToRover(const Eigen::Vector2d& p) const {
    const double c = std::cos(heading), s = std::sin(heading);
    const double dx = p.x() - x, dy = p.y() - y;
    return {c * dx + s * dy, -s * dx + c * dy};
  }
};

/// Position x, y of a 3-D pose and the heading of its projected x axis.
inline Pose2 ToPose2(const Eigen::Isometry3d& site_from_rover) {
  const Eigen::Vector3d fwd = site_from_rover.linear().col(0);
  return {site_from_rover.translation().x(), site_from_rover.translation().y(),
          std::atan2(fwd.y(), fwd.x())};
}

/// The pose after driving arc length `s` (negative = backward) on curvature `k` from `start`.
inline Pose2 AlongArc(const Pose2& start, double k, double s) {
  Pose2 p = start;
  if (std::abs(k) < 1e-9) {
    p.x += s * std::cos(start.heading);
    p.y += s * std::sin(start.heading);
    return p;
  }
  const double dh = k * s;
  p.x += (std::sin(start.heading + dh) - std::sin(start.heading)) / k;
  p.y += (std::cos(start.heading) - std::cos(start.heading + dh)) / k;
  p.heading = WrapAngle(start.heading + dh);
  return p;
}

/// The pose after turning in place by `angle` (counter-clockwise positive).
inline Pose2 Turned(const Pose2& start, double angle) {
  Pose2 p = start;
  p.heading = WrapAngle(start.heading + angle);
  return p;
}

}  // namespace rover::geometry
