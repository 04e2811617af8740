#include "imu_idl.hpp"

namespace rover::ddl {

static_assert(rover_HEALTH_OK == static_cast<int>(SensorHealth::kOk));
static_assert(rover_HEALTH_DEGRADED == static_cast<int>(SensorHealth::kDegraded));
static_assert(rover_HEALTH_FAILED == static_cast<int>(SensorHealth::kFailed));
static_assert(rover_HEALTH_STALE == static_cast<int>(SensorHealth::kStale));

hw::ImuRaw ImuRawFromIdl(const rover_hw_ImuRaw& in) {
  hw::ImuRaw r;
  r.stamp_ns = in.header.stamp_ns;
  for (std::size_t i = 0; i < 3; ++i) {
    r.gyro[i] = in.gyro[i];
    r.accel[i] = in.accel[i];
  }
  r.temperature = in.temperature;
  r.status = in.status;
  return r;
}

void ImuToIdl(const Imu& in, rover_ddl_Imu* out) {
  out->angular_velocity = {in.angular_velocity.x(), in.angular_velocity.y(),
                           in.angular_velocity.z()};
  out->linear_acceleration = {in.linear_acceleration.x(), in.linear_acceleration.y(),
                              in.linear_acceleration.z()};
  out->temperature = in.temperature;
  out->health = ImuHealthToIdl(in.health);
}

rover_SensorHealth ImuHealthToIdl(SensorHealth h) {
  return static_cast<rover_SensorHealth>(static_cast<int>(h));
}

}  // namespace rover::ddl
