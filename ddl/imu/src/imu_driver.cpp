#include "rover/ddl/imu/imu_driver.hpp"

#include <Eigen/LU>
#include <cmath>

namespace rover::ddl::imu {

Result<ImuDriver> ImuDriver::Create(const ImuSpec& spec) {
  HardwareConfig c;
  c.imu = spec;
  ROVER_RETURN_IF_ERROR(c.Validate().WithPrefix("imu spec"));
  return ImuDriver(spec);
}

ImuDriver::ImuDriver(const ImuSpec& spec) : spec_(spec) {
  gyro_map_ = spec.rover_from_case * spec.gyro.ScaleMisalignment().inverse();
  accel_map_ = spec.rover_from_case * spec.accel.ScaleMisalignment().inverse();
}

Imu ImuDriver::Convert(const hw::ImuRaw& raw) const {
  Imu out;
  out.stamp = Time{raw.stamp_ns};
  Eigen::Vector3d g, a;
  for (int i = 0; i < 3; ++i) {
    g[i] = raw.gyro[static_cast<std::size_t>(i)] * spec_.gyro.lsb;
    a[i] = raw.accel[static_cast<std::size_t>(i)] * spec_.accel.lsb;
  }
  out.angular_velocity = gyro_map_ * (g - spec_.gyro.bias);
  out.linear_acceleration = accel_map_ * (a - spec_.accel.bias);
  out.temperature = raw.temperature * hw::kImuTemperatureLsb;

  const char* axes = "xyz";
  if (raw.status & hw::kImuSelfTestFail) {
    out.health = msg::SensorHealth::kFailed;
    out.health_reason = "IMU self-test failed";
    return out;
  }
  for (int i = 0; i < 3; ++i) {
    // One LSB of slack for rounding at full scale.
    if (std::abs(g[i]) > spec_.gyro.range + spec_.gyro.lsb) {
      out.health = msg::SensorHealth::kFailed;
      out.health_reason = std::string("gyro ") + axes[i] + " reads beyond full scale";
      return out;
    }
    if (std::abs(a[i]) > spec_.accel.range + spec_.accel.lsb) {
      out.health = msg::SensorHealth::kFailed;
      out.health_reason = std::string("accelerometer ") + axes[i] + " reads beyond full scale";
      return out;
    }
  }
  if (raw.status & (hw::kImuGyroSaturated | hw::kImuAccelSaturated)) {
    out.health = msg::SensorHealth::kDegraded;
    out.health_reason =
        (raw.status & hw::kImuGyroSaturated) ? "gyro saturated" : "accelerometer saturated";
  }
  return out;
}

}  // namespace rover::ddl::imu
