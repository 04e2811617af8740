#include "reference_gestalt.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "rover/apl/gestalt/arc_evaluator.hpp"
#include "rover/apl/gestalt/arc_geometry.hpp"

namespace rover::apl::gestalt::testing {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

bool InDisc(int dx, int dy, double r) { return dx * dx + dy * dy <= r * r + 1e-9; }

std::uint8_t Byte(int v) { return static_cast<std::uint8_t>(std::clamp(v, 0, 255)); }

}  // namespace

ReferenceResult ReferenceAssess(const GestaltOptions& o, const nav_core::RangeScan& scan) {
  const int n = o.grid_cells();
  const double r = o.cell_size;
  const Eigen::Vector2d rover = scan.site_from_rover.translation().head<2>();
  const int i0 = static_cast<int>(std::floor(rover.x() / r)) - n / 2;
  const int j0 = static_cast<int>(std::floor(rover.y() / r)) - n / 2;
  // Points per cell (site frame relative to the rover, as TerrainMap's first update).
  const Eigen::Vector3d origin = scan.site_from_rover.translation();
  Grid<std::vector<Eigen::Vector3d>> points(n, n);
  for (std::size_t k = 0; k < scan.pixel_count(); ++k) {
    if (scan.valid[k] == 0) continue;
    const Eigen::Vector3d pr(scan.xyz[3 * k], scan.xyz[3 * k + 1], scan.xyz[3 * k + 2]);
    if (!pr.allFinite()) continue;
    const Eigen::Vector3d p = scan.site_from_rover * pr;
    if ((p.head<2>() - rover).norm() > o.max_point_distance) continue;
    const int i = static_cast<int>(std::floor(p.x() / r)) - i0;
    const int j = static_cast<int>(std::floor(p.y() / r)) - j0;
    if (!points.Contains(i, j)) continue;
    points.at(i, j).push_back(p - origin);
  }
  // Cell statistics from the raw points.
  Grid<CellStats> stats(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const auto& pts = points.at(i, j);
      if (static_cast<int>(pts.size()) < o.min_cell_points || pts.empty()) continue;
      Eigen::Vector3d m = Eigen::Vector3d::Zero();
      for (const auto& p : pts) m += p;
      m /= static_cast<double>(pts.size());
      CellStats& s = stats.at(i, j);
      s.covered = true;
      s.x = m.x();
      s.y = m.y();
      s.z = m.z();
    }
  }
  const double R = o.rover_disc_radius_cells();
  const double rb = o.step_disc_radius_cells();
  const int Ri = static_cast<int>(std::floor(R + 1e-9));
  const int rbi = static_cast<int>(std::floor(rb + 1e-9));
  int disc_cells = 0;
  for (int dy = -Ri; dy <= Ri; ++dy) {
    for (int dx = -Ri; dx <= Ri; ++dx) disc_cells += InDisc(dx, dy, R) ? 1 : 0;
  }
  ReferenceResult out;
  out.assessments = Grid<CellAssessment>(n, n);
  Grid<std::int16_t> goodness(n, n, -1);
  std::vector<Eigen::Vector3d> disc_points;
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      disc_points.clear();
      int covered = 0;
      for (int dy = -Ri; dy <= Ri; ++dy) {
        for (int dx = -Ri; dx <= Ri; ++dx) {
          if (!InDisc(dx, dy, R) || !points.Contains(i + dx, j + dy)) continue;
          const auto& pts = points.at(i + dx, j + dy);
          disc_points.insert(disc_points.end(), pts.begin(), pts.end());
          covered += stats.at(i + dx, j + dy).covered ? 1 : 0;
        }
      }
      CellAssessment& a = out.assessments.at(i, j);
      a.coverage = static_cast<float>(static_cast<double>(covered) / disc_cells);
      if (a.coverage < o.min_coverage || disc_points.size() < 3) continue;
      Eigen::Vector3d m = Eigen::Vector3d::Zero();
      for (const auto& p : disc_points) m += p;
      m /= static_cast<double>(disc_points.size());
      Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
      for (const auto& p : disc_points) cov += (p - m) * (p - m).transpose();
      cov /= static_cast<double>(disc_points.size());
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(cov);
      Eigen::Vector3d normal = es.eigenvectors().col(0).normalized();
      if (normal.z() < 0.0) normal = -normal;
      const double l0 = std::max(0.0, es.eigenvalues()[0]);
      const double l1 = std::max(0.0, es.eigenvalues()[1]);
      const double residual = std::sqrt(l0);
      const double tilt = std::acos(std::clamp(normal.z(), -1.0, 1.0));
      a.tilt = static_cast<float>(tilt);
      a.roughness = static_cast<float>(residual);
      if (l1 < o.eigen_ratio * l0) {
        if (residual < o.max_roughness) continue;
        a.status = AssessStatus::kNotPlanar;
        goodness.at(i, j) = 0;
        continue;
      }
      a.status = AssessStatus::kAssessed;
      // Step: every belly disc centred in the rover disc, every covered cell inside both.
      double step = 0.0;
      if (normal.z() > 1e-3) {
        auto plane_z = [&](double x, double y) {
          return m.z() - (normal.x() * (x - m.x()) + normal.y() * (y - m.y())) / normal.z();
        };
        // Each cell's spread of heights above the plane, straight from its points.
        const double gb = -normal.x() / normal.z(), gc = -normal.y() / normal.z();
        auto spread = [&](int ci, int cj) {
          const auto& pts = points.at(ci, cj);
          double mean = 0.0;
          for (const auto& p : pts) mean += p.z() - gb * p.x() - gc * p.y();
          mean /= static_cast<double>(pts.size());
          double var = 0.0;
          for (const auto& p : pts) {
            const double h = p.z() - gb * p.x() - gc * p.y() - mean;
            var += h * h;
          }
          return std::sqrt(var / static_cast<double>(pts.size()));
        };
        for (int sy = -Ri; sy <= Ri; ++sy) {
          for (int sx = -Ri; sx <= Ri; ++sx) {
            if (!InDisc(sx, sy, R)) continue;
            double hi = -kInf, lo = kInf;
            for (int dy = -rbi; dy <= rbi; ++dy) {
              for (int dx = -rbi; dx <= rbi; ++dx) {
                const int cx = sx + dx, cy = sy + dy;
                if (!InDisc(dx, dy, rb) || !InDisc(cx, cy, R)) continue;
                if (!stats.Contains(i + cx, j + cy)) continue;
                const CellStats& c = stats.at(i + cx, j + cy);
                if (!c.covered) continue;
                const double e = c.z - plane_z(c.x, c.y);
                hi = std::max(hi, e + o.step_sigma_k * spread(i + cx, j + cy));
                lo = std::min(lo, e);
              }
            }
            if (hi > -kInf) step = std::max(step, hi - lo);
          }
        }
      } else {
        step = kInf;
      }
      a.step = static_cast<float>(std::min(step, 1e3));
      const int gt = RampGoodness(tilt, o.tilt_safe, o.max_tilt);
      const int gr = RampGoodness(residual, o.roughness_safe, o.max_roughness);
      const int gs = RampGoodness(step, o.step_safe, o.max_step);
      a.tilt_goodness = Byte(gt);
      a.roughness_goodness = Byte(gr);
      a.step_goodness = Byte(gs);
      a.goodness = Byte(std::min({gt, gr, gs}));
      goodness.at(i, j) = a.goodness;
    }
  }
  // Publish as TerrainMap does: unknown, border, known.
  nav_core::GoodnessMap& map = out.map;
  map.origin_x = i0 * r;
  map.origin_y = j0 * r;
  map.resolution = r;
  map.width = map.height = n;
  map.unknown_goodness = o.unknown_goodness;
  map.unknown_certainty = o.unknown_certainty;
  map.goodness.assign(map.cell_count(), 0);
  map.certainty.assign(map.cell_count(), 0);
  map.flags.assign(map.cell_count(), 0);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const std::size_t k = map.Index(i, j);
      if (goodness.at(i, j) < 0) {
        map.goodness[k] = Byte(o.unknown_goodness);
        map.certainty[k] = Byte(o.unknown_certainty);
        continue;
      }
      bool border = false;
      for (int dj = -1; dj <= 1; ++dj) {
        for (int di = -1; di <= 1; ++di) {
          if (!goodness.Contains(i + di, j + dj) || goodness.at(i + di, j + dj) < 0) border = true;
        }
      }
      map.goodness[k] =
          Byte(border ? std::min<int>(goodness.at(i, j), o.border_goodness) : goodness.at(i, j));
      map.certainty[k] = Byte(border ? o.border_certainty : 255);
      map.flags[k] =
          static_cast<std::uint8_t>(nav_core::kCellKnown | (border ? nav_core::kCellBorder : 0));
    }
  }
  return out;
}

