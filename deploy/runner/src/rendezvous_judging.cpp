#include "rover/deploy/runner/rendezvous_judging.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>

#include "rover/base/units.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::deploy::runner {
namespace {

// Index of the truth track point nearest in time to t (the track is sorted by time).
std::size_t NearestTrackIndex(const RunResult& r, double t) {
  const auto& tr = r.truth_track;
  const auto it = std::lower_bound(tr.begin(), tr.end(), t,
                                   [](const std::array<double, 3>& p, double v) { return p[0] < v; });
  if (it == tr.end()) return tr.size() - 1;
  const std::size_t i = static_cast<std::size_t>(it - tr.begin());
  if (i > 0 && std::abs(tr[i - 1][0] - t) < std::abs(tr[i][0] - t)) return i - 1;
  return i;
}

sim::judge::Criterion Figure(std::string name, double v, std::string unit, std::string detail) {
  return {std::move(name), v, 0.0, std::move(unit), true, std::move(detail)};
}

}  // namespace

double TrueLanderDistance(const sim::terrain::Lander& lander, double x, double y) {
  return std::hypot(x - lander.params.x, y - lander.params.y);
}

std::vector<sim::judge::Criterion> RendezvousFigures(const RendezvousLog& log,
                                                     const sim::terrain::Lander& lander,
                                                     const std::vector<sim::terrain::Rock>& rocks,
                                                     const RunResult& result) {
  std::vector<sim::judge::Criterion> out;
  if (result.truth_track.empty()) return out;
  // Distance estimates at seed 004's checkpoints.
  for (double d : {15.0, 25.0, 35.0, 45.0}) {
    double best_gap = 3.0, err = std::numeric_limits<double>::quiet_NaN(), truth = 0.0;
    for (const RendezvousSample& s : log.samples) {
      if (!(s.range > 0.0) || !s.new_range) continue;
      const auto& p = result.truth_track[NearestTrackIndex(result, s.t)];
      const double true_d = TrueLanderDistance(lander, p[1], p[2]);
      if (std::abs(true_d - d) < best_gap) {
        best_gap = std::abs(true_d - d);
        err = 100.0 * std::abs(s.range - true_d) / true_d;
        truth = true_d;
      }
    }
    if (std::isfinite(err)) {
      char detail[128];
      std::snprintf(detail, sizeof detail,
                    "|estimate - truth| / truth of the sighting nearest %.0f m (true %.2f m)", d,
                    truth);
      char name[32];
      std::snprintf(name, sizeof name, "range_error_%.0fm", d);
      out.push_back(Figure(name, err, "%", detail));
    }
  }
  // Placement at the ramp base.
  if (log.at_base_t && log.ramp >= 0 && log.ramp <= 1) {
    const sim::terrain::LanderRamp& ramp = lander.ramps[static_cast<std::size_t>(log.ramp)];
    const Eigen::Vector2d a = -ramp.direction.normalized();
    const Eigen::Vector2d n(-a.y(), a.x());
    const Eigen::Vector2d goal = ramp.bottom_center.head<2>() - log.standoff * a;
    const std::size_t i = NearestTrackIndex(result, *log.at_base_t);
    const auto& p = result.truth_track[i];
    const Eigen::Vector2d d = Eigen::Vector2d(p[1], p[2]) - goal;
    const std::string where = "true rover origin against ramp " + std::to_string(log.ramp) +
                              "'s foot less the standoff, at AT_RAMP_BASE";
    out.push_back(Figure("placement_lateral", 100.0 * std::abs(d.dot(n)), "cm", where));
    out.push_back(Figure("placement_longitudinal", 100.0 * std::abs(d.dot(a)), "cm", where));
    if (i < result.truth_yaw.size()) {
      const double h = geometry::WrapAngle(result.truth_yaw[i] - std::atan2(a.y(), a.x()));
      out.push_back(Figure("placement_heading", std::abs(h) / kDegree, "deg", where));
    }
  }
  // Acquisition and distractors (long range). A sighting drives the rover towards the estimate
  // it leaves: toward a distractor when, seen from the rover's true position, the estimate's
  // direction falls within a layered outcrop's angular radius and outside the lander's (deck
  // and ramps). A range error along the right bearing is not a distractor.
  const Eigen::Vector2d deck(lander.params.x, lander.params.y);
  const double lander_reach = lander.params.Description().Apothem() + lander.params.ramp_length;
  int toward = 0;
  std::optional<double> acquired_at;
  const auto angle = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return std::abs(std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b)));
  };
  for (const RendezvousSample& s : log.samples) {
    if (!s.new_range) continue;
    const auto& p = result.truth_track[NearestTrackIndex(result, s.t)];
    const Eigen::Vector2d rover(p[1], p[2]);
    if (!acquired_at) acquired_at = TrueLanderDistance(lander, p[1], p[2]);
    const Eigen::Vector2d dir = s.target - rover;
    const Eigen::Vector2d to_lander = deck - rover;
    if (dir.norm() < 1e-6 || to_lander.norm() <= lander_reach) continue;
    if (angle(dir, to_lander) <= std::asin(lander_reach / to_lander.norm())) continue;
    for (const sim::terrain::Rock& r : rocks) {
      if (r.layers <= 0) continue;
      const Eigen::Vector2d to_rock = r.position.head<2>() - rover;
      const double radius = sim::terrain::RockBoundingRadius(r) + 0.5;
      if (to_rock.norm() <= radius || angle(dir, to_rock) <= std::asin(radius / to_rock.norm())) {
        ++toward;
        break;
      }
    }
  }
  if (acquired_at) {
    out.push_back(Figure("acquired_at_m", *acquired_at, "m",
                         "true distance to the deck centre at the first sighting accepted"));
  }
  out.push_back(Figure("toward_distractor", toward, "count",
                       "sightings after which the estimate's direction from the rover pointed at "
                       "a layered outcrop and not at the lander"));
  const auto& last = result.truth_track.back();
  const bool on_deck = lander.InDeck(last[1], last[2]);
  out.push_back(Figure("on_deck", on_deck ? 1.0 : 0.0, "count",
                       "1 when the last sim/truth point is inside the deck hexagon"));
  return out;
}

}  // namespace rover::deploy::runner
