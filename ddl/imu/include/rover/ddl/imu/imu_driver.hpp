#pragma once
/// @file
/// IMU driver: hw/imu raw LSB (IMU case frame) -> ddl/imu in SI units in the rover frame, with
/// the nominal calibration of ImuSpec (the inverse of its measurement model):
///   x_rover = rover_from_case K^-1 (raw lsb - bias),   K = (I + misalignment) diag(scale)
/// for the gyro (rad/s) and the accelerometer (m/s^2, specific force: +g up at rest);
/// temperature = raw 0.01 deg C.
/// Health: FAILED if the self-test bit is set or an axis reads beyond full scale (corrupt
/// sample); DEGRADED if a saturation bit is set (that triad's value is clipped); else OK.

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "rover/base/status.hpp"
#include "rover/hwconfig/hardware_config.hpp"
#include "rover/msg/sensors.hpp"

namespace rover::ddl::imu {

/// ddl/imu (rover/msg/sensors.hpp) and why its health is not OK.
struct Imu : msg::Imu {
  std::string health_reason;  ///< empty when kOk (not in the IDL; for logs)
};

class ImuDriver {
 public:
  /// Errors: invalid spec (singular K, non-rotation mounting, bad lsb).
  static Result<ImuDriver> Create(const ImuSpec& spec);
  Imu Convert(const hw::ImuRaw& raw) const;
  const ImuSpec& spec() const { return spec_; }

 private:
  explicit ImuDriver(const ImuSpec& spec);
  ImuSpec spec_;
  Eigen::Matrix3d gyro_map_, accel_map_;  // rover_from_case K^-1
};

}  // namespace rover::ddl::imu
