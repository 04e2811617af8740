#include "rover/deploy/runner/autonav_judging.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "rover/geometry/polygon.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::deploy::runner {
namespace {

constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

// Horizontal distance from `p` to the nearest track point (track points are 0.2 s
// apart, a few centimetres at rover speeds).
double NearestTrackDistance(const Track& track, const Eigen::Vector2d& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& q : track) best = std::min(best, std::hypot(q[1] - p.x(), q[2] - p.y()));
  return best;
}

Eigen::Vector2d CellCentre(const GoodnessGrid& m, int i, int j) {
  return {m.origin_x + (i + 0.5) * m.resolution, m.origin_y + (j + 0.5) * m.resolution};
}

bool Marked(const GoodnessGrid& m, int i, int j, int obstacle_goodness) {
  if (!m.Known(i, j)) return false;
  const std::size_t k = static_cast<std::size_t>(j) * static_cast<std::size_t>(m.width) +
                        static_cast<std::size_t>(i);
  return k < m.goodness.size() && m.goodness[k] <= obstacle_goodness;
}

std::string Count(const char* what, int a, int b) {
  char buf[128];
  std::snprintf(buf, sizeof buf, what, a, b);
  return buf;
}

}  // namespace

int KeepOutEntries(const Track& track, const std::vector<std::vector<Eigen::Vector2d>>& zones,
                   double margin) {
  int n = 0;
  for (const auto& q : track) {
    const Eigen::Vector2d p(q[1], q[2]);
    for (const auto& z : zones) {
      if (z.size() < 3) continue;
      const bool hit = geometry::InsidePolygon(z, p) || geometry::DistanceToPolygon(z, p) < margin;
      if (hit) {
        ++n;
        break;
      }
    }
  }
  return n;
}

double HazardMapQuality::Recall() const {
  return hazards_seen > 0 ? static_cast<double>(hazards_marked) / hazards_seen : kNan;
}

double HazardMapQuality::FalseObstacleRate() const {
  return obstacle_cells > 0 ? static_cast<double>(false_obstacle_cells) / obstacle_cells : kNan;
}

HazardMapQuality EvaluateHazardMap(const GoodnessGrid& map,
                                   const std::vector<sim::judge::JudgeRock>& rocks,
                                   double traversable_height, const Track& truth_track,
                                   const HazardMapOptions& options) {
  HazardMapQuality q;
  std::vector<const sim::judge::JudgeRock*> hazards;
  for (const auto& r : rocks) {
    if (r.height > traversable_height) hazards.push_back(&r);
  }
  const double res = map.resolution;
  if (!(res > 0) || map.width <= 0 || map.height <= 0) return q;
  for (const sim::judge::JudgeRock* r : hazards) {
    if (truth_track.empty() || NearestTrackDistance(truth_track, r->xy) > options.path_radius) {
      continue;
    }
    ++q.hazards_near_path;
    const int centre = map.CellAt(r->xy.x(), r->xy.y());
    if (centre < 0 || !map.Known(centre % map.width, centre / map.width)) continue;
    ++q.hazards_seen;
    const double radius = r->diameter / 2 + res;
    const int ci = centre % map.width, cj = centre / map.width;
    const int span = static_cast<int>(std::ceil(radius / res));
    bool marked = false;
    for (int j = cj - span; j <= cj + span && !marked; ++j) {
      for (int i = ci - span; i <= ci + span && !marked; ++i) {
        marked = Marked(map, i, j, options.obstacle_goodness) &&
                 (CellCentre(map, i, j) - r->xy).norm() <= radius;
      }
    }
    if (marked) ++q.hazards_marked;
  }
  for (int j = 0; j < map.height; ++j) {
    for (int i = 0; i < map.width; ++i) {
      if (!Marked(map, i, j, options.obstacle_goodness)) continue;
      ++q.obstacle_cells;
      const Eigen::Vector2d c = CellCentre(map, i, j);
      const bool explained = std::any_of(hazards.begin(), hazards.end(), [&](const auto* r) {
        return (r->xy - c).norm() <= options.reach + r->diameter / 2 + 0.5 * res;
      });
      if (!explained) ++q.false_obstacle_cells;
    }
  }
  return q;
}

