#include "rover/apl/gestalt/arc_evaluator.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "rover/apl/gestalt/arc_geometry.hpp"
#include "rover/apl/gestalt/cost_to_go.hpp"
#include "rover/apl/nav_core/range_scan.hpp"
#include "rover/base/range_check.hpp"

namespace rover::apl::gestalt {
namespace {

using nav_core::ArcEvaluation;
using nav_core::ArcRequest;
using nav_core::Candidate;
using nav_core::GoalMode;
using nav_core::GoodnessMap;
using nav_core::MotionKind;
using nav_core::Vote;

constexpr int kForward = 0, kBackward = 1, kTurns = 2;
// [m/rad] cost_to_go: what turning in place costs beside driving (a half turn ~ 1.6 m).
constexpr double kTurnCostPerRad = 0.5;

double WrapPi(double a) {
  a = std::remainder(a, 2.0 * std::numbers::pi);  // [-pi, pi]
  return a <= -std::numbers::pi ? a + 2.0 * std::numbers::pi : a;
}

int Round255(double v) { return std::clamp(static_cast<int>(std::lround(v)), 0, 255); }

}  // namespace

Vote MergeVotes(const Vote& hazard, const Vote& waypoint, int min_vote_goodness) {
  if (hazard.goodness < min_vote_goodness || waypoint.goodness < min_vote_goodness ||
      hazard.certainty + waypoint.certainty <= 0) {
    return hazard.goodness <= waypoint.goodness ? hazard : waypoint;
  }
  const double sum = static_cast<double>(hazard.goodness) * hazard.certainty +
                     static_cast<double>(waypoint.goodness) * waypoint.certainty;
  return {Round255(sum / (hazard.certainty + waypoint.certainty)),
          std::max(hazard.certainty, waypoint.certainty)};
}

int ChooseCandidate(const std::vector<Vote>& merged, const std::vector<int>& group) {
  ROVER_DEMAND(merged.size() == group.size());
  int best = 0;
  for (const Vote& v : merged) best = std::max(best, v.goodness);
  if (best <= 0) return -1;
  int chosen = -1, best_len = 0;
  const int n = static_cast<int>(merged.size());
  for (int k = 0; k < n;) {
    if (merged[static_cast<std::size_t>(k)].goodness != best) {
      ++k;
      continue;
    }
    int end = k + 1;
    while (end < n && merged[static_cast<std::size_t>(end)].goodness == best &&
           group[static_cast<std::size_t>(end)] == group[static_cast<std::size_t>(k)]) {
      ++end;
    }
    const int len = end - k;
    if (len > best_len) {
      best_len = len;
      chosen = k + (len - 1) / 2;
    }
    k = end;
  }
  return chosen;
}

Result<ArcEvaluator> ArcEvaluator::Create(const GestaltOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  return ArcEvaluator(options);
}

ArcEvaluator::ArcEvaluator(const GestaltOptions& options) : options_(options) {
  auto add_arcs = [&](int count, int direction, int group) {
    for (int a = 0; a < count; ++a) {
      Candidate c;
      c.kind = MotionKind::kArc;
      c.direction = direction;
      c.curvature = count == 1 ? 0.0 : options.max_curvature * (-1.0 + 2.0 * a / (count - 1));
      candidates_.push_back(c);
      groups_.push_back(group);
    }
  };
  add_arcs(options.num_forward_arcs, 1, kForward);
  add_arcs(options.num_backward_arcs, -1, kBackward);
  std::vector<double> turns;
  for (int t = 1; t <= options.num_point_turns; ++t) {
    turns.push_back(WrapPi(2.0 * std::numbers::pi * t / (options.num_point_turns + 1)));
  }
  std::sort(turns.begin(), turns.end());
  for (double a : turns) {
    Candidate c;
    c.kind = MotionKind::kPointTurn;
    c.turn_angle = a;
    candidates_.push_back(c);
    groups_.push_back(kTurns);
  }
}

PathVote ArcEvaluator::HazardVote(const GoodnessMap& map,
                                  const std::vector<PathCell>& cells) const {
  PathVote pv;
  pv.cells = static_cast<int>(cells.size());
  pv.all_known = !cells.empty();
  double sw = 0.0, sg = 0.0, sc = 0.0;
  bool forbidden = false;
  for (const PathCell& c : cells) {
    const nav_core::CellValue v = map.At(c.i, c.j);
    if (!v.known()) pv.all_known = false;
    if (v.goodness < options_.min_allowed_goodness) forbidden = true;
    const double w =
        1.0 + (options_.near_weight - 1.0) * std::max(0.0, 1.0 - c.s / options_.plan_max_dist);
    sw += w;
    sg += w * v.goodness;
    sc += w * v.certainty;
  }
  if (forbidden) {
    pv.vote = {0, 255};
  } else if (sw > 0.0) {
    pv.vote = {Round255(sg / sw), Round255(sc / sw)};
  } else {
    pv.vote = {map.unknown_goodness, map.unknown_certainty};
  }
  return pv;
}

namespace {
// Does hazard point `local` (rover frame at the pose tested) hit the grown footprint?
bool HitsFootprint(const GestaltOptions& o, const FootprintHazard& h,
                   const Eigen::Vector2d& local) {
  const double m = o.footprint_margin;
  if (local.x() < o.footprint_min_x - m || local.x() > o.footprint_max_x + m ||
      local.y() < o.footprint_min_y - m || local.y() > o.footprint_max_y + m) {
    return false;
  }
  if (!o.footprint_straddle) return true;
  for (const hwconfig::ContactPart& part : o.contact_parts) {
    if (part.clearance > 0.0 && !h.tall) continue;
    if (part.DistanceTo(local) < m) return true;
  }
  return false;
}
}  // namespace

std::vector<FootprintHazard> ArcEvaluator::FootprintHazards(const GoodnessMap& map,
                                                            const Pose2& pose) const {
  const GestaltOptions& o = options_;
  const Eigen::Vector2d lo(o.footprint_min_x - o.footprint_margin,
                           o.footprint_min_y - o.footprint_margin);
  const Eigen::Vector2d hi(o.footprint_max_x + o.footprint_margin,
                           o.footprint_max_y + o.footprint_margin);
  const double reach = o.plan_max_dist + std::max(lo.norm(), hi.norm()) + o.cell_size;
  const double c = std::cos(pose.yaw), s = std::sin(pose.yaw);
  std::vector<FootprintHazard> points;
  int i0 = 0, j0 = 0, i1 = 0, j1 = 0;
  map.CellOf(pose.x - reach, pose.y - reach, &i0, &j0);
  map.CellOf(pose.x + reach, pose.y + reach, &i1, &j1);
  for (int j = std::max(0, j0); j <= std::min(map.height - 1, j1); ++j) {
    for (int i = std::max(0, i0); i <= std::min(map.width - 1, i1); ++i) {
      const std::uint8_t flags = map.flags[map.Index(i, j)];
      if ((flags & nav_core::kCellHazard) == 0) continue;
      const Eigen::Vector2d d = map.CellCenter(i, j) - Eigen::Vector2d(pose.x, pose.y);
      if (d.squaredNorm() > reach * reach) continue;
      const FootprintHazard h{Eigen::Vector2d(c * d.x() + s * d.y(), -s * d.x() + c * d.y()),
                              (flags & nav_core::kCellTall) != 0};
      if (HitsFootprint(o, h, h.q)) continue;  // under the rover already
      points.push_back(h);
    }
  }
  return points;
}

double ArcEvaluator::FirstFootprintHit(const Candidate& candidate, double length,
                                       const std::vector<FootprintHazard>& hazards) const {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  if (hazards.empty()) return kInf;
  const GestaltOptions& o = options_;
  auto hit_at = [&](const Eigen::Vector2d& p, double heading) {
    const double c = std::cos(heading), s = std::sin(heading);
    for (const FootprintHazard& h : hazards) {
      const Eigen::Vector2d d = h.q - p;
      if (HitsFootprint(o, h, Eigen::Vector2d(c * d.x() + s * d.y(), -s * d.x() + c * d.y()))) {
        return true;
      }
    }
    return false;
  };
  if (candidate.kind == MotionKind::kPointTurn) {
    constexpr double kStep = 2.5 * std::numbers::pi / 180.0;
    const int n = static_cast<int>(std::ceil(std::abs(candidate.turn_angle) / kStep));
    for (int t = 1; t <= n; ++t) {
      if (hit_at(Eigen::Vector2d::Zero(), candidate.turn_angle * t / n)) return 0.0;
    }
    return kInf;
  }
  const double ds = 0.5 * o.cell_size;
  const int n = static_cast<int>(std::ceil(length / ds));
  for (int t = 1; t <= n; ++t) {
    const double s = std::min(length, t * ds);
    const Eigen::Vector2d p = ArcPoint(candidate.curvature, candidate.direction, s);
    if (hit_at(p, candidate.direction * candidate.curvature * s)) return s;
  }
  return kInf;
}

Result<ArcEvaluation> ArcEvaluator::Evaluate(const GoodnessMap& map,
                                             const ArcRequest& request) const {
  ROVER_RETURN_IF_ERROR(request.Validate());
  const GestaltOptions& o = options_;
  ArcEvaluation e;
  e.candidates = candidates_;
  const std::size_t n = candidates_.size();
  e.hazard.assign(n, Vote{});
  e.waypoint.assign(n, Vote{});
  e.merged.assign(n, Vote{});

  const Pose2 pose = PlanarPose(request.site_from_rover);
  const double c = std::cos(pose.yaw), s = std::sin(pose.yaw);
  const double dx = request.goal.x() - pose.x, dy = request.goal.y() - pose.y;
  const double gx = c * dx + s * dy, gy = -s * dx + c * dy;  // goal in the rover frame
  e.distance_to_goal = std::hypot(gx, gy);
  if (e.distance_to_goal <= request.goal_tolerance) {
    e.mode = GoalMode::kReached;
    return e;
  }
  const double k_goal = 2.0 * gy / (gx * gx + gy * gy);
  const double bearing = std::atan2(gy, gx);
  const bool backup = std::abs(k_goal) > o.max_curvature;
  e.mode = backup ? GoalMode::kBackUp : GoalMode::kNormal;
  // How far the goal lies behind abeam (> 0 behind, < 0 ahead), and the direction toward it.
  const double behind_abeam = std::abs(bearing) - 0.5 * std::numbers::pi;
  int toward_direction = behind_abeam <= 0.0 ? 1 : -1;
  if (request.last_direction > 0 && behind_abeam <= o.direction_hysteresis) toward_direction = 1;
  if (request.last_direction < 0 && behind_abeam >= -o.direction_hysteresis) toward_direction = -1;
  const double k_backup = (gy >= 0.0 ? -1.0 : 1.0) * o.max_curvature;
  const double k_clamped = std::clamp(k_goal, -o.max_curvature, o.max_curvature);
  const double length =
      std::clamp(e.distance_to_goal, o.plan_min_dist + o.cell_size, o.plan_max_dist);

  std::vector<PathCell> cells;
  std::vector<PathVote> path_votes(n);
  const std::vector<FootprintHazard> hazards =
      o.footprint_check ? FootprintHazards(map, pose) : std::vector<FootprintHazard>{};
  for (std::size_t k = 0; k < n; ++k) {
    Candidate& cand = e.candidates[k];
    double peak = 0.0, exponent = 0.0;
    if (cand.kind == MotionKind::kArc) {
      cand.length = length;
      SweptCells(map, pose, ArcPath{cand.curvature, cand.direction, o.plan_min_dist, length},
                 o.path_half_width, &cells);
      double centre = k_goal;
      if (backup) {
        centre = cand.direction < 0 ? k_backup : k_clamped;
        peak = o.backup_vote_scale *
               (cand.direction < 0 ? o.waypoint_peak_toward : o.waypoint_peak_away);
      } else {
        peak = cand.direction == toward_direction ? o.waypoint_peak_toward : o.waypoint_peak_away;
      }
      const double dk = cand.curvature - centre;
      exponent = dk * dk / (2.0 * o.arc_vote_variance);
    } else {
      TurnCells(map, pose, o.path_half_width, &cells);
      peak = backup ? o.waypoint_peak_toward : o.waypoint_peak_away;
      const double da = WrapPi(cand.turn_angle - bearing);
      exponent = da * da / (2.0 * o.turn_vote_variance);
    }
    path_votes[k] = HazardVote(map, cells);
    if (o.footprint_check && cand.kind == MotionKind::kPointTurn &&
        path_votes[k].vote.goodness > 0) {
      // A turn is worth what it leads to: the straight path of `length` from the new heading
      // (without this, a turn's vote is its centre cell's, near perfect, and a rover facing
      // rocks turns back and forth toward headings it cannot drive).
      const Pose2 turned{pose.x, pose.y, pose.yaw + cand.turn_angle};
      SweptCells(map, turned, ArcPath{0.0, 1, o.plan_min_dist, length}, o.path_half_width,
                 &cells);
      const PathVote straight = HazardVote(map, cells);
      Vote& v = path_votes[k].vote;
      if (straight.vote.goodness == 0) {
        v = straight.vote;
      } else {
        const double hit = FirstFootprintHit(Candidate{MotionKind::kArc, 0.0, 1, length, 0.0},
                                             length, FootprintHazards(map, turned));
        if (hit <= o.footprint_forbid_dist) {
          v = {0, 255};
        } else {
          const int g = hit < length ? std::max(1, Round255(straight.vote.goodness * hit / length))
                                     : straight.vote.goodness;
          v.goodness = std::min(v.goodness, g);
          v.certainty = std::min(v.certainty, straight.vote.certainty);
        }
      }
    }
    if (!hazards.empty() && path_votes[k].vote.goodness > 0) {
      const double hit = FirstFootprintHit(cand, length, hazards);
      Vote& v = path_votes[k].vote;
      if (cand.kind == MotionKind::kPointTurn ? hit < length : hit <= o.footprint_forbid_dist) {
        v = {0, 255};
      } else if (hit < length) {
        v.goodness = std::max(1, Round255(v.goodness * hit / length));
      }
    }
    e.hazard[k] = path_votes[k].vote;
    e.waypoint[k] = {Round255(peak * std::exp(-exponent)), o.waypoint_certainty};
    e.merged[k] = MergeVotes(e.hazard[k], e.waypoint[k], o.min_vote_goodness);
  }
  if (o.cost_to_go) {
    // Waypoint votes from drive cost + cost-to-go (file comment).
    CostToGoOptions co;
    co.clearance = std::min(-o.footprint_min_y, o.footprint_max_y) + o.footprint_margin;
    co.straddle = o.footprint_straddle;
    co.min_allowed_goodness = o.min_allowed_goodness;
    co.goodness_weight = o.cost_goodness_weight;
    co.unknown_cost_factor = o.cost_unknown_factor;
    const gestalt::CostToGo ctg(map, request.goal, co);
    std::vector<double> cost(n, std::numeric_limits<double>::infinity());
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < n; ++k) {
      const Candidate& cand = e.candidates[k];
      Eigen::Vector2d end_r;  // rover frame
      double drive = length;
      if (cand.kind == MotionKind::kArc) {
        end_r = ArcPoint(cand.curvature, cand.direction, length);
      } else {
        end_r = length * Eigen::Vector2d(std::cos(cand.turn_angle), std::sin(cand.turn_angle));
        drive += kTurnCostPerRad * std::abs(cand.turn_angle);
      }
      const double ex = pose.x + c * end_r.x() - s * end_r.y();
      const double ey = pose.y + s * end_r.x() + c * end_r.y();
      cost[k] = drive + ctg.Cost(ex, ey);
      // The best is taken over the candidates the hazard vote allows: a forbidden candidate's
      // low cost must not push every allowed one's vote down.
      if (e.hazard[k].goodness > 0) best = std::min(best, cost[k]);
    }
    if (std::isfinite(best)) {
      for (std::size_t k = 0; k < n; ++k) {
        const Candidate& cand = e.candidates[k];
        const double peak = cand.kind == MotionKind::kArc && cand.direction > 0
                                ? o.waypoint_peak_toward
                                : o.waypoint_peak_away;
        const double excess = cost[k] - best;  // inf -> vote 0
        e.waypoint[k] = {
            std::isfinite(excess)
                ? Round255(peak * std::exp(-excess * excess /
                                           (2.0 * o.cost_vote_sigma * o.cost_vote_sigma)))
                : 0,
            o.waypoint_certainty};
        e.merged[k] = MergeVotes(e.hazard[k], e.waypoint[k], o.min_vote_goodness);
      }
    }
  }
  e.chosen = ChooseCandidate(e.merged, groups_);

  int best_forward = 0;
  for (std::size_t k = 0; k < n; ++k) {
    if (groups_[k] == kForward) best_forward = std::max(best_forward, e.merged[k].goodness);
  }
  e.image_rear = best_forward < o.min_fwd_threshold;
  if (e.chosen >= 0 && e.choice().kind == MotionKind::kArc) {
    const int group = groups_[static_cast<std::size_t>(e.chosen)];
    e.all_paths_safe = true;
    for (std::size_t k = 0; k < n; ++k) {
      if (groups_[k] != group) continue;
      if (!path_votes[k].all_known || e.hazard[k].goodness < o.skip_imaging_goodness) {
        e.all_paths_safe = false;
        break;
      }
    }
  }
  return e;
}

}  // namespace rover::apl::gestalt
