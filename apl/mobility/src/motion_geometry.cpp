#include "rover/apl/mobility/motion_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rover/base/range_check.hpp"
#include "rover/base/units.hpp"
#include "rover/geometry/polygon.hpp"

namespace rover::apl::mobility {

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
  if (const std::string why = geometry::WhyNotSimple(v); !why.empty()) {
    return InvalidArgument(name + ": " + why + " (the polygon is not simple)");
  }
  return Status::Ok();
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
