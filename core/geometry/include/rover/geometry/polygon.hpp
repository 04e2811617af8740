#pragma once
/// @file
/// Planar polygons (keep-out zones, footprints) in any 2-D frame, units of the caller (m in the
/// site frame for keep-out zones). A polygon is its vertices in order, either winding; the edge
/// i runs from vertex i to vertex (i + 1) mod n.

#include <Eigen/Core>
#include <span>
#include <string>

namespace rover::geometry {

/// z of the cross product of a and b: > 0 when b is counter-clockwise of a.
inline double Cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// Whether the closed segments ab and cd share a point (touching ends and collinear overlaps
/// included).
bool SegmentsTouch(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d);

/// Distance from p to the closed segment ab (to a when a == b).
double DistanceToSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                         const Eigen::Vector2d& p);

/// Empty when the polygon (at least 3 finite vertices) is simple; otherwise why not, the first
/// of, in this order:
///   "vertices 2 and 3 are equal"       (consecutive vertices coincide)
///   "edges 0 and 1 overlap"            (adjacent edges fold back onto each other)
///   "edges 0 and 2 cross"              (non-adjacent edges touch)
///   "the polygon has no area"          (|signed area| < 1e-9 x unit^2)
/// Edge pairs are taken in order (0, 1), (0, 2), ... (1, 2), ...; collinear vertices show as
/// an overlap.
/// Preconditions: vertices.size() >= 3, all finite (the caller checks input first).
std::string WhyNotSimple(std::span<const Eigen::Vector2d> vertices);

/// Whether p is strictly inside the polygon (even-odd rule; points on an edge may go either way).
bool InsidePolygon(std::span<const Eigen::Vector2d> polygon, const Eigen::Vector2d& p);

/// Distance from p to the polygon's boundary (infinity for an empty polygon).
double DistanceToPolygon(std::span<const Eigen::Vector2d> polygon, const Eigen::Vector2d& p);

}  // namespace rover::geometry
