#include "rover/apl/enav/enav_planner.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>

#include "rover/base/format.hpp"

namespace rover::apl::enav {
namespace {

constexpr double kNoCost = std::numeric_limits<double>::infinity();
constexpr double kTurnStep = 10.0 * std::numbers::pi / 180.0;  // [rad] poses along a turn
constexpr double kBlockedFactor = 10.0;  // [per m] a blocked cell's price when ranking blind
constexpr double kContinueDistance = 0.2;  // [m] the rover counts as on its previous path
constexpr double kContinueHeading = 0.2;   // [rad] ... heading this close to the path's
constexpr double kEntryReach = 0.05;  // [m] past the tolerance's edge: far enough to count
constexpr double kRetraceStep = 0.02;      // [m] poses along the last drive searched
constexpr double kRetraceMax = 1.5;        // [m] ... this far
constexpr double kRetraceDistance = 0.15;  // [m] the rover counts as on its last drive
constexpr double kRetraceHeading = 0.15;   // [rad] ... heading this close
constexpr double kRetraceMin = 0.1;        // [m] less driven than this: nothing to retrace
constexpr std::size_t kRouteCostsKept = 4096;  // route points remembered for CostToGo
constexpr double kRouteMatch = 0.25;  // [m] a point this near a remembered route point is it
constexpr double kMinTurn = 0.02;     // [rad] smaller turns toward a route pose are not made
constexpr double kMinStep = 0.05;     // [m] nearer route poses are not aimed at
constexpr double kOnLine = 0.1;       // [m] off a route step's line: no longer on it
constexpr double kOnLineHeading = 0.15;  // [rad] turned off a route step's line: no longer on it
constexpr double kStandingMargin = 0.4;  // [m] around the footprint: ground not "unseen"
                                         // (the wheels hide their own surroundings)

// Whether site point p lies on the rover's ground footprint at `pose`, grown by `margin`.
bool OnFootprint(const geometry::Pose2& pose, hwconfig::Footprint f, double margin,
                 const Eigen::Vector2d& p) {
  const Eigen::Vector2d d = p - pose.xy();
  const double c = std::cos(pose.heading), s = std::sin(pose.heading);
  f.min_x -= margin;
  f.max_x += margin;
  f.min_y -= margin;
  f.max_y += margin;
  return f.Contains(c * d.x() + s * d.y(), -s * d.x() + c * d.y());
}



// Whether wheel `w` at `pose` stands on ground the rover covers at `start` (its footprint grown
// by kStandingMargin): the cameras cannot see there, so that ground does not count as unseen.
bool OnStandingGround(const hwconfig::RoverDescription& rover, const geometry::Pose2& start,
                      const geometry::Pose2& pose, int w) {
  return OnFootprint(start, rover.GroundFootprint(), kStandingMargin,
                     pose.ToSite(rover.WheelCentre(w).head<2>()));
}

nav_core::Candidate FirstSegment(const TreePath& p) {
  nav_core::Candidate c;
  if (p.turn != 0.0) {
    c.kind = nav_core::MotionKind::kPointTurn;
    c.turn_angle = p.turn;
    return c;
  }
  c.kind = nav_core::MotionKind::kArc;
  c.curvature = p.k1;
  c.direction = p.direction;
  c.length = p.length1;
  return c;
}

}  // namespace

Result<EnavPlanner> EnavPlanner::Create(const EnavOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  return EnavPlanner(options);
}

EnavPlanner::EnavPlanner(const EnavOptions& options) : options_(options) {
  const double k_max = options.rover.MaxCurvature();
  const int n = options.num_curvatures;
  for (int i = 0; i < n; ++i) {
    curvatures_.push_back(n == 1 ? 0.0 : -k_max + 2.0 * k_max * i / (n - 1));
  }
  // Exactly straight in the middle (odd counts).
  for (double& k : curvatures_) {
    if (std::abs(k) < 1e-9) k = 0.0;
  }
}

std::optional<double> EnavPlanner::CostToGo(const Eigen::Vector2d& goal,
                                            const Eigen::Vector2d& xy) const {
  if (field_.goal() != goal) return std::nullopt;
  if (options_.route_max_expansions > 0 && options_.route_first) {
    // The route cost found when a decision was made there (a route is over poses: the field's
    // heading-blind value may rise along a detour the route runs down).
    // The newest decision with a point near xy, its nearest point.
    const RouteCost* best = nullptr;
    for (auto it = route_costs_.rbegin(); it != route_costs_.rend(); ++it) {
      if (best != nullptr && it->decision != best->decision) break;
      const double d = (it->xy - xy).norm();
      if (d <= kRouteMatch && (best == nullptr || d < (best->xy - xy).norm())) best = &*it;
    }
    if (best != nullptr) return best->cost;
    return std::nullopt;
  }
  const double c = field_.Cost(xy);
  if (!std::isfinite(c)) return std::nullopt;
  return c;
}

Result<nav_core::ArcEvaluation> EnavPlanner::Evaluate(const nav_core::GoodnessMap& map,
                                                      const nav_core::ArcRequest& request) const {
  (void)map;
  (void)request;
  return FailedPrecondition(
      "the ENav planner needs heights: use apl/enav's HeightTerrain as the terrain assessor");
}

std::vector<geometry::Pose2> EnavPlanner::Samples(const geometry::Pose2& start,
                                                  const TreePath& p) const {
  std::vector<geometry::Pose2> out;
  const double ds = options_.sample_spacing;
  const geometry::Pose2 s0 = geometry::Turned(start, p.turn);
  const double end = p.end_s > 0.0 ? p.end_s : p.length1 + p.length2;
  auto segment = [&](const geometry::Pose2& from, double k, double length, double offset) {
    const int n = std::max(1, static_cast<int>(std::ceil(length / ds - 1e-9)));
    for (int i = 1; i <= n; ++i) {
      const double s = length * i / n;
      if (offset + s > end + 1e-9) return false;
      out.push_back(geometry::AlongArc(from, k, p.direction * s));
    }
    return true;
  };
  if (!segment(s0, p.k1, p.length1, 0.0)) return out;
  if (p.length2 > 0.0) segment(geometry::AlongArc(s0, p.k1, p.direction * p.length1), p.k2,
                               p.length2, p.length1);
  return out;
}

bool EnavPlanner::CheckPath(const ClearanceChecker& checker, const geometry::Pose2& start,
                            const Exempt& on, TreePath* p) const {
  // The turn in place.
  if (p->turn != 0.0) {
    const int n = std::max(1, static_cast<int>(std::ceil(std::abs(p->turn) / kTurnStep)));
    for (int i = 1; i <= n; ++i) {
      const geometry::Pose2 pose = geometry::Turned(start, p->turn * i / n);
      const PoseCheck c = checker.CheckPose(pose, true, &on);
      if (!c.ok) {
        p->why = "turn " + FormatNumber(p->turn / kDegree, 3) + " deg: " + c.why;
        return false;
      }
      // A turn sweeps the corner wheels beside the rover, where the cameras may never have
      // looked: every wheel patch off the ground it stands on must have been seen.
      for (int w = 0; w < hwconfig::kNumWheels; ++w) {
        if ((c.unknown_mask & (1U << w)) == 0) continue;
        if (OnStandingGround(options_.rover, start, pose, w)) continue;
        p->why = "turn " + FormatNumber(p->turn / kDegree, 3) + " deg: wheel " +
                 hwconfig::WheelName(w) + " over unseen ground";
        return false;
      }
    }
  }
  const std::vector<geometry::Pose2> poses = Samples(start, *p);
  int unknown = 0, wheels = 0;
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const double s = options_.sample_spacing * static_cast<double>(i + 1);
    if (s > options_.check_length + 1e-9) break;
    const bool ace = s <= options_.ace_length + 1e-9;
    const PoseCheck c = checker.CheckPose(poses[i], ace, &on);
    if (!c.ok) {
      p->why = "at " + FormatNumber(s, 2) + " m: " + c.why;
      return false;
    }
    if (s <= options_.known_length + 1e-9) {
      // Ground the rover stands on now is not "unseen": the cameras cannot see under it.
      for (int w = 0; w < hwconfig::kNumWheels; ++w) {
        if (OnStandingGround(options_.rover, start, poses[i], w)) continue;
        wheels += 1;
        if ((c.unknown_mask & (1U << w)) != 0) unknown += 1;
      }
    }
  }
  if (wheels > 0 && unknown > options_.max_unknown_fraction * wheels) {
    p->why = FormatNumber(100.0 * unknown / wheels, 3) + " % of the wheel patches in the first " +
             FormatNumber(options_.known_length) + " m unseen";
    return false;
  }
  return true;
}

