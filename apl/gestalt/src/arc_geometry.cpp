#include "rover/apl/gestalt/arc_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rover::apl::gestalt {
namespace {

constexpr double kStraight = 1e-9;  // |k| below this is a straight line
constexpr double kTwoPi = 2.0 * std::numbers::pi;

double CappedEnd(const ArcPath& p) {
  const double k = std::abs(p.curvature);
  return k < kStraight ? p.s_max : std::min(p.s_max, kTwoPi / k);
}

// Rover-frame point -> site and back.
Eigen::Vector2d ToSite(const Pose2& pose, const Eigen::Vector2d& p) {
  const double c = std::cos(pose.yaw), s = std::sin(pose.yaw);
  return {pose.x + c * p.x() - s * p.y(), pose.y + s * p.x() + c * p.y()};
}
Eigen::Vector2d ToRover(const Pose2& pose, const Eigen::Vector2d& q) {
  const double c = std::cos(pose.yaw), s = std::sin(pose.yaw);
  const double dx = q.x() - pose.x, dy = q.y() - pose.y;
  return {c * dx + s * dy, -s * dx + c * dy};
}

}  // namespace

Pose2 PlanarPose(const Eigen::Isometry3d& site_from_rover) {
  const Eigen::Matrix3d& r = site_from_rover.linear();
  return {site_from_rover.translation().x(), site_from_rover.translation().y(),
          std::atan2(r(1, 0), r(0, 0))};
}

Eigen::Vector2d ArcPoint(double curvature, int direction, double s) {
  const double d = direction < 0 ? -1.0 : 1.0;
  if (std::abs(curvature) < kStraight) return {d * s, 0.0};
  const double a = curvature * s;
  return {d * std::sin(a) / curvature, (1.0 - std::cos(a)) / curvature};
}

ArcProjection ProjectOntoArc(const ArcPath& path, const Eigen::Vector2d& p) {
  // Canonical form: forward (mirror x for backward) and turning left (mirror y for k < 0).
  const double k = std::abs(path.curvature);
  const Eigen::Vector2d q(path.direction < 0 ? -p.x() : p.x(), path.curvature < 0 ? -p.y() : p.y());
  const double s0 = path.s_min, s1 = CappedEnd(path);
  ArcProjection out;
  if (k < kStraight) {
    out.s = std::clamp(q.x(), s0, s1);
    out.distance = std::hypot(q.x() - out.s, q.y());
    return out;
  }
  // Circle centre (0, R); the point at arc length s is (R sin(k s), R - R cos(k s)).
  const double radius = 1.0 / k;
  const Eigen::Vector2d v(q.x(), q.y() - radius);
  double phi = std::atan2(v.x(), -v.y());  // 0 at the start, increasing along the path
  if (phi < 0.0) phi += kTwoPi;
  const double s_q = phi / k;
  if (s_q >= s0 && s_q <= s1) {
    out.s = s_q;
    out.distance = std::abs(v.norm() - radius);
    return out;
  }
  auto end_point = [&](double s) {
    return Eigen::Vector2d(radius * std::sin(k * s), radius * (1.0 - std::cos(k * s)));
  };
  const double d0 = (q - end_point(s0)).norm(), d1 = (q - end_point(s1)).norm();
  out.s = d0 <= d1 ? s0 : s1;
  out.distance = std::min(d0, d1);
  return out;
}

void SweptCells(const nav_core::GoodnessMap& map, const Pose2& pose, const ArcPath& path,
                double half_width, std::vector<PathCell>* cells) {
  cells->clear();
  const double r = map.resolution;
  const double s1 = CappedEnd(path);
  const double ds = 0.25 * r;
  const int steps = std::max(1, static_cast<int>(std::ceil((s1 - path.s_min) / ds)));
  // Sample cells, then every cell within `margin` of a sample is a candidate.
  std::vector<Eigen::Vector2i> sample_cells;
  sample_cells.reserve(static_cast<std::size_t>(steps + 1));
  int lo_i = 1 << 30, lo_j = 1 << 30, hi_i = -(1 << 30), hi_j = -(1 << 30);
  for (int n = 0; n <= steps; ++n) {
    const double s = std::min(s1, path.s_min + n * ds);
    const Eigen::Vector2d q = ToSite(pose, ArcPoint(path.curvature, path.direction, s));
    int i = 0, j = 0;
    map.CellOf(q.x(), q.y(), &i, &j);
    sample_cells.emplace_back(i, j);
    lo_i = std::min(lo_i, i);
    hi_i = std::max(hi_i, i);
    lo_j = std::min(lo_j, j);
    hi_j = std::max(hi_j, j);
  }
  const int margin = static_cast<int>(std::ceil((half_width + 0.5 * ds) / r + 0.5));
  lo_i -= margin;
  lo_j -= margin;
  hi_i += margin;
  hi_j += margin;
  const int w = hi_i - lo_i + 1, h = hi_j - lo_j + 1;
  std::vector<std::uint8_t> seen(static_cast<std::size_t>(w) * h, 0);
  for (const Eigen::Vector2i& sc : sample_cells) {
    for (int j = sc.y() - margin; j <= sc.y() + margin; ++j) {
      for (int i = sc.x() - margin; i <= sc.x() + margin; ++i) {
        std::uint8_t& mark = seen[static_cast<std::size_t>(j - lo_j) * w + (i - lo_i)];
        if (mark != 0) continue;
        mark = 1;
        const ArcProjection pr = ProjectOntoArc(path, ToRover(pose, map.CellCenter(i, j)));
        if (pr.distance <= half_width) cells->push_back({i, j, pr.s});
      }
    }
  }
}

void TurnCells(const nav_core::GoodnessMap& map, const Pose2& pose, double half_width,
               std::vector<PathCell>* cells) {
  cells->clear();
  int ci = 0, cj = 0;
  map.CellOf(pose.x, pose.y, &ci, &cj);
  const int m = static_cast<int>(std::ceil(half_width / map.resolution)) + 1;
  for (int j = cj - m; j <= cj + m; ++j) {
    for (int i = ci - m; i <= ci + m; ++i) {
      const Eigen::Vector2d c = map.CellCenter(i, j);
      if (std::hypot(c.x() - pose.x, c.y() - pose.y) <= half_width) cells->push_back({i, j, 0.0});
    }
  }
}

}  // namespace rover::apl::gestalt
