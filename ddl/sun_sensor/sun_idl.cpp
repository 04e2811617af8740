#include "sun_idl.hpp"

namespace rover::ddl {

static_assert(rover_HEALTH_OK == static_cast<int>(SensorHealth::kOk));
static_assert(rover_HEALTH_DEGRADED == static_cast<int>(SensorHealth::kDegraded));
static_assert(rover_HEALTH_FAILED == static_cast<int>(SensorHealth::kFailed));
static_assert(rover_HEALTH_STALE == static_cast<int>(SensorHealth::kStale));

hw::SunSensorRaw SunSensorRawFromIdl(const rover_hw_SunSensorRaw& in) {
  hw::SunSensorRaw r;
  r.stamp_ns = in.header.stamp_ns;
  r.spot = {in.spot[0], in.spot[1]};
  r.intensity = in.intensity;
  return r;
}

void SunSensorToIdl(const SunSensor& in, rover_ddl_SunSensor* out) {
  out->sun_vector = {in.sun_vector.x(), in.sun_vector.y(), in.sun_vector.z()};
  out->valid = in.valid;
  out->intensity = in.intensity;
  out->health = SunHealthToIdl(in.health);
}

rover_SensorHealth SunHealthToIdl(SensorHealth h) {
  return static_cast<rover_SensorHealth>(static_cast<int>(h));
}

}  // namespace rover::ddl