bool EnavPlanner::Settle(const ClearanceChecker& checker, const geometry::Pose2& start,
                         const Exempt& on, bool escape, TreePath* p) const {
  if (p->entry_s <= 0.0 || p->end_s <= p->entry_s + kEntryReach) return false;
  TreePath shorter = *p;
  shorter.end_s = p->entry_s + kEntryReach;
  if (!CheckPath(checker, start, on, &shorter)) return false;
  if (escape && !Clears(checker, start, on, &shorter)) return false;
  *p = shorter;
  p->settled = true;
  p->checked = 1;
  return true;
}

namespace {
// Whether the height cell under site point xy has been seen.
bool GoalSeen(const HeightTerrain& t, const Eigen::Vector2d& xy) {
  const nav_core::HeightMap& m = *t.height_map();
  int i = 0, j = 0;
  m.CellOf(xy.x(), xy.y(), &i, &j);
  return m.Contains(i, j) && m.count[m.Index(i, j)] > 0;
}
}  // namespace

bool EnavPlanner::Clears(const ClearanceChecker& checker, const geometry::Pose2& start,
                         const Exempt& exempt, TreePath* p) const {
  TreePath first = *p;
  first.length2 = 0.0;
  first.end_s = 0.0;
  const std::vector<geometry::Pose2> poses = Samples(start, first);
  const geometry::Pose2 end = poses.empty() ? geometry::Turned(start, p->turn) : poses.back();
  for (const auto& [part, k] : checker.Touching(end, 0.0).entries) {
    if (exempt.Has(k)) {
      p->why = "escape: still touching the hazard it starts beside after its first segment";
      return false;
    }
  }
  return true;
}

