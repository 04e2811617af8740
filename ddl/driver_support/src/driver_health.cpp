#include "rover/ddl/driver_support/driver_health.hpp"

#include <cstdio>

#include "rover/base/check.hpp"

namespace rover::ddl::driver_support {
namespace {
std::string Num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}
}  // namespace

InputMonitor::InputMonitor(std::string name, double stale_after_s, double max_future_s)
    : name_(std::move(name)), stale_after_s_(stale_after_s), max_future_s_(max_future_s) {
  ROVER_DEMAND(stale_after_s > 0.0 && max_future_s > 0.0);
}

Status InputMonitor::Accept(std::int64_t stamp_ns, Time now, bool clock_valid) {
  if (stamp_ns < 0) {
    ++rejected_;
    return OutOfRange(name_ + ": sample stamped " + std::to_string(stamp_ns) + " ns (negative)");
  }
  if (clock_valid && ToSeconds(Time{stamp_ns} - now) > max_future_s_) {
    ++rejected_;
    return OutOfRange(name_ + ": sample stamped " + Num(Time{stamp_ns}.seconds()) +
                      " s is more than " + Num(max_future_s_) + " s ahead of the run clock (" +
                      Num(now.seconds()) + " s)");
  }
  last_arrival_ = now;
  ++accepted_;
  return Status::Ok();
}

bool InputMonitor::Stale(Time now) const {
  return !last_arrival_ || ToSeconds(now - *last_arrival_) > stale_after_s_;
}

std::string InputMonitor::StaleReason(Time now) const {
  if (!last_arrival_) return name_ + ": no sample yet";
  if (Stale(now)) return name_ + ": no sample for more than " + Num(stale_after_s_) + " s";
  return "";
}

bool ClockJumpDetector::WentBack(Time now, bool clock_valid) {
  if (!clock_valid) return false;
  const bool back = last_ && now < *last_;
  last_ = now;
  return back;
}

void HealthSummary::Worsen(msg::SensorHealth h, const std::string& why) {
  if (msg::WorseHealth(health, h) != health) {
    health = h;
    reason = why;
  }
}

}  // namespace rover::ddl::driver_support
