#pragma once
/// @file
/// Sun-sensor driver: hw/sun_sensor spot centroid [detector counts] and intensity [ADC counts]
/// -> ddl/sun_sensor unit sun vector in the rover frame, with the nominal SunSensorSpec:
///   s_sensor = normalise((col - pp_x) / f, (row - pp_y) / f, 1),  sun = rover_from_sensor s_sensor
///   intensity = min(1, adc / full_scale_intensity)
/// valid = adc >= min_intensity and the spot lies within the field of view. When not valid the
/// sun vector is zero. Health: FAILED if a bright spot lies outside the field of view (no
/// optics can put it there: a detector or data fault); OK otherwise (no sun is not a fault).

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "rover/base/status.hpp"
#include "rover/hwconfig/hardware_config.hpp"
#include "rover/msg/sensors.hpp"

namespace rover::ddl::sun_sensor {

/// ddl/sun_sensor (rover/msg/sensors.hpp) and why it is not valid or not OK.
struct SunSensor : msg::SunSensor {
  std::string reason;  ///< why not valid / not OK (not in the IDL; for logs)
};

class SunSensorDriver {
 public:
  /// Errors: invalid spec.
  static Result<SunSensorDriver> Create(const SunSensorSpec& spec);
  SunSensor Convert(const hw::SunSensorRaw& raw) const;
  const SunSensorSpec& spec() const { return spec_; }

 private:
  explicit SunSensorDriver(const SunSensorSpec& spec) : spec_(spec) {}
  SunSensorSpec spec_;
};

}  // namespace rover::ddl::sun_sensor