std::optional<TreePath> EnavPlanner::Retrace(const geometry::Pose2& start) const {
  if (!last_drive_) return std::nullopt;
  // Where along the last choice's arc (from where the arc starts) the rover stands.
  double best = kRetraceDistance, best_s = 0.0;
  for (double s = kRetraceStep; s <= kRetraceMax + 1e-9; s += kRetraceStep) {
    const geometry::Pose2 p =
        geometry::AlongArc(last_drive_->start, last_drive_->k, last_drive_->direction * s);
    const double d = (p.xy() - start.xy()).norm();
    const double dh = std::abs(geometry::WrapAngle(p.heading - start.heading));
    if (d < best && dh < kRetraceHeading) {
      best = d;
      best_s = s;
    }
  }
  if (best_s < kRetraceMin) return std::nullopt;
  TreePath r;
  r.direction = -last_drive_->direction;
  r.k1 = last_drive_->k;
  r.length1 = best_s;
  r.turn_index = -4;
  r.k1_index = -4;
  return r;
}

RouteSearchOptions EnavPlanner::RouteOptions() const {
  RouteSearchOptions ro;
  ro.margin = options_.route_margin;
  ro.backward_factor = options_.route_backward_factor;
  ro.turn_cost = options_.turn_cost;
  ro.max_expansions = options_.route_max_expansions;
  return ro;
}

bool EnavPlanner::KeepsRouteRoom(const ClearanceChecker& checker, const geometry::Pose2& start,
                                 double start_room, const geometry::Pose2& pose) const {
  return checker.Room(pose) >
         NeededRoom(RouteOptions(), start_room, (pose.xy() - start.xy()).norm());
}