MotionFigures EvaluateMotion(const Track& track, double t0, double t1,
                             const std::vector<double>& yaw, double still_speed,
                             double still_turn_rate) {
  MotionFigures m;
  m.duration = std::max(0.0, t1 - t0);
  const bool with_yaw = !yaw.empty() && yaw.size() == track.size();
  double still_s = 0, turning_s = 0;
  std::size_t prev = track.size();
  for (std::size_t i = 0; i < track.size(); ++i) {
    const auto& p = track[i];
    if (p[0] < t0 || p[0] > t1) continue;
    if (prev < track.size()) {
      const auto& q = track[prev];
      const double dt = p[0] - q[0];
      const double d = std::hypot(p[1] - q[1], p[2] - q[2]);
      m.distance += d;
      if (dt > 0 && d / dt < still_speed) {
        const double turn = with_yaw ? std::abs(geometry::WrapAngle(yaw[i] - yaw[prev])) : 0.0;
        (turn / dt >= still_turn_rate ? turning_s : still_s) += dt;
      }
    }
    prev = i;
  }
  if (m.duration > 0) {
    m.traverse_rate = m.distance / m.duration * 3600.0;
    m.standing_still = std::clamp(still_s / m.duration, 0.0, 1.0);
    m.turning_in_place = std::clamp(turning_s / m.duration, 0.0, 1.0);
  }
  return m;
}

std::vector<sim::judge::Criterion> AutonavFigures(const MobilityOutcome& mob,
                                                  const Track& truth_track,
                                                  const std::vector<sim::judge::JudgeRock>& rocks,
                                                  double traversable_height,
                                                  const HazardMapOptions& options,
                                                  const std::vector<double>& truth_yaw) {
  std::vector<sim::judge::Criterion> out;
  out.push_back({"mobility_steps", static_cast<double>(mob.steps), kNan, "count", true,
                 "drive steps apl/mobility_status reported"});
  out.push_back({"mobility_images", static_cast<double>(mob.images), kNan, "count", true,
                 "range images apl/mobility_status reported"});
  const MotionFigures m = EvaluateMotion(truth_track, mob.sim_start_s, mob.sim_end_s, truth_yaw);
  char buf[160];
  std::snprintf(buf, sizeof buf, "sim/truth: %.2f m in %.1f simulated s of the command", m.distance,
                m.duration);
  out.push_back({"traverse_rate", m.traverse_rate, kNan, "m/h", true, buf});
  out.push_back({"standing_still", 100.0 * m.standing_still, kNan, "%", true,
                 truth_yaw.empty()
                     ? "share of the command's simulated time below 1 cm/s (sim/truth)"
                     : "share of the command's simulated time below 1 cm/s and turning below "
                       "0.01 rad/s (sim/truth)"});
  if (!truth_yaw.empty()) {
    out.push_back({"turning_in_place", 100.0 * m.turning_in_place, kNan, "%", true,
                   "share of the command's simulated time below 1 cm/s but turning (sim/truth)"});
  }
  if (mob.last_map) {
    const HazardMapQuality q =
        EvaluateHazardMap(*mob.last_map, rocks, traversable_height, truth_track, options);
    // A figure without a measurement is left out (result.json has no NaN).
    if (q.hazards_seen > 0) {
      out.push_back({"hazard_map_recall", 100.0 * q.Recall(), kNan, "%", true,
                   Count("%d of %d seen hazards marked obstacle (last apl/goodness_map)",
                         q.hazards_marked, q.hazards_seen) +
                       Count(", %d near the path, %d unseen", q.hazards_near_path,
                             q.hazards_near_path - q.hazards_seen)});
    }
    if (q.obstacle_cells > 0) {
      out.push_back({"hazard_map_false_obstacle_rate", 100.0 * q.FalseObstacleRate(), kNan, "%",
                     true,
                     Count("%d of %d obstacle cells with no truth hazard within reach",
                           q.false_obstacle_cells, q.obstacle_cells)});
    }
  }
  return out;
}

}  // namespace rover::deploy::runner
