#include "rover/sim/judge/passability.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <numbers>
#include <queue>
#include <utility>

#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::sim::judge {

namespace {
constexpr double kMaxStates = 4e7;
constexpr double kBin = 1.0;  // [m] rock bins for the collision test
}  // namespace

Status PassabilityQuery::Validate() const {
  if (!start.allFinite()) return InvalidArgument("passability.start: not finite");
  if (!goal.allFinite()) return InvalidArgument("passability.goal: not finite");
  if (!area_min.allFinite() || !area_max.allFinite()) {
    return InvalidArgument("passability.area: not finite");
  }
  ROVER_RETURN_IF_ERROR(CheckRange("passability.start_yaw", start_yaw, -100.0, 100.0, "rad"));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("passability.tolerance", tolerance, "m"));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("passability.margin", margin, "m"));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("passability.traversable_height", traversable_height, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("passability.cell", cell, 0.02, 1.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("passability.headings", headings, 4, 360));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("passability.turn_cost", turn_cost, "m"));
  const Eigen::Vector2d size = area_max - area_min;
  if (!(size.x() >= cell && size.y() >= cell)) {
    return InvalidArgument("passability.area: " + FormatNumber(size.x()) + " x " +
                           FormatNumber(size.y()) + " m is less than one cell (" +
                           FormatNumber(cell) + " m) across");
  }
  const double states = std::floor(size.x() / cell) * std::floor(size.y() / cell) * headings;
  if (states > kMaxStates) {
    return InvalidArgument("passability.area: " + FormatNumber(states) +
                           " lattice states, more than " + FormatNumber(kMaxStates) +
                           " (a coarser cell or a smaller area)");
  }
  return Status::Ok();
}

