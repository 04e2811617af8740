#include "rover/msg/health_idl.hpp"

#include "idl_enum.hpp"

namespace rover::msg {

static_assert(rover_HEALTH_OK == static_cast<int>(SensorHealth::kOk));
static_assert(rover_HEALTH_DEGRADED == static_cast<int>(SensorHealth::kDegraded));
static_assert(rover_HEALTH_FAILED == static_cast<int>(SensorHealth::kFailed));
static_assert(rover_HEALTH_STALE == static_cast<int>(SensorHealth::kStale));

rover_SensorHealth HealthToIdl(SensorHealth h) {
  return internal::EnumToIdl<rover_SensorHealth>(h);
}

Result<SensorHealth> HealthFromIdl(const rover_SensorHealth& h, std::string_view field) {
  return internal::EnumFromIdl<SensorHealth>(h, 4, field, "SensorHealth");
}

}  // namespace rover::msg
