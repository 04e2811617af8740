#include "rover/dl/smoke/heading_integrator.hpp"

#include <cmath>
#include <numbers>
#include <string>

namespace rover::dl::smoke {

Status HeadingIntegrator::Add(Time t, double yaw_rate) {
  if (!std::isfinite(yaw_rate)) return InvalidArgument("yaw rate is not finite");
  if (samples_ > 0) {
    if (t <= last_) {
      return InvalidArgument("sample stamped " + std::to_string(t.ns) +
                             " ns is not after the previous one (" + std::to_string(last_.ns) +
                             " ns)");
    }
    const Duration dt = t - last_;
    if (dt > max_gap_) {
      last_ = t;  // restart integration from here
      return OutOfRange("gap of " + std::to_string(ToSeconds(dt)) + " s between samples");
    }
    heading_ = std::remainder(heading_ + yaw_rate * ToSeconds(dt), 2.0 * std::numbers::pi);
  }
  last_ = t;
  ++samples_;
  return Status::Ok();
}

}  // namespace rover::dl::smoke
