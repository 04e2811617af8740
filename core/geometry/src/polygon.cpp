#include "rover/geometry/polygon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rover/base/check.hpp"

namespace rover::geometry {

bool SegmentsTouch(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  const double d1 = Cross2(b - a, c - a), d2 = Cross2(b - a, d - a);
  const double d3 = Cross2(d - c, a - c), d4 = Cross2(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
    return true;  // a proper crossing
  }
  // r lies on pq when it is collinear with it (cross product cr == 0) and inside its box.
  auto on = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r,
               double cr) {
    return cr == 0.0 && std::min(p.x(), q.x()) <= r.x() && r.x() <= std::max(p.x(), q.x()) &&
           std::min(p.y(), q.y()) <= r.y() && r.y() <= std::max(p.y(), q.y());
  };
  return on(a, b, c, d1) || on(a, b, d, d2) || on(c, d, a, d3) || on(c, d, b, d4);
}

double DistanceToSegment(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                         const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0.0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + t * ab - p).norm();
}

std::string WhyNotSimple(std::span<const Eigen::Vector2d> v) {
  const std::size_t n = v.size();
  ROVER_DEMAND(n >= 3);
  auto pair = [](const char* what, std::size_t i, std::size_t j, const char* verb) {
    return std::string(what) + " " + std::to_string(i) + " and " + std::to_string(j) + " " + verb;
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (v[i] == v[(i + 1) % n]) return pair("vertices", i, (i + 1) % n, "are equal");
  }
  for (std::size_t i = 0; i < n; ++i) {
    for (std::size_t j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      if (adjacent) {
        // Adjacent edges share one vertex; they must not fold back onto each other.
        const std::size_t shared = j == i + 1 ? j : i;
        const Eigen::Vector2d& a = v[(shared + n - 1) % n];
        const Eigen::Vector2d& o = v[shared];
        const Eigen::Vector2d& b = v[(shared + 1) % n];
        if (Cross2(a - o, b - o) == 0.0 && (a - o).dot(b - o) > 0.0) {
          return pair("edges", i, j, "overlap");
        }
      } else if (SegmentsTouch(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n])) {
        return pair("edges", i, j, "cross");
      }
    }
  }
  double area2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) area2 += Cross2(v[i], v[(i + 1) % n]);
  if (std::abs(area2) < 1e-9) return "the polygon has no area";
  return "";
}

bool InsidePolygon(std::span<const Eigen::Vector2d> poly, const Eigen::Vector2d& p) {
  bool inside = false;
  const std::size_t n = poly.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++) {
    const Eigen::Vector2d& a = poly[i];
    const Eigen::Vector2d& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) &&
        p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x()) {
      inside = !inside;
    }
  }
  return inside;
}

double DistanceToPolygon(std::span<const Eigen::Vector2d> poly, const Eigen::Vector2d& p) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    d = std::min(d, DistanceToSegment(poly[i], poly[(i + 1) % poly.size()], p));
  }
  return d;
}

}  // namespace rover::geometry