nav_core::ArcEvaluation ReferenceEvaluate(const GestaltOptions& o, const nav_core::GoodnessMap& map,
                                          const nav_core::ArcRequest& request) {
  using nav_core::MotionKind;
  auto evaluator = ArcEvaluator::Create(o);
  ROVER_DEMAND(evaluator.ok());
  nav_core::ArcEvaluation e;
  e.candidates = evaluator->candidates();
  const std::size_t nc = e.candidates.size();
  e.hazard.resize(nc);
  e.waypoint.resize(nc);
  e.merged.resize(nc);
  const Pose2 pose = PlanarPose(request.site_from_rover);
  const double c = std::cos(pose.yaw), s = std::sin(pose.yaw);
  const double dx = request.goal.x() - pose.x, dy = request.goal.y() - pose.y;
  const double gx = c * dx + s * dy, gy = -s * dx + c * dy;
  e.distance_to_goal = std::hypot(gx, gy);
  if (e.distance_to_goal <= request.goal_tolerance) {
    e.mode = nav_core::GoalMode::kReached;
    return e;
  }
  const double k_goal = 2.0 * gy / (gx * gx + gy * gy);
  const double bearing = std::atan2(gy, gx);
  const bool backup = std::abs(k_goal) > o.max_curvature;
  e.mode = backup ? nav_core::GoalMode::kBackUp : nav_core::GoalMode::kNormal;
  const double length =
      std::clamp(e.distance_to_goal, o.plan_min_dist + o.cell_size, o.plan_max_dist);
  for (std::size_t k = 0; k < nc; ++k) {
    nav_core::Candidate& cand = e.candidates[k];
    // Hazard: test every cell of the map.
    double sw = 0.0, sg = 0.0, scert = 0.0;
    bool forbidden = false;
    ArcPath path{cand.curvature, cand.direction, o.plan_min_dist, length};
    if (cand.kind == MotionKind::kArc) cand.length = length;
    for (int j = 0; j < map.height; ++j) {
      for (int i = 0; i < map.width; ++i) {
        const Eigen::Vector2d q = map.CellCenter(i, j);
        const double qx = q.x() - pose.x, qy = q.y() - pose.y;
        const Eigen::Vector2d p(c * qx + s * qy, -s * qx + c * qy);
        double dist = 0.0, at_s = 0.0;
        if (cand.kind == MotionKind::kArc) {
          const ArcProjection pr = ProjectOntoArc(path, p);
          dist = pr.distance;
          at_s = pr.s;
        } else {
          dist = p.norm();
        }
        if (dist > o.path_half_width) continue;
        const nav_core::CellValue v = map.At(i, j);
        forbidden = forbidden || v.goodness < o.min_allowed_goodness;
        const double w = 1.0 + (o.near_weight - 1.0) * std::max(0.0, 1.0 - at_s / o.plan_max_dist);
        sw += w;
        sg += w * v.goodness;
        scert += w * v.certainty;
      }
    }
    e.hazard[k] = forbidden ? nav_core::Vote{0, 255}
                            : nav_core::Vote{static_cast<int>(std::lround(sg / sw)),
                                             static_cast<int>(std::lround(scert / sw))};
    // Waypoint.
    double peak = 0.0, expo = 0.0;
    if (cand.kind == MotionKind::kArc) {
      double centre = k_goal;
      if (backup) {
        centre = cand.direction < 0 ? -std::copysign(o.max_curvature, gy)
                                    : std::clamp(k_goal, -o.max_curvature, o.max_curvature);
        peak = o.backup_vote_scale *
               (cand.direction < 0 ? o.waypoint_peak_toward : o.waypoint_peak_away);
      } else {
        peak =
            cand.direction == (gx >= 0.0 ? 1 : -1) ? o.waypoint_peak_toward : o.waypoint_peak_away;
      }
      expo = (cand.curvature - centre) * (cand.curvature - centre) / (2.0 * o.arc_vote_variance);
    } else {
      peak = backup ? o.waypoint_peak_toward : o.waypoint_peak_away;
      double da =
          std::fmod(cand.turn_angle - bearing + 3.0 * std::numbers::pi, 2.0 * std::numbers::pi) -
          std::numbers::pi;
      expo = da * da / (2.0 * o.turn_vote_variance);
    }
    e.waypoint[k] = {static_cast<int>(std::lround(peak * std::exp(-expo))), o.waypoint_certainty};
    e.merged[k] = MergeVotes(e.hazard[k], e.waypoint[k], o.min_vote_goodness);
  }
  e.chosen = ChooseCandidate(e.merged, evaluator->groups());
  return e;
}

}  // namespace rover::apl::gestalt::testing