Result<std::optional<double>> ContactFreePathLength(const std::vector<JudgeRock>& rocks,
                                                    const RoverFootprint& footprint,
                                                    const PassabilityQuery& q) {
  ROVER_RETURN_IF_ERROR(q.Validate());
  const int nx = static_cast<int>(std::floor((q.area_max.x() - q.area_min.x()) / q.cell));
  const int ny = static_cast<int>(std::floor((q.area_max.y() - q.area_min.y()) / q.cell));
  const int nk = q.headings;

  // The blocking rocks, binned for the collision test.
  const int bx = static_cast<int>(std::ceil((q.area_max.x() - q.area_min.x()) / kBin)) + 1;
  const int by = static_cast<int>(std::ceil((q.area_max.y() - q.area_min.y()) / kBin)) + 1;
  std::vector<std::vector<const JudgeRock*>> bins(static_cast<std::size_t>(bx) * by);
  double max_reach = 0.0;
  for (const JudgeRock& r : rocks) {
    if (r.height <= q.traversable_height) continue;
    const int ix = static_cast<int>(std::floor((r.xy.x() - q.area_min.x()) / kBin));
    const int iy = static_cast<int>(std::floor((r.xy.y() - q.area_min.y()) / kBin));
    if (ix < 0 || iy < 0 || ix >= bx || iy >= by) continue;
    max_reach = std::max(max_reach, r.Reach());
    bins[static_cast<std::size_t>(iy) * bx + ix].push_back(&r);
  }
  hwconfig::ContactPart ground;  // the whole ground-footprint rectangle
  ground.min = footprint.body_min;
  ground.max = footprint.body_max;
  const double reach = std::max(footprint.body_min.norm(), footprint.body_max.norm()) + q.margin +
                       max_reach;

  auto index = [&](int ix, int iy, int k) {
    return (static_cast<std::size_t>(iy) * nx + ix) * nk + static_cast<std::size_t>(k);
  };
  auto centre = [&](int ix, int iy) {
    return Eigen::Vector2d(q.area_min.x() + (ix + 0.5) * q.cell,
                           q.area_min.y() + (iy + 0.5) * q.cell);
  };
  auto heading = [&](int k) { return 2.0 * std::numbers::pi * k / nk; };
  // -1 unknown, 0 blocked, 1 free.
  std::vector<std::int8_t> state(static_cast<std::size_t>(nx) * ny * nk, -1);
  auto touches = [&](const JudgeRock& rock, const Eigen::Matrix2d& rot, const Eigen::Vector2d& p) {
    if (q.rectangle) return RockTouches(rock, rot, p, ground, q.margin);
    for (const hwconfig::ContactPart& part : footprint.parts) {
      if (rock.height > footprint.ClearanceOf(part) && RockTouches(rock, rot, p, part, q.margin)) {
        return true;
      }
    }
    return false;
  };
  auto is_free = [&](int ix, int iy, int k) {
    std::int8_t& s = state[index(ix, iy, k)];
    if (s >= 0) return s == 1;
    const Eigen::Vector2d p = centre(ix, iy);
    const Eigen::Matrix2d rot = Eigen::Rotation2Dd(heading(k)).toRotationMatrix();
    const int x0 = std::max(0, static_cast<int>(std::floor((p.x() - reach - q.area_min.x()) / kBin)));
    const int x1 = std::min(bx - 1, static_cast<int>(std::floor((p.x() + reach - q.area_min.x()) / kBin)));
    const int y0 = std::max(0, static_cast<int>(std::floor((p.y() - reach - q.area_min.y()) / kBin)));
    const int y1 = std::min(by - 1, static_cast<int>(std::floor((p.y() + reach - q.area_min.y()) / kBin)));
    bool free = true;
    for (int y = y0; free && y <= y1; ++y) {
      for (int x = x0; free && x <= x1; ++x) {
        for (const JudgeRock* rock : bins[static_cast<std::size_t>(y) * bx + x]) {
          if (touches(*rock, rot, p)) {
            free = false;
            break;
          }
        }
      }
    }
    s = free ? 1 : 0;
    return free;
  };
  auto cell_of = [&](const Eigen::Vector2d& p, int* ix, int* iy) {
    *ix = static_cast<int>(std::floor((p.x() - q.area_min.x()) / q.cell));
    *iy = static_cast<int>(std::floor((p.y() - q.area_min.y()) / q.cell));
    return *ix >= 0 && *iy >= 0 && *ix < nx && *iy < ny;
  };

  int sx = 0, sy = 0;
  if (!cell_of(q.start, &sx, &sy)) return std::optional<double>();
  int sk = static_cast<int>(std::lround(q.start_yaw / (2.0 * std::numbers::pi) * nk)) % nk;
  if (sk < 0) sk += nk;
  if (!is_free(sx, sy, sk)) return std::optional<double>();

  std::vector<float> dist(state.size(), std::numeric_limits<float>::infinity());
  using Item = std::pair<float, std::size_t>;
  std::priority_queue<Item, std::vector<Item>, std::greater<>> open;
  dist[index(sx, sy, sk)] = 0.0F;
  open.push({0.0F, index(sx, sy, sk)});
  const auto turn = static_cast<float>(q.turn_cost);
  while (!open.empty()) {
    const auto [d, i] = open.top();
    open.pop();
    if (d > dist[i]) continue;
    const int k = static_cast<int>(i % static_cast<std::size_t>(nk));
    const int ix = static_cast<int>((i / static_cast<std::size_t>(nk)) % static_cast<std::size_t>(nx));
    const int iy = static_cast<int>(i / static_cast<std::size_t>(nk) / static_cast<std::size_t>(nx));
    const Eigen::Vector2d p = centre(ix, iy);
    if ((p - q.goal).norm() <= q.tolerance) return std::optional<double>(static_cast<double>(d));
    auto relax = [&](int jx, int jy, int jk, float cost) {
      if (jx < 0 || jy < 0 || jx >= nx || jy >= ny || !is_free(jx, jy, jk)) return;
      const std::size_t j = index(jx, jy, jk);
      if (d + cost < dist[j]) {
        dist[j] = d + cost;
        open.push({d + cost, j});
      }
    };
    relax(ix, iy, (k + 1) % nk, turn);
    relax(ix, iy, (k + nk - 1) % nk, turn);
    const Eigen::Vector2d step = q.cell * Eigen::Vector2d(std::cos(heading(k)), std::sin(heading(k)));
    for (const Eigen::Vector2d& n : {Eigen::Vector2d(p + step), Eigen::Vector2d(p - step)}) {
      int jx = 0, jy = 0;
      if (!cell_of(n, &jx, &jy) || (jx == ix && jy == iy)) continue;
      relax(jx, jy, k, static_cast<float>((centre(jx, jy) - p).norm()));
    }
  }
  return std::optional<double>();
}

}  // namespace rover::sim::judge
