#include "rover/apl/roaman/waypoint_fit.hpp"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>
#include <nlopt.hpp>
#include <numbers>
#include <utility>

namespace rover::apl::roaman {

namespace {

double Wrap(double t) {
  while (t > std::numbers::pi) t -= 2.0 * std::numbers::pi;
  while (t <= -std::numbers::pi) t += 2.0 * std::numbers::pi;
  return t;
}

}  // namespace

double TurnAngle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d u = b - a, v = c - b;
  return Wrap(std::atan2(v.y(), v.x()) - std::atan2(u.y(), u.x()));
}

bool TurnSafe(const PlanningGrid& grid, const Footprint& footprint, const Eigen::Vector2d& a,
              const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return grid.ClearanceAt(b) >= footprint.TurnClearance(TurnAngle(a, b, c));
}

std::vector<Leg> MakeLegs(const std::vector<Eigen::Vector2d>& waypoints) {
  std::vector<Leg> legs;
  for (std::size_t k = 1; k < waypoints.size(); ++k) {
    Leg l;
    l.from = waypoints[k - 1];
    l.to = waypoints[k];
    const Eigen::Vector2d d = l.to - l.from;
    l.length = d.norm();
    l.heading = std::atan2(d.y(), d.x());
    if (!legs.empty()) l.turn = Wrap(l.heading - legs.back().heading);
    legs.push_back(l);
  }
  return legs;
}

std::vector<Eigen::Vector2d> SamplePath(const std::vector<Eigen::Vector2d>& vertices, double step,
                                        std::vector<int>* vertex_index) {
  std::vector<Eigen::Vector2d> out;
  vertex_index->clear();
  for (std::size_t k = 0; k < vertices.size(); ++k) {
    if (k > 0) {
      const Eigen::Vector2d a = vertices[k - 1], b = vertices[k];
      const int n = std::max(1, static_cast<int>(std::ceil((b - a).norm() / step)));
      for (int s = 1; s < n; ++s) out.push_back(a + (b - a) * (static_cast<double>(s) / n));
    }
    vertex_index->push_back(static_cast<int>(out.size()));
    out.push_back(vertices[k]);
  }
  return out;
}

std::vector<int> SelectWaypoints(const PlanningGrid& grid,
                                 const std::vector<Eigen::Vector2d>& vertices, double tolerance,
                                 const Footprint& footprint) {
  const double leg_clearance = footprint.leg_clearance();
  const int n = static_cast<int>(vertices.size());
  if (n <= 2) {
    std::vector<int> all;
    for (int k = 0; k < n; ++k) all.push_back(k);
    return all;
  }
  std::vector<int> index;
  const std::vector<Eigen::Vector2d> points = SamplePath(vertices, grid.cell, &index);
  std::vector<std::uint8_t> keep(static_cast<std::size_t>(n), 0);
  keep.front() = keep.back() = 1;
  std::vector<std::pair<int, int>> stack{{0, n - 1}};
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    if (b - a < 2) continue;
    const Eigen::Vector2d& pa = vertices[static_cast<std::size_t>(a)];
    const Eigen::Vector2d& pb = vertices[static_cast<std::size_t>(b)];
    double worst = 0.0;
    for (int k = index[static_cast<std::size_t>(a)]; k <= index[static_cast<std::size_t>(b)]; ++k) {
      worst = std::max(worst, DistanceToSegment(points[static_cast<std::size_t>(k)], pa, pb));
    }
    if (worst <= tolerance && grid.SegmentClear(pa, pb, leg_clearance)) continue;
    int split = (a + b) / 2;
    if (worst > tolerance) {
      double far = -1.0;
      for (int m = a + 1; m < b; ++m) {
        const double d = DistanceToSegment(vertices[static_cast<std::size_t>(m)], pa, pb);
        if (d > far) {
          far = d;
          split = m;
        }
      }
    }
    keep[static_cast<std::size_t>(split)] = 1;
    stack.emplace_back(a, split);
    stack.emplace_back(split, b);
  }
  // Turn repair: a waypoint whose turn is not safe gets back the vertices between its
  // neighbours (the full path's turns are safe, so this ends).
  while (true) {
    std::vector<int> kept;
    for (int k = 0; k < n; ++k) {
      if (keep[static_cast<std::size_t>(k)]) kept.push_back(k);
    }
    bool changed = false;
    for (std::size_t m = 1; m + 1 < kept.size(); ++m) {
      const auto v = [&](std::size_t q) { return vertices[static_cast<std::size_t>(kept[q])]; };
      if (TurnSafe(grid, footprint, v(m - 1), v(m), v(m + 1))) continue;
      for (int k = kept[m - 1] + 1; k < kept[m + 1]; ++k) {
        if (!keep[static_cast<std::size_t>(k)]) {
          keep[static_cast<std::size_t>(k)] = 1;
          changed = true;
        }
      }
    }
    if (!changed) return kept;
  }
}

double FitError(const std::vector<Eigen::Vector2d>& points,
                const std::vector<Eigen::Vector2d>& waypoints) {
  double e = 0.0;
  for (const Eigen::Vector2d& p : points) {
    double d = std::numeric_limits<double>::infinity();
    for (std::size_t k = 1; k < waypoints.size(); ++k) {
      d = std::min(d, DistanceToSegment(p, waypoints[k - 1], waypoints[k]));
    }
    if (waypoints.size() == 1) d = (p - waypoints.front()).norm();
    e += d * d;
  }
  return e;
}

