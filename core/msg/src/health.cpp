#include "rover/msg/health.hpp"

#include "rover/base/format.hpp"

namespace rover::msg {
namespace {

int Severity(SensorHealth h) {
  switch (h) {
    case SensorHealth::kOk:
      return 0;
    case SensorHealth::kDegraded:
      return 1;
    case SensorHealth::kStale:
      return 2;
    case SensorHealth::kFailed:
      return 3;
  }
  return 3;
}

}  // namespace

const char* SensorHealthName(SensorHealth h) {
  switch (h) {
    case SensorHealth::kOk:
      return "ok";
    case SensorHealth::kDegraded:
      return "degraded";
    case SensorHealth::kFailed:
      return "failed";
    case SensorHealth::kStale:
      return "stale";
  }
  return "?";
}

SensorHealth WorseHealth(SensorHealth a, SensorHealth b) {
  return Severity(a) >= Severity(b) ? a : b;
}

HealthReport FreshnessReport(std::string_view topic, std::optional<Time> newest, Time now,
                             double max_age_s, std::string_view missing_suffix,
                             std::string_view stale_suffix) {
  if (!newest.has_value()) {
    return {SensorHealth::kDegraded,
            "no " + std::string(topic) + " received yet" + std::string(missing_suffix)};
  }
  const double age = ToSeconds(now - *newest);
  if (age > max_age_s) {
    return {SensorHealth::kDegraded, std::string(topic) + " is stale (" + FormatNumber(age) +
                                         " s old)" + std::string(stale_suffix)};
  }
  return {};
}

void HealthLatch::Latch(std::string_view problem, std::initializer_list<log::Field> fields,
                        std::initializer_list<std::string_view> detail_keys) {
  problem_ = std::string(problem);
  for (const log::Field& f : fields) {
    for (std::string_view k : detail_keys) {
      if (f.key == k) {
        problem_ += " " + f.key + "=" + f.value;
        break;
      }
    }
  }
}

HealthReport HealthLatch::Report(HealthReport otherwise) const {
  if (latched()) return {SensorHealth::kDegraded, problem_};
  return otherwise;
}

}  // namespace rover::msg
