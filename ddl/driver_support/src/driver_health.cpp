#include "rover/ddl/driver_support/driver_health.hpp"

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"

namespace rover::ddl::driver_support {
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
    return OutOfRange(name_ + ": sample stamped " + FormatNumber(Time{stamp_ns}.seconds(), 3) +
                      " s is more than " + FormatNumber(max_future_s_, 3) +
                      " s ahead of the run clock (" + FormatNumber(now.seconds(), 3) + " s)");
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
  if (Stale(now))
    return name_ + ": no sample for more than " + FormatNumber(stale_after_s_, 3) + " s";
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