bool PolylineSafe(const PlanningGrid& grid, const std::vector<Eigen::Vector2d>& waypoints,
                  const Footprint& footprint) {
  for (std::size_t k = 1; k + 1 < waypoints.size(); ++k) {
    if (!TurnSafe(grid, footprint, waypoints[k - 1], waypoints[k], waypoints[k + 1])) return false;
  }
  for (std::size_t k = 1; k < waypoints.size(); ++k) {
    if (!grid.SegmentClear(waypoints[k - 1], waypoints[k], footprint.leg_clearance())) return false;
  }
  return true;
}

namespace {

struct FitData {
  const PlanningGrid* grid = nullptr;
  const std::vector<Eigen::Vector2d>* points = nullptr;
  std::vector<Eigen::Vector2d> waypoints;  // the ends fixed, interior from x
  Footprint footprint;
  double best_error = std::numeric_limits<double>::infinity();
  std::vector<Eigen::Vector2d> best;
  int evaluations = 0;

  void Load(const double* x) {
    for (std::size_t k = 1; k + 1 < waypoints.size(); ++k) {
      waypoints[k] = {x[2 * (k - 1)], x[2 * (k - 1) + 1]};
    }
  }
};

double Objective(unsigned n, const double* x, double* grad, void* data) {
  (void)n;
  (void)grad;  // COBYLA is derivative-free
  auto* d = static_cast<FitData*>(data);
  d->Load(x);
  ++d->evaluations;
  const double e = FitError(*d->points, d->waypoints);
  if (e < d->best_error && PolylineSafe(*d->grid, d->waypoints, d->footprint)) {
    d->best_error = e;
    d->best = d->waypoints;
  }
  return e;
}

// c_l = leg_clearance - min clearance under leg l (legs first), then c = TurnClearance(turn) -
// clearance at each interior waypoint; feasible when all are <= 0.
void Constraints(unsigned m, double* result, unsigned n, const double* x, double* grad,
                 void* data) {
  (void)m;
  (void)n;
  (void)grad;
  auto* d = static_cast<FitData*>(data);
  d->Load(x);
  const std::size_t legs = d->waypoints.size() - 1;
  for (std::size_t k = 0; k < legs; ++k) {
    result[k] = d->footprint.leg_clearance() -
                d->grid->MinClearanceAlong(d->waypoints[k], d->waypoints[k + 1]);
  }
  const std::vector<Eigen::Vector2d>& w = d->waypoints;
  for (std::size_t k = 1; k < legs; ++k) {
    result[legs + k - 1] = d->footprint.TurnClearance(TurnAngle(w[k - 1], w[k], w[k + 1])) -
                           d->grid->ClearanceAt(w[k]);
  }
}

}  // namespace

FitResult FitWaypoints(const PlanningGrid& grid, const std::vector<Eigen::Vector2d>& points,
                       const std::vector<Eigen::Vector2d>& initial, const Footprint& footprint,
                       int max_evaluations) {
  FitResult r;
  r.waypoints = initial;
  r.error_before = r.error_after = FitError(points, initial);
  if (initial.size() < 3) {
    r.outcome = "no interior waypoint to fit";
    return r;
  }
  if (max_evaluations <= 0) {
    r.outcome = "fit disabled (fit_max_evaluations = 0)";
    return r;
  }
  FitData data;
  data.grid = &grid;
  data.points = &points;
  data.waypoints = initial;
  data.footprint = footprint;
  data.best_error = r.error_before;
  data.best = initial;
  const unsigned n = static_cast<unsigned>(2 * (initial.size() - 2));
  const unsigned m = static_cast<unsigned>(2 * initial.size() - 3);  // legs + interior
  std::vector<double> x(n);
  for (std::size_t k = 1; k + 1 < initial.size(); ++k) {
    x[2 * (k - 1)] = initial[k].x();
    x[2 * (k - 1) + 1] = initial[k].y();
  }
  try {
    nlopt::opt opt(nlopt::LN_COBYLA, n);
    opt.set_min_objective(Objective, &data);
    opt.add_inequality_mconstraint(Constraints, &data, std::vector<double>(m, 1e-9));
    opt.set_maxeval(max_evaluations);
    opt.set_xtol_abs(0.05 * grid.cell);
    opt.set_initial_step(2.0 * grid.cell);
    double value = 0.0;
    const nlopt::result res = opt.optimize(x, value);
    switch (res) {
      case nlopt::SUCCESS:
        r.outcome = "success";
        break;
      case nlopt::XTOL_REACHED:
        r.outcome = "xtol reached";
        break;
      case nlopt::MAXEVAL_REACHED:
        r.outcome = "maxeval reached";
        break;
      default:
        r.outcome = "nlopt result " + std::to_string(static_cast<int>(res));
    }
  } catch (const std::exception& e) {
    r.outcome = std::string("nlopt stopped: ") + e.what();
  }
  r.evaluations = data.evaluations;
  r.waypoints = data.best;
  r.error_after = data.best_error;
  return r;
}

}  // namespace rover::apl::roaman
