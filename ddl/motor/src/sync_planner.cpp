#include "rover/ddl/motor/sync_planner.hpp"

#include <algorithm>
#include <cmath>

#include "rover/base/check.hpp"

namespace rover::ddl::motor {

double ProfileDuration(double d, double v, double a) {
  ROVER_DEMAND(d >= 0.0 && v > 0.0 && a > 0.0);
  if (d >= v * v / a) return d / v + v / a;
  return 2.0 * std::sqrt(d / a);
}

double ProfilePosition(double d, double v, double a, double t) {
  if (t <= 0.0 || d <= 0.0) return 0.0;
  double peak = v;
  double t_ramp = v / a;
  double t_cruise = (d - v * v / a) / v;
  if (t_cruise < 0.0) {  // triangle
    peak = std::sqrt(a * d);
    t_ramp = peak / a;
    t_cruise = 0.0;
  }
  const double total = 2.0 * t_ramp + t_cruise;
  if (t >= total) return d;
  if (t <= t_ramp) return 0.5 * a * t * t;
  const double ramp_dist = 0.5 * a * t_ramp * t_ramp;
  if (t <= t_ramp + t_cruise) return ramp_dist + peak * (t - t_ramp);
  const double tr = total - t;  // time left
  return d - 0.5 * a * tr * tr;
}

double RampPosition(double v, double a, double t) {
  if (t <= 0.0) return 0.0;
  const double t_ramp = v / a;
  if (t <= t_ramp) return 0.5 * a * t * t;
  return 0.5 * v * t_ramp + v * (t - t_ramp);
}

SyncPlan PlanSynchronisedMove(const std::vector<AxisMove>& axes) {
  SyncPlan plan;
  plan.rates.assign(axes.size(), 0.0);
  for (const AxisMove& m : axes) {
    plan.duration_s =
        std::max(plan.duration_s, ProfileDuration(m.distance, m.max_rate, m.acceleration));
  }
  const double t = plan.duration_s;
  for (std::size_t i = 0; i < axes.size(); ++i) {
    const AxisMove& m = axes[i];
    if (m.distance <= 0.0 || t <= 0.0) continue;
    const double disc =
        std::max(0.0, m.acceleration * m.acceleration * t * t - 4.0 * m.acceleration * m.distance);
    // Smaller root, written to avoid cancellation: v = 2 a d / (a T + sqrt(disc)).
    const double v = 2.0 * m.acceleration * m.distance / (m.acceleration * t + std::sqrt(disc));
    plan.rates[i] = std::min(v, m.max_rate);
  }
  return plan;
}

}  // namespace rover::ddl::motor
