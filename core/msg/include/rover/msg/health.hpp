#pragma once
/// @file
/// The health of a sensor or a derived quantity (idl/rover_common.idl SensorHealth), carried by
/// ddl/* samples and by every heartbeat on sys/health, and HealthLatch: the "last problem until
/// the next success" bookkeeping of a service's heartbeat health.

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

#include "rover/base/log.hpp"
#include "rover/base/time.hpp"

namespace rover::msg {

/// Same ordinals as the IDL enum.
enum class SensorHealth : std::uint8_t {
  kOk = 0,        ///< within range and fresh
  kDegraded = 1,  ///< usable with care (e.g. saturated axis, low signal)
  kFailed = 2,    ///< do not use
  kStale = 3,     ///< the source stopped updating
};

/// "ok", "degraded", "failed", "stale" ("?" for a value no enumerator has).
const char* SensorHealthName(SensorHealth h);

/// The worse of two health values: kFailed > kStale > kDegraded > kOk.
SensorHealth WorseHealth(SensorHealth a, SensorHealth b);

/// Whether a sample of this health may be used (OK or DEGRADED; FAILED and STALE may not).
constexpr bool IsUsable(SensorHealth h) {
  return h == SensorHealth::kOk || h == SensorHealth::kDegraded;
}

/// A health value and its reason, as a heartbeat carries them.
struct HealthReport {
  SensorHealth health = SensorHealth::kOk;
  std::string reason;  ///< empty when kOk

  friend bool operator==(const HealthReport&, const HealthReport&) = default;
};

/// What an input's freshness says at `now`: DEGRADED "no <topic> received yet<missing_suffix>"
/// without a sample, DEGRADED "<topic> is stale (<age> s old)<stale_suffix>" when the newest
/// sample is more than `max_age_s` old, else OK.
HealthReport FreshnessReport(std::string_view topic, std::optional<Time> newest, Time now,
                             double max_age_s, std::string_view missing_suffix = "",
                             std::string_view stale_suffix = "");

/// A service's latched problem: once something went wrong (a bad frame, an unanswered request)
/// the service reports DEGRADED with that reason until its next success clears it, so that an
/// operator sees the problem even though the service kept running.
class HealthLatch {
 public:
  /// Latches `problem`, followed by " key=value" for every field (of the warning that reported
  /// it) whose key is one of `detail_keys`, in the order of `fields`.
  void Latch(std::string_view problem, std::initializer_list<log::Field> fields = {},
             std::initializer_list<std::string_view> detail_keys = {});
  /// The next success: nothing is latched any more.
  void Clear() { problem_.clear(); }

  bool latched() const { return !problem_.empty(); }
  /// The latched text ("" when none).
  const std::string& problem() const { return problem_; }
  /// DEGRADED with the latched problem if there is one, else `otherwise` (what the service's
  /// inputs say, e.g. a stale input).
  HealthReport Report(HealthReport otherwise = {}) const;

 private:
  std::string problem_;
};

}  // namespace rover::msg