std::optional<Route> EnavPlanner::Kept(const ClearanceChecker& checker,
                                       const geometry::Pose2& start,
                                       const Eigen::Vector2d& goal) const {
  if (!plan_ || plan_goal_ != goal || plan_->nodes.size() < 2) return std::nullopt;
  const double start_room = checker.Room(start);
  // On the line of the last step (up to its end): the rover itself, then the route from the
  // pose the line aims at (a step is driven a drive length at a time; from halfway along a
  // line that cut a corner no node of the route may be near, and at its end the rover faces
  // the line's way, not the route's).
  if (step_ && step_->target < plan_->nodes.size()) {
    const Eigen::Vector2d line = step_->to - step_->from;
    const double length = line.norm();
    const Eigen::Vector2d u = line / std::max(length, 1e-9);
    const Eigen::Vector2d rel = start.xy() - step_->from;
    const double s = rel.dot(u), lateral = std::abs(u.x() * rel.y() - u.y() * rel.x());
    const double line_heading = std::atan2(step_->dir * u.y(), step_->dir * u.x());
    if (length > 0.0 && lateral <= kOnLine && s >= -kOnLine && s <= length + kOnLine &&
        std::abs(geometry::WrapAngle(start.heading - line_heading)) <= kOnLineHeading) {
      Route kept;
      kept.at_goal = plan_->at_goal;
      const double g0 = plan_->nodes[step_->target].g - (length - s);
      RouteNode here;
      here.pose = start;
      kept.nodes.push_back(here);
      bool fits = true;
      for (std::size_t k = step_->target; fits && k < plan_->nodes.size(); ++k) {
        RouteNode n = plan_->nodes[k];
        fits = KeepsRouteRoom(checker, start, start_room, n.pose);
        n.g -= g0;
        kept.nodes.push_back(n);
      }
      if (fits) {
        kept.cost = plan_->cost - g0;
        return kept;
      }
    }
  }
  // The node nearest the rover, if it is on the route.
  std::size_t at = 0;
  double best = kContinueDistance;
  for (std::size_t k = 0; k < plan_->nodes.size(); ++k) {
    const geometry::Pose2& q = plan_->nodes[k].pose;
    const double d = (q.xy() - start.xy()).norm();
    if (d < best && std::abs(geometry::WrapAngle(q.heading - start.heading)) < kContinueHeading) {
      best = d;
      at = k;
    }
  }
  if (best >= kContinueDistance) return std::nullopt;
  Route kept;
  kept.at_goal = plan_->at_goal;
  const double g0 = plan_->nodes[at].g;
  for (std::size_t k = at; k < plan_->nodes.size(); ++k) {
    RouteNode n = plan_->nodes[k];
    if (!KeepsRouteRoom(checker, start, start_room, n.pose)) return std::nullopt;
    n.g -= g0;
    if (k == at) n.move = 0;
    kept.nodes.push_back(n);
  }
  kept.cost = plan_->cost - g0;
  return kept;
}

std::optional<TreePath> EnavPlanner::RouteStep(const ClearanceChecker& checker,
                                               const geometry::Pose2& start, const Route& route,
                                               const Eigen::Vector2d& goal, double tolerance,
                                               std::size_t* target) const {
  // The route's poses within route_lookahead along it (each with the direction it is driven
  // in), and its first straight run: the moves in the first move's direction and heading.
  struct Target {
    std::size_t node;
    int dir;
  };
  std::vector<Target> targets;
  std::vector<std::size_t> run;
  int run_dir = 0;
  bool run_open = true;
  double along = 0.0;
  for (std::size_t k = 1; k < route.nodes.size(); ++k) {
    const RouteNode& node = route.nodes[k];
    along += (node.pose.xy() - route.nodes[k - 1].pose.xy()).norm();
    if (along > options_.route_lookahead + 1e-9) break;
    if (node.move == 0) {
      run_open = run_open && run.empty();
      continue;
    }
    if (run_dir == 0) run_dir = node.move;
    if (run_open && node.move == run_dir) {
      run.push_back(k);
    } else {
      run_open = false;
    }
    targets.push_back({k, node.move});
    // A pose within the goal's tolerance is as far as a step aims.
    if ((node.pose.xy() - goal).norm() <= tolerance) break;
  }
  const double start_room = checker.Room(start);
  // A turn to `heading`, then `length` straight in the route's direction, if it passes.
  auto step = [&](double heading, int dir, double length) -> std::optional<TreePath> {
    TreePath p;
    p.turn = geometry::WrapAngle(heading - start.heading);
    if (std::abs(p.turn) < kMinTurn) p.turn = 0.0;
    p.direction = dir;
    p.length1 = length;
    p.turn_index = -5;
    p.k1_index = -5;
    p.cost = route.cost;
    // The line keeps the route's room (it may cut a corner the route went round), then the
    // clearance check proper.
    const std::vector<geometry::Pose2> poses = Samples(start, p);
    if (!std::all_of(poses.begin(), poses.end(), [&](const geometry::Pose2& q) {
          return KeepsRouteRoom(checker, start, start_room, q);
        })) {
      return std::nullopt;
    }
    // The route may run through unseen ground (priced); a step aims only through seen ground,
    // backward too (nothing images behind the rover before it backs).
    if (!std::all_of(poses.begin(), poses.end(), [&](const geometry::Pose2& q) {
          const std::uint8_t unknown = checker.CheckPose(q, true).unknown_mask;
          for (int w = 0; w < hwconfig::kNumWheels; ++w) {
            if ((unknown & (1U << w)) == 0) continue;
            if (!OnStandingGround(options_.rover, start, q, w)) return false;
          }
          return true;
        })) {
      return std::nullopt;
    }
    if (!CheckPath(checker, start, Exempt{}, &p)) return std::nullopt;
    p.checked = 1;
    p.why = "route";
    return p;
  };
  // Farthest first, straight at the pose (cutting the route's zigzags over lattice headings,
  // and a short reversal the lattice makes to line up).
  for (auto it = targets.rbegin(); it != targets.rend(); ++it) {
    const Eigen::Vector2d d = route.nodes[it->node].pose.xy() - start.xy();
    const double length = d.norm();
    if (length < kMinStep) continue;
    const double bearing = std::atan2(d.y(), d.x()) + (it->dir > 0 ? 0.0 : std::numbers::pi);
    if (std::optional<TreePath> p = step(bearing, it->dir, length)) {
      *target = it->node;
      return p;
    }
  }
  // None: the route's own first straight run (its lattice heading, not the bearing: a line at
  // the bearing swings the body off the heading the route keeps between rocks), farthest first.
  if (run.empty()) return std::nullopt;
  const double heading = route.nodes[run.front()].pose.heading;
  const Eigen::Vector2d axis(std::cos(heading), std::sin(heading));
  for (auto it = run.rbegin(); it != run.rend(); ++it) {
    const double length = run_dir * (route.nodes[*it].pose.xy() - start.xy()).dot(axis);
    if (length < kMinStep) continue;
    if (std::optional<TreePath> p = step(heading, run_dir, length)) {
      *target = *it;
      return p;
    }
  }
  return std::nullopt;
}

