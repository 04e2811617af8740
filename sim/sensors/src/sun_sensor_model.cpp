#include "rover/sim/sensors/sun_sensor_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rover/base/check.hpp"
#include "rover/geometry/transforms.hpp"
#include "rover/sim/sensors/motor_telemetry_model.hpp"

namespace rover::sim::sensors {

SunSensorModel::SunSensorModel(const SunSensorSpec& spec, const SunSensorErrors& errors,
                               double noise_scale, std::uint64_t seed)
    : spec_(spec), errors_(errors), noise_scale_(noise_scale), rng_(seed) {
  ROVER_DEMAND(noise_scale >= 0.0 && errors.optical_depth >= 0.0);
  rover_from_sensor_ =
      spec.rover_from_sensor * geometry::RotationFromRpy(errors.mounting_error_rpy);
}

bool SunSensorModel::SunVisible(const Eigen::Vector3d& sun_site,
                                const Eigen::Matrix3d& site_from_rover) const {
  const double n = sun_site.norm();
  if (!(n > 0.0) || !std::isfinite(n)) return false;
  const Eigen::Vector3d d = sun_site / n;
  if (d.z() <= 0.0) return false;  // below the horizon
  const Eigen::Vector3d s = rover_from_sensor_.transpose() * (site_from_rover.transpose() * d);
  return s.z() > 0.0 && s.z() >= std::cos(spec_.fov);
}

hw::SunSensorRaw SunSensorModel::Sample(const Eigen::Vector3d& sun_site,
                                        const Eigen::Matrix3d& site_from_rover, Time stamp) {
  hw::SunSensorRaw raw;
  raw.stamp_ns = stamp.ns;
  // Draw the noise every sample so that visibility does not shift the noise sequence.
  const double nx = rng_.Normal(noise_scale_ * spec_.spot_noise_counts);
  const double ny = rng_.Normal(noise_scale_ * spec_.spot_noise_counts);
  const double ni = rng_.Normal(noise_scale_ * spec_.intensity_noise_counts);
  if (!SunVisible(sun_site, site_from_rover)) return raw;

  const Eigen::Vector3d d = sun_site.normalized();
  const Eigen::Vector3d s = rover_from_sensor_.transpose() * (site_from_rover.transpose() * d);
  const double f = spec_.focal_counts * (1.0 + errors_.focal_error);
  const Eigen::Vector2d pp = spec_.principal_point + errors_.principal_point_error;
  constexpr double kLo = std::numeric_limits<std::int16_t>::min();
  constexpr double kHi = std::numeric_limits<std::int16_t>::max();
  const double col = std::clamp(std::round(f * s.x() / s.z() + pp.x() + nx), kLo, kHi);
  const double row = std::clamp(std::round(f * s.y() / s.z() + pp.y() + ny), kLo, kHi);
  raw.spot = {static_cast<std::int16_t>(col), static_cast<std::int16_t>(row)};
  const double airmass = 1.0 / std::max(d.z(), 0.05);  // d.z = sin(elevation)
  const double intensity =
      spec_.full_scale_intensity * s.z() * std::exp(-errors_.optical_depth * (airmass - 1.0));
  raw.intensity = ToAdc12(intensity + ni);
  return raw;
}

}  // namespace rover::sim::sensors
