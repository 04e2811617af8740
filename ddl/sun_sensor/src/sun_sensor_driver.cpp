#include "rover/ddl/sun_sensor/sun_sensor_driver.hpp"

#include <algorithm>
#include <cmath>

namespace rover::ddl::sun_sensor {

Result<SunSensorDriver> SunSensorDriver::Create(const SunSensorSpec& spec) {
  HardwareConfig c;
  c.sun_sensor = spec;
  ROVER_RETURN_IF_ERROR(c.Validate().WithPrefix("sun sensor spec"));
  return SunSensorDriver(spec);
}

SunSensor SunSensorDriver::Convert(const hw::SunSensorRaw& raw) const {
  SunSensor out;
  out.stamp = Time{raw.stamp_ns};
  out.intensity = std::clamp(raw.intensity / spec_.full_scale_intensity, 0.0, 1.0);
  const double col = raw.spot[0], row = raw.spot[1];
  if (raw.intensity < spec_.min_intensity) {
    out.reason = raw.intensity == 0 ? "no sun in the field of view" : "spot too dim";
    return out;
  }
  // Allow half a count of rounding at the edge of the field of view.
  const double tx = (std::abs(col - spec_.principal_point.x()) - 0.5) / spec_.focal_counts;
  const double ty = (std::abs(row - spec_.principal_point.y()) - 0.5) / spec_.focal_counts;
  if (std::atan(std::hypot(std::max(tx, 0.0), std::max(ty, 0.0))) > spec_.fov) {
    out.health = msg::SensorHealth::kFailed;
    out.reason = "bright spot outside the field of view";
    return out;
  }
  const Eigen::Vector3d s((col - spec_.principal_point.x()) / spec_.focal_counts,
                          (row - spec_.principal_point.y()) / spec_.focal_counts, 1.0);
  out.sun_vector = spec_.rover_from_sensor * s.normalized();
  out.valid = true;
  return out;
}

}  // namespace rover::ddl::sun_sensor