Result<nav_core::ArcEvaluation> EnavPlanner::Plan(const nav_core::TerrainAssessor& terrain,
                                                  const nav_core::ArcRequest& request) const {
  ROVER_RETURN_IF_ERROR(request.Validate());
  const auto* ht = dynamic_cast<const HeightTerrain*>(&terrain);
  if (ht == nullptr) {
    return FailedPrecondition(
        "the ENav planner needs heights: use apl/enav's HeightTerrain as the terrain assessor");
  }
  nav_core::ArcEvaluation eval;
  const geometry::Pose2 start = geometry::ToPose2(request.site_from_rover);
  eval.distance_to_goal = (request.goal - start.xy()).norm();
  last_ = PlanRecord{};
  last_.start = start;
  last_.goal = request.goal;
  if (eval.distance_to_goal <= request.goal_tolerance) {
    eval.mode = nav_core::GoalMode::kReached;
    return eval;
  }
  field_.Update(*ht, request.goal, request.goal_tolerance);
  const double tol2 = request.goal_tolerance * request.goal_tolerance;
  // A goal on a seen rock taller than the belly clearance is refused at once: the rover
  // cannot stand there. (Unseen goals are planned toward; a goal the heading-blind
  // configuration space blocks is approached: the clearance check decides.)
  if (ht->DistanceAt(HazardLayer::kBody, request.goal) == 0.0F && GoalSeen(*ht, request.goal) &&
      eval.distance_to_goal > request.goal_tolerance + options_.first_length) {
    eval.why.push_back("the goal (" + FormatNumber(request.goal.x(), 3) + ", " +
                       FormatNumber(request.goal.y(), 3) +
                       ") lies on a rock taller than the belly clearance");
    return eval;
  }

  const ClearanceChecker checker(*ht);
  std::vector<int> checked;
  std::vector<TreePath>& paths = last_.paths;
  // The route search first: a straight step along the cheapest route over poses, if one passes
  // the clearance check; else the tree.
  auto try_route = [&]() {
    if (options_.route_max_expansions <= 0) return;
    relaxed_.Update(*ht, request.goal, request.goal_tolerance);
    const RouteSearchOptions ro = RouteOptions();
    // A search from where the rover stands every decision (the lattice is anchored there, so
    // what fits differs by a few centimetres from one anchor to the next, and the map grows);
    // the route being followed is kept unless the new one is cheaper by route_switch_m.
    std::optional<Route> kept = Kept(checker, start, request.goal);
    last_.route = search_.Search(*ht, relaxed_, start, request.goal, request.goal_tolerance, ro);
    if (kept && (!last_.route || last_.route->cost > kept->cost - options_.route_switch)) {
      const int expansions = last_.route ? last_.route->expansions : 0;
      last_.route = std::move(kept);
      last_.route->expansions = expansions;
      last_.route_kept = true;
    }
    plan_ = last_.route;
    plan_goal_ = request.goal;
    step_.reset();
    if (last_.route) {
      decisions_ += 1;
      // The route's cost to go from where the rover stands and from its points ahead (where
      // the rover will be when the mobility manager weighs its progress).
      double along = 0.0;
      const std::vector<RouteNode>& nodes = last_.route->nodes;
      for (std::size_t k = 0; k < nodes.size() && along <= options_.route_lookahead; ++k) {
        if (k > 0) along += (nodes[k].pose.xy() - nodes[k - 1].pose.xy()).norm();
        route_costs_.push_back({k == 0 ? start.xy() : nodes[k].pose.xy(),
                                last_.route->cost - (nodes[k].g - nodes.front().g), decisions_});
      }
      if (route_costs_.size() > kRouteCostsKept) {
        route_costs_.erase(route_costs_.begin(),
                           route_costs_.begin() +
                               static_cast<std::ptrdiff_t>(route_costs_.size() - kRouteCostsKept));
      }
      std::size_t target = 0;
      if (std::optional<TreePath> step = RouteStep(checker, start, *last_.route, request.goal,
                                                   request.goal_tolerance, &target)) {
        const geometry::Pose2 from = geometry::Turned(start, step->turn);
        step_ = RouteLine{from.xy(), last_.route->nodes[target].pose.xy(), step->direction,
                          target};
        last_.routed = true;
        last_.ranked = last_.route->expansions;
        eval.candidates_ranked = last_.ranked;
        last_.chosen = static_cast<int>(paths.size());
        paths.push_back(*step);
        checked.push_back(last_.chosen);
        last_.checks += 1;
      }
    }
  };
  if (options_.route_first) try_route();
  if (!last_.routed) {
    // The tree and its cheap costs.
    const int nt = options_.num_turns;
    for (int t = 0; t < nt; ++t) {
      const double turn = t == 0 ? 0.0 : geometry::WrapAngle(2.0 * std::numbers::pi * t / nt);
      for (std::size_t a = 0; a < curvatures_.size(); ++a) {
        for (std::size_t b = 0; b < curvatures_.size(); ++b) {
          if (options_.second_length == 0.0 && b > 0) break;
          TreePath p;
          p.turn = turn;
          p.turn_index = t;
          p.k1_index = static_cast<int>(a);
          p.k1 = curvatures_[a];
          p.k2 = curvatures_[b];
          p.length1 = options_.first_length;
          p.length2 = options_.second_length;
          paths.push_back(p);
        }
      }
    }
    // The previous choice, continued from where the rover is now on it (if it is): the same
    // curvatures, the first shortened by what was driven and the second lengthened as much, so
    // it reaches as far as a fresh path. It gets commit_bonus off its cost (a plan is kept unless
    // a clearly better one appears; replanning every half metre otherwise dithers).
    if (previous_) {
      const std::vector<geometry::Pose2> prev = Samples(previous_->start, previous_->path);
      double best_d = kContinueDistance;
      int best_i = -1;
      for (int i = 0; i < static_cast<int>(prev.size()); ++i) {
        const double d = (prev[static_cast<std::size_t>(i)].xy() - start.xy()).norm();
        const double dh = std::abs(geometry::WrapAngle(prev[static_cast<std::size_t>(i)].heading -
                                                       start.heading));
        if (d < best_d && dh < kContinueHeading) {
          best_d = d;
          best_i = i;
        }
      }
      const TreePath& q = previous_->path;
      const double driven = options_.sample_spacing * (best_i + 1);
      if (best_i >= 0 && driven < q.length1 + q.length2 - options_.sample_spacing) {
        TreePath c;
        c.turn_index = -2;
        c.k1_index = -2;
        c.direction = 1;
        if (driven < q.length1) {
          c.k1 = q.k1;
          c.length1 = q.length1 - driven;
          c.k2 = q.k2;
          c.length2 = q.length2 + driven;
        } else {
          c.k1 = q.k2;
          c.length1 = q.length1 + q.length2 - driven;
          c.k2 = q.k2;
          c.length2 = driven;
        }
        paths.push_back(c);
      }
    }
    previous_.reset();
    // Cheap costs. `blind`: the cost-to-go reaches none of the tree (the rover in a pocket the
    // heading-blind configuration space closes, or the goal cut off): price blocked cells instead
    // of discarding them and end with the straight-line distance, so the checks still get ranked
    // candidates to decide on.
    const double check_to = request.drive_length > 0.0
                                ? std::min(request.drive_length, eval.distance_to_goal)
                                : eval.distance_to_goal;
    auto cost_all = [&](bool blind) {
      for (TreePath& p : paths) {
        double j = options_.turn_cost * std::abs(p.turn);
        if (p.turn_index == -2) j -= options_.commit_bonus;
        const std::vector<geometry::Pose2> poses = Samples(start, p);
        double s_prev = 0.0;
        bool reached = false;
        p.end_s = 0.0;
        p.entry_s = 0.0;
        for (std::size_t i = 0; i < poses.size() && std::isfinite(j); ++i) {
          const double s = std::min(p.length1 + p.length2, options_.sample_spacing * (i + 1.0));
          const double ds = s - s_prev;
          s_prev = s;
          const double k = s <= p.length1 + 1e-9 ? p.k1 : p.k2;
          double factor = field_.Factor(poses[i].xy());
          if (blind) factor = std::min(factor, kBlockedFactor);
          j += ds * (factor + options_.curvature_cost * std::abs(k));
          if ((poses[i].xy() - request.goal).squaredNorm() <= tol2) {
            // Priced to where it enters the goal's tolerance, but checked as far as the caller
            // drives it: the mobility manager's last step runs up to the goal's distance (a path
            // reaches no point farther than its arc length, so that covers the step).
            p.end_s = std::min(p.length1 + p.length2, std::max(s, check_to));
            p.entry_s = s;
            reached = true;
            break;
          }
        }
        if (!reached && std::isfinite(j) && !poses.empty()) {
          j += blind ? options_.unknown_cost_factor * (poses.back().xy() - request.goal).norm()
                     : field_.Cost(poses.back().xy());
        }
        p.cost = j;
      }
    };
    cost_all(false);
    if (std::none_of(paths.begin(), paths.end(),
                     [](const TreePath& p) { return std::isfinite(p.cost); })) {
      cost_all(true);
      last_.blind = true;
    }
    std::vector<int> order;
    for (int i = 0; i < static_cast<int>(paths.size()); ++i) {
      if (std::isfinite(paths[static_cast<std::size_t>(i)].cost)) order.push_back(i);
    }
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
      return paths[static_cast<std::size_t>(a)].cost < paths[static_cast<std::size_t>(b)].cost;
    });
    last_.ranked = static_cast<int>(order.size());
    eval.candidates_ranked = last_.ranked;

    // Backward arcs (a K-turn's first half), ranked by cost-to-go at their end: tried when no
    // forward path passes.
    std::vector<int> back;
    for (std::size_t a = 0; a < curvatures_.size(); ++a) {
      TreePath p;
      p.direction = -1;
      p.k1 = curvatures_[a];
      p.k1_index = static_cast<int>(a);
      p.turn_index = -1;
      p.length1 = options_.first_length;
      const std::vector<geometry::Pose2> poses = Samples(start, p);
      p.cost = poses.empty() ? kNoCost : field_.Cost(poses.back().xy()) + options_.first_length;
      if (std::isfinite(p.cost)) back.push_back(static_cast<int>(paths.size()));
      paths.push_back(p);
    }
    std::stable_sort(back.begin(), back.end(), [&](int a, int b) {
      return paths[static_cast<std::size_t>(a)].cost < paths[static_cast<std::size_t>(b)].cost;
    });

    // Clearance checks in rank order; a failed turn + first segment fails its whole subtree. If
    // nothing passes, once more with hazards near the rover's own footprint ignored (escape: the
    // map now says the rover stands beside a rock it was cleared to approach).
    for (const bool escape : {false, true}) {
      if (escape && !last_.routed && !options_.route_first) {
        try_route();
        if (last_.routed) break;
      }
      // Normally nothing is exempt. Escaping, the hazard cells the parts touch where the rover
      // stands (within escape_margin) are, but the path's first segment must leave them behind.
      const Exempt on = escape ? checker.Touching(start, options_.escape_margin) : Exempt{};
      std::map<std::pair<int, int>, std::string> failed_prefix;
      std::map<std::pair<int, int>, bool> passed_prefix;
      int budget = options_.max_checks;
      for (const int idx : order) {
        if (budget <= 0) break;
        TreePath& p = paths[static_cast<std::size_t>(idx)];
        const std::pair<int, int> key{p.turn_index, p.k1_index};
        if (auto it = failed_prefix.find(key); it != failed_prefix.end()) {
          p.checked = -1;
          p.why = it->second;
          continue;
        }
        budget -= 1;
        last_.checks += 1;
        checked.push_back(idx);
        if (!passed_prefix.count(key)) {
          TreePath prefix = p;
          prefix.length2 = 0.0;
          prefix.end_s = p.end_s > 0.0 ? std::min(p.end_s, p.length1) : p.length1;
          if (!CheckPath(checker, start, on, &prefix)) {
            if (Settle(checker, start, on, escape, &p)) {
              last_.chosen = idx;
              break;
            }
            failed_prefix[key] = prefix.why;
            p.checked = -1;
            p.why = prefix.why;
            continue;
          }
          passed_prefix[key] = true;
        }
        if (CheckPath(checker, start, on, &p) && (!escape || Clears(checker, start, on, &p))) {
          p.checked = 1;
          last_.chosen = idx;
          break;
        }
        if (Settle(checker, start, on, escape, &p)) {
          last_.chosen = idx;
          break;
        }
        p.checked = -1;
      }
      for (const int idx : back) {
        if (last_.chosen >= 0) break;
        TreePath& p = paths[static_cast<std::size_t>(idx)];
        last_.checks += 1;
        checked.push_back(idx);
        if (CheckPath(checker, start, on, &p) && (!escape || Clears(checker, start, on, &p))) {
          p.checked = 1;
          last_.chosen = idx;
          break;
        }
        p.checked = -1;
      }
      if (last_.chosen >= 0) {
        last_.escape = escape;
        break;
      }
    }
  }
  eval.clearance_checks = last_.checks;

  // Nothing passes: back along the last drive if the rover is still on it. The rover's own
  // parts swept that ground moments ago, so it is clear whatever the map now says (a rock
  // beside a wheel re-measured from nearer, a stereo artefact under it); from there the next
  // decision sees the spot from farther back.
  if (last_.chosen < 0) {
    if (std::optional<TreePath> r = Retrace(start)) {
      r->checked = 1;
      r->why = "retrace: back along the last drive";
      last_.retrace = true;
      last_.chosen = static_cast<int>(paths.size());
      paths.push_back(*r);
      checked.push_back(last_.chosen);
    }
  }
  // The arc this choice drives (after its turn, if any; the manager drives both before the next
  // decision). A retrace keeps the arc it backs along: offered again while the rover is on it,
  // it runs out where that arc began.
  if (last_.chosen >= 0 && !last_.retrace) {
    const TreePath& p = paths[static_cast<std::size_t>(last_.chosen)];
    last_drive_ = LastDrive{geometry::Turned(start, p.turn), p.k1, p.direction};
  }

  // The evaluation: the checked paths' first segments in rank order.
  double best = kNoCost;
  for (const int idx : checked) best = std::min(best, paths[static_cast<std::size_t>(idx)].cost);
  for (const int idx : checked) {
    const TreePath& p = paths[static_cast<std::size_t>(idx)];
    eval.candidates.push_back(FirstSegment(p));
    const bool ok = p.checked == 1;
    const int wp = p.cost > 0.0 && std::isfinite(best)
                       ? static_cast<int>(std::lround(255.0 * std::clamp(best / p.cost, 0.0, 1.0)))
                       : 255;
    eval.hazard.push_back({ok ? 255 : 0, 255});
    eval.waypoint.push_back({wp, 255});
    eval.merged.push_back({ok ? wp : 0, 255});
    eval.why.push_back(p.why);
    if (idx == last_.chosen) eval.chosen = static_cast<int>(eval.candidates.size()) - 1;
  }
  if (last_.chosen >= 0) {
    const TreePath& p = paths[static_cast<std::size_t>(last_.chosen)];
    if (p.turn != 0.0) {
      nav_core::Candidate t;
      t.kind = nav_core::MotionKind::kPointTurn;
      t.turn_angle = p.turn;
      eval.path.push_back(t);
    }
    nav_core::Candidate a;
    a.curvature = p.k1;
    a.direction = p.direction;
    a.length = p.length1;
    eval.path.push_back(a);
    if (p.length2 > 0.0) {
      a.curvature = p.k2;
      a.length = p.length2;
      eval.path.push_back(a);
    }
    // A path settled into the goal's tolerance is cleared no farther than it was checked; a
    // route step no farther than the route pose it aims at (often nearer than a drive length:
    // driven on, the rover passed the pose where the route turned).
    if (p.settled) eval.max_drive = p.end_s;
    if (last_.routed) eval.max_drive = p.length1;
    if (p.direction > 0 && !last_.escape) previous_ = Previous{start, p};
  }
  return eval;
}

}  // namespace rover::apl::enav
