#include "rover/apl/enav/route_search.hpp"

#include <algorithm>
#include <cmath>
#include <queue>
#include <utility>

namespace rover::apl::enav {
namespace {

constexpr int kHeadings = 16;
// Cell offsets of the 16 lattice headings, counter-clockwise from +x.
constexpr int kDi[kHeadings] = {1, 2, 1, 1, 0, -1, -1, -2, -1, -2, -1, -1, 0, 1, 1, 2};
constexpr int kDj[kHeadings] = {0, 1, 1, 2, 1, 2, 1, 1, 0, -1, -1, -2, -1, -2, -1, -1};
constexpr std::uint8_t kTested = 1, kAllowed = 2, kClosed = 4;

}  // namespace

double RouteSearch::Heading(int h) {
  return std::atan2(static_cast<double>(kDj[h]), static_cast<double>(kDi[h]));
}

int RouteSearch::NearestHeading(double heading) {
  int best = 0;
  double best_d = 10.0;
  for (int h = 0; h < kHeadings; ++h) {
    const double d = std::abs(geometry::WrapAngle(heading - Heading(h)));
    if (d < best_d) {
      best_d = d;
      best = h;
    }
  }
  return best;
}

std::optional<Route> RouteSearch::Search(const HeightTerrain& terrain, const CostToGoField& field,
                                         const geometry::Pose2& start,
                                         const Eigen::Vector2d& goal, double tolerance,
                                         const RouteSearchOptions& options) const {
  const nav_core::HeightMap& m = *terrain.height_map();
  const ClearanceChecker checker(terrain);
  const int w = m.width, hgt = m.height;
  const std::size_t n = static_cast<std::size_t>(w) * hgt * kHeadings;
  g_.assign(n, std::numeric_limits<float>::infinity());
  parent_.assign(n, -1);
  state_.assign(n, 0);
  double heading[kHeadings], length[kHeadings], turn[kHeadings];
  for (int h = 0; h < kHeadings; ++h) {
    heading[h] = Heading(h);
    length[h] = m.resolution * std::hypot(kDi[h], kDj[h]);
  }
  for (int h = 0; h < kHeadings; ++h) {
    turn[h] = std::abs(geometry::WrapAngle(heading[(h + 1) % kHeadings] - heading[h]));
  }
  auto centre = [&](int i, int j) { return m.CellCenter(i, j); };
  auto index = [&](int i, int j, int h) {
    return (static_cast<std::size_t>(j) * w + i) * kHeadings + static_cast<std::size_t>(h);
  };
  auto pose_of = [&](std::size_t s) {
    const int h = static_cast<int>(s % kHeadings);
    const std::size_t c = s / kHeadings;
    const Eigen::Vector2d xy = centre(static_cast<int>(c % w), static_cast<int>(c / w));
    return geometry::Pose2{xy.x(), xy.y(), heading[h]};
  };
  auto allowed = [&](std::size_t s) {
    std::uint8_t& st = state_[s];
    if ((st & kTested) == 0) {
      st |= kTested;
      if (checker.Fits(pose_of(s), options.margin)) st |= kAllowed;
    }
    return (st & kAllowed) != 0;
  };
  const bool goal_on_map = [&] {
    int i = 0, j = 0;
    m.CellOf(goal.x(), goal.y(), &i, &j);
    return m.Contains(i, j);
  }();
  const double tol2 = tolerance * tolerance;
  auto terminal = [&](int i, int j) {
    if (goal_on_map) return (centre(i, j) - goal).squaredNorm() <= tol2;
    return i <= 1 || j <= 1 || i >= w - 2 || j >= hgt - 2;
  };

  int si = 0, sj = 0;
  m.CellOf(start.x, start.y, &si, &sj);
  if (!m.Contains(si, sj)) return std::nullopt;
  const double h0 = field.Cost(centre(si, sj));
  if (!std::isfinite(h0)) return std::nullopt;
  // The start: its cell at the two lattice headings either side of the rover's, each at the
  // price of turning to it. The rover stands there, so they are allowed whatever the map says
  // with the route's margin (a heading snapped by up to 13 deg swings the corner wheels up to
  // 0.2 m) unless its parts do not fit even at its exact pose with no margin.
  if (!checker.Fits(start, 0.0)) return std::nullopt;
  using Item = std::pair<float, std::size_t>;  // f, pose
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  const int hn = NearestHeading(start.heading);
  const int other = geometry::WrapAngle(start.heading - heading[hn]) >= 0.0
                        ? (hn + 1) % kHeadings
                        : (hn + kHeadings - 1) % kHeadings;
  for (const int h : {hn, other}) {
    const std::size_t s0 = index(si, sj, h);
    state_[s0] = kTested | kAllowed;
    g_[s0] = static_cast<float>(
        options.turn_cost * std::abs(geometry::WrapAngle(heading[h] - start.heading)));
    open.push({g_[s0] + static_cast<float>(h0), s0});
  }
  Route route;
  std::optional<std::size_t> end;
  while (!open.empty() && route.expansions < options.max_expansions) {
    const auto [f, s] = open.top();
    open.pop();
    if ((state_[s] & kClosed) != 0) continue;
    state_[s] |= kClosed;
    route.expansions += 1;
    const int h = static_cast<int>(s % kHeadings);
    const std::size_t c = s / kHeadings;
    const int i = static_cast<int>(c % w), j = static_cast<int>(c / w);
    if (terminal(i, j)) {
      end = s;
      route.cost = f;
      break;
    }
    const float g = g_[s];
    auto relax = [&](std::size_t t, double step_cost, double h_cost) {
      if (!std::isfinite(step_cost) || !std::isfinite(h_cost)) return;
      const float ng = g + static_cast<float>(step_cost);
      if (ng >= g_[t] || (state_[t] & kClosed) != 0) return;
      g_[t] = ng;
      parent_[t] = static_cast<std::int32_t>(s);
      open.push({ng + static_cast<float>(h_cost), t});
    };
    // Straight moves, forward and backward.
    for (const int dir : {1, -1}) {
      const int ni = i + dir * kDi[h], nj = j + dir * kDj[h];
      if (!m.Contains(ni, nj)) continue;
      const std::size_t t = index(ni, nj, h);
      if ((state_[t] & kClosed) != 0 || !allowed(t)) continue;
      const Eigen::Vector2d xy = centre(ni, nj);
      const double cost = length[h] * field.Factor(xy) * (dir > 0 ? 1.0 : options.backward_factor);
      relax(t, cost, field.Cost(xy));
    }
    // Turns in place to the next heading either way (allowed also halfway).
    for (const int dh : {1, kHeadings - 1}) {
      const int nh = (h + dh) % kHeadings;
      const std::size_t t = index(i, j, nh);
      if ((state_[t] & kClosed) != 0 || !allowed(t)) continue;
      const double angle = dh == 1 ? turn[h] : turn[nh];
      const geometry::Pose2 p = pose_of(s);
      if (!checker.Fits(geometry::Turned(p, 0.5 * (dh == 1 ? angle : -angle)), options.margin)) {
        continue;
      }
      relax(t, options.turn_cost * angle, field.Cost(p.xy()));
    }
  }
  if (!end) return std::nullopt;
  route.at_goal = goal_on_map;
  std::vector<RouteNode> back;
  for (std::int64_t s = static_cast<std::int64_t>(*end); s >= 0;
       s = parent_[static_cast<std::size_t>(s)]) {
    RouteNode node;
    node.pose = pose_of(static_cast<std::size_t>(s));
    node.g = g_[static_cast<std::size_t>(s)];
    const std::int32_t p = parent_[static_cast<std::size_t>(s)];
    if (p >= 0) {
      const std::size_t pc = static_cast<std::size_t>(p) / kHeadings;
      if (pc == static_cast<std::size_t>(s) / kHeadings) {
        node.move = 0;
      } else {
        const Eigen::Vector2d d = node.pose.xy() - pose_of(static_cast<std::size_t>(p)).xy();
        node.move = d.x() * std::cos(node.pose.heading) + d.y() * std::sin(node.pose.heading) > 0
                        ? 1
                        : -1;
      }
    }
    back.push_back(node);
  }
  route.nodes.assign(back.rbegin(), back.rend());
  return route;
}

}  // namespace rover::apl::enav
