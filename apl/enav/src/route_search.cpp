#include "rover/apl/enav/route_search.hpp"

#include <algorithm>
#include <cmath>
#include <queue>
#include <utility>

namespace rover::apl::enav {
namespace {

// Cell offsets of the 16 lattice headings, counter-clockwise from the start's heading.
constexpr int kDi[RouteSearch::kHeadings] = {1, 2, 1, 1, 0, -1, -1, -2, -1, -2, -1, -1, 0, 1, 1, 2};
constexpr int kDj[RouteSearch::kHeadings] = {0, 1, 1, 2, 1, 2, 1, 1, 0, -1, -1, -2, -1, -2, -1, -1};
constexpr std::uint8_t kTested = 1, kAllowed = 2, kClosed = 4;
constexpr double kRoomSlack = 1e-6;  // [m] a pose as near a hazard as the start is allowed

}  // namespace

double NeededRoom(const RouteSearchOptions& options, double start_room, double distance) {
  if (distance > options.near_start) return options.margin;
  return std::min(options.margin, start_room - kRoomSlack);
}

double RouteSearch::Heading(int h) {
  return std::atan2(static_cast<double>(kDj[h]), static_cast<double>(kDi[h]));
}

std::optional<Route> RouteSearch::Search(const HeightTerrain& terrain, const CostToGoField& field,
                                         const geometry::Pose2& start,
                                         const Eigen::Vector2d& goal, double tolerance,
                                         const RouteSearchOptions& options) const {
  const nav_core::HeightMap& m = *terrain.height_map();
  const ClearanceChecker checker(terrain);
  // The lattice: the map's cell count and size, centred on the rover and turned to its heading.
  const int w = m.width, hgt = m.height;
  const int i0 = w / 2, j0 = hgt / 2;
  const double c = m.resolution;
  const Eigen::Vector2d ex(std::cos(start.heading), std::sin(start.heading));
  const Eigen::Vector2d ey(-ex.y(), ex.x());
  const std::size_t n = static_cast<std::size_t>(w) * hgt * kHeadings;
  g_.assign(n, std::numeric_limits<float>::infinity());
  parent_.assign(n, -1);
  state_.assign(n, 0);
  double heading[kHeadings], length[kHeadings], turn[kHeadings];
  for (int h = 0; h < kHeadings; ++h) {
    heading[h] = geometry::WrapAngle(start.heading + Heading(h));
    length[h] = c * std::hypot(kDi[h], kDj[h]);
  }
  for (int h = 0; h < kHeadings; ++h) {
    turn[h] = std::abs(geometry::WrapAngle(Heading((h + 1) % kHeadings) - Heading(h)));
  }
  auto centre = [&](int i, int j) -> Eigen::Vector2d {
    return start.xy() + (c * (i - i0)) * ex + (c * (j - j0)) * ey;
  };
  auto index = [&](int i, int j, int h) {
    return (static_cast<std::size_t>(j) * w + i) * kHeadings + static_cast<std::size_t>(h);
  };
  auto pose_of = [&](std::size_t s) {
    const int h = static_cast<int>(s % kHeadings);
    const std::size_t k = s / kHeadings;
    const Eigen::Vector2d xy = centre(static_cast<int>(k % w), static_cast<int>(k / w));
    return geometry::Pose2{xy.x(), xy.y(), heading[h]};
  };
  const double start_room = checker.Room(start);
  auto fits = [&](const geometry::Pose2& p) {
    return checker.Room(p) > NeededRoom(options, start_room, (p.xy() - start.xy()).norm());
  };
  auto allowed = [&](std::size_t s) {
    std::uint8_t& st = state_[s];
    if ((st & kTested) == 0) {
      st |= kTested;
      if (fits(pose_of(s))) st |= kAllowed;
    }
    return (st & kAllowed) != 0;
  };
  auto map_cell = [&](const Eigen::Vector2d& xy, int* i, int* j) {
    m.CellOf(xy.x(), xy.y(), i, j);
    return m.Contains(*i, *j);
  };
  int gi = 0, gj = 0;
  const bool goal_on_map = map_cell(goal, &gi, &gj);
  const double tol2 = tolerance * tolerance;
  auto terminal = [&](int i, int j) {
    const Eigen::Vector2d xy = centre(i, j);
    if (goal_on_map) return (xy - goal).squaredNorm() <= tol2;
    int mi = 0, mj = 0;
    if (!map_cell(xy, &mi, &mj)) return true;
    return mi <= 1 || mj <= 1 || mi >= w - 2 || mj >= hgt - 2;
  };

  const double h0 = field.Cost(start.xy());
  if (!std::isfinite(h0)) return std::nullopt;
  // The rover stands at the start: it is allowed unless its parts touch a hazard there.
  if (!(start_room > 0.0)) return std::nullopt;
  using Item = std::pair<float, std::size_t>;  // f, pose
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  const std::size_t s0 = index(i0, j0, 0);
  state_[s0] = kTested | kAllowed;
  g_[s0] = 0.0F;
  open.push({static_cast<float>(h0), s0});
  Route route;
  std::optional<std::size_t> end;
  while (!open.empty() && route.expansions < options.max_expansions) {
    const auto [f, s] = open.top();
    open.pop();
    if ((state_[s] & kClosed) != 0) continue;
    state_[s] |= kClosed;
    route.expansions += 1;
    const int h = static_cast<int>(s % kHeadings);
    const std::size_t k = s / kHeadings;
    const int i = static_cast<int>(k % w), j = static_cast<int>(k / w);
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
      if (ni < 0 || nj < 0 || ni >= w || nj >= hgt) continue;
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
      if (!fits(geometry::Turned(p, 0.5 * (dh == 1 ? angle : -angle)))) continue;
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
  route.nodes.front().pose = start;  // the same pose, without the lattice's rounding
  return route;
}

}  // namespace rover::apl::enav
