#pragma once
/// @file
/// Sun sensor: sun direction (site frame) and rover attitude -> hw/sun_sensor spot centroid and
/// intensity.
///
/// With the TRUE mounting rover_from_sensor_true = rover_from_sensor R(mounting_error), the sun
/// direction in the sensor frame is s = sensor_from_rover_true rover_from_site d_site. The sun is
/// seen if it is above the horizon (d_site.z > 0) and within the field of view
/// (angle(s, z) <= fov). Then (pinhole, focal f_true = focal_counts (1 + focal_error)):
///   spot      = round(f_true (s_x / s_z, s_y / s_z) + pp + pp_error + N(0, (k sigma_spot)^2))
///   intensity = round(I_fs cos(angle(s, z)) exp(-tau (m - 1)) + N(0, (k sigma_I)^2)),
///   m = 1 / max(sin(elevation), 0.05)  (airmass, capped), clamped to the 12-bit ADC
/// with tau the atmospheric dust optical depth and k = noise_scale. Not seen: spot (0, 0),
/// intensity 0. A driver decides validity from the intensity (dust can make it too dim).

#include <Eigen/Core>
#include <cstdint>

#include "rover/base/time.hpp"
#include "rover/hwconfig/hardware_config.hpp"
#include "rover/sim/sensors/sampling.hpp"

namespace rover::sim::sensors {

struct SunSensorErrors {
  Eigen::Vector3d mounting_error_rpy = Eigen::Vector3d::Zero();     ///< [rad]
  Eigen::Vector2d principal_point_error = Eigen::Vector2d::Zero();  ///< [counts]
  double focal_error = 0.0;                                         ///< relative
  double optical_depth = 0.5;  ///< tau, dust optical depth (0.3 clear .. 5 global dust storm)
};

class SunSensorModel {
 public:
  /// Preconditions: spec valid, noise_scale >= 0, optical_depth >= 0.
  SunSensorModel(const SunSensorSpec& spec, const SunSensorErrors& errors, double noise_scale,
                 std::uint64_t seed);

  /// `sun_site`: direction to the sun in the site frame (any length > 0);
  /// `site_from_rover`: the rover's attitude.
  hw::SunSensorRaw Sample(const Eigen::Vector3d& sun_site, const Eigen::Matrix3d& site_from_rover,
                          Time stamp);

  /// True if the sun would be seen (above the horizon and within the FOV), noise aside.
  bool SunVisible(const Eigen::Vector3d& sun_site, const Eigen::Matrix3d& site_from_rover) const;
  const Eigen::Matrix3d& TrueRoverFromSensor() const { return rover_from_sensor_; }

 private:
  SunSensorSpec spec_;
  SunSensorErrors errors_;
  double noise_scale_;
  Eigen::Matrix3d rover_from_sensor_;
  NoiseRng rng_;
};

}  // namespace rover::sim::sensors
