#include "rover/apl/mobility/motion_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::apl::mobility {
namespace {

constexpr double kPi = 3.14159265358979323846;

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Whether segments ab and cd share a point (collinear overlaps included).
bool SegmentsTouch(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d) {
  const double d1 = Cross(b - a, c - a), d2 = Cross(b - a, d - a);
  const double d3 = Cross(d - c, a - c), d4 = Cross(d - c, b - c);
  if (((d1 > 0 && d2 < 0) || (d1 < 0 && d2 > 0)) && ((d3 > 0 && d4 < 0) || (d3 < 0 && d4 > 0))) {
    return true;
  }
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

}  // namespace

Pose2 PlanarPose(const Eigen::Isometry3d& site_from_rover) {
  const Eigen::Matrix3d r = site_from_rover.linear();
  return {site_from_rover.translation().x(), site_from_rover.translation().y(),
          std::atan2(r(1, 0), r(0, 0))};
}

double WrapAngle(double a) {
  a = std::remainder(a, 2.0 * kPi);
  return a <= -kPi ? a + 2.0 * kPi : a;
}

double PathLength(const Primitive& p) {
  return (p.kind == PrimitiveKind::kArc || p.kind == PrimitiveKind::kStraight)
             ? std::abs(p.distance)
             : 0.0;
}

Pose2 Propagate(const Pose2& start, const Primitive& p) {
  if (p.kind == PrimitiveKind::kTurnInPlace) {
    return {start.x, start.y, WrapAngle(start.heading + p.angle)};
  }
  if (p.kind != PrimitiveKind::kArc && p.kind != PrimitiveKind::kStraight) return start;
  const double k = p.kind == PrimitiveKind::kArc ? p.curvature : 0.0;
  const double s = p.distance;
  double dx = s, dy = 0.0;
  if (std::abs(k) > 1e-9) {
    dx = std::sin(k * s) / k;
    dy = (1.0 - std::cos(k * s)) / k;
  }
  const double c = std::cos(start.heading), sn = std::sin(start.heading);
  return {start.x + c * dx - sn * dy, start.y + sn * dx + c * dy, WrapAngle(start.heading + k * s)};
}

std::vector<Eigen::Vector2d> SweptCentre(const Pose2& start, const Primitive& p, double spacing) {
  std::vector<Eigen::Vector2d> pts{start.xy()};
  const double len = PathLength(p);
  if (len <= 0.0 || spacing <= 0.0) return pts;
  const int n = std::max(1, static_cast<int>(std::ceil(len / spacing)));
  for (int i = 1; i <= n; ++i) {
    Primitive part = p;
    part.distance = p.distance * static_cast<double>(i) / n;
    pts.push_back(Propagate(start, part).xy());
  }
  return pts;
}

Status CheckSimplePolygon(const std::string& field, const KeepOutZone& zone) {
  const std::string name = field + " ('" + zone.name + "').vertices";
  const auto& v = zone.vertices;
  const int n = static_cast<int>(v.size());
  if (n < 3 || n > 16) {
    return InvalidArgument(name + ": " + std::to_string(n) + " vertices (need 3..16)");
  }
  for (int i = 0; i < n; ++i) {
    ROVER_RETURN_IF_ERROR(CheckFinite(name + "[" + std::to_string(i) + "].x", v[i].x()));
    ROVER_RETURN_IF_ERROR(CheckFinite(name + "[" + std::to_string(i) + "].y", v[i].y()));
  }
  for (int i = 0; i < n; ++i) {
    if (v[i] == v[(i + 1) % n]) {
      return InvalidArgument(name + ": vertices " + std::to_string(i) + " and " +
                             std::to_string((i + 1) % n) +
                             " are equal (the polygon is not simple)");
    }
  }
  double area2 = 0.0;
  for (int i = 0; i < n; ++i) area2 += Cross(v[i], v[(i + 1) % n]);
  if (std::abs(area2) < 1e-9) {
    return InvalidArgument(name + ": area is " + FormatNumber(0.5 * std::abs(area2)) +
                           " m^2 (the polygon is degenerate)");
  }
  for (int i = 0; i < n; ++i) {
    for (int j = i + 1; j < n; ++j) {
      const bool adjacent = j == i + 1 || (i == 0 && j == n - 1);
      if (adjacent) {
        // Adjacent edges share one vertex; they must not fold back onto each other.
        const int shared = j == i + 1 ? j : i;
        const Eigen::Vector2d& a = v[(shared + n - 1) % n];
        const Eigen::Vector2d& o = v[shared];
        const Eigen::Vector2d& b = v[(shared + 1) % n];
        if (Cross(a - o, b - o) == 0.0 && (a - o).dot(b - o) > 0.0) {
          return InvalidArgument(name + ": edges " + std::to_string(i) + " and " +
                                 std::to_string(j) + " overlap (the polygon is not simple)");
        }
        continue;
      }
      if (SegmentsTouch(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n])) {
        return InvalidArgument(name + ": edges " + std::to_string(i) + " and " + std::to_string(j) +
                               " cross (the polygon is not simple)");
      }
    }
  }
  return Status::Ok();
}

bool InsidePolygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
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

double DistanceToPolygon(const std::vector<Eigen::Vector2d>& poly, const Eigen::Vector2d& p) {
  double d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < poly.size(); ++i) {
    d = std::min(d, DistanceToSegment(poly[i], poly[(i + 1) % poly.size()], p));
  }
  return d;
}

KeepOutHit FirstKeepOutHit(const std::vector<Eigen::Vector2d>& points,
                           const std::vector<KeepOutZone>& zones, double margin) {
  for (std::size_t k = 0; k < points.size(); ++k) {
    for (std::size_t z = 0; z < zones.size(); ++z) {
      const auto& poly = zones[z].vertices;
      if (poly.size() < 3) continue;
      if (InsidePolygon(poly, points[k]) || DistanceToPolygon(poly, points[k]) < margin) {
        return {static_cast<int>(k), static_cast<int>(z)};
      }
    }
  }
  return {};
}

double MarsLocalMeanSolarTimeHours(double unix_s, double longitude_east) {
  const double jd_tt = unix_s / 86400.0 + 2440587.5 + 69.184 / 86400.0;
  const double msd = (jd_tt - 2405522.0028779) / 1.0274912517;
  const double mst = 24.0 * (msd - std::floor(msd));
  const double lmst = mst + longitude_east * 180.0 / kPi / 15.0;
  return lmst - 24.0 * std::floor(lmst / 24.0);
}

}  // namespace rover::apl::mobility
