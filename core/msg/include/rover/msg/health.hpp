#pragma once
/// @file
/// The health of a sensor or a derived quantity (idl/rover_common.idl SensorHealth), carried by
/// ddl/* samples and by every heartbeat on sys/health.

#include <cstdint>

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

}  // namespace rover::msg
