#pragma once
/// @file
/// Options of the simulated sensors: the seed, a global noise scale, the TRUE-vs-NOMINAL
/// calibration errors (the drivers only know the nominal HardwareConfig, so these are what
/// calibration and estimation have to cope with) and the site/season for the sun.
/// Declared as parameters under a prefix (default "sensors") for the simulator's YAML.

#include <cstdint>
#include <string>

#include "rover/base/params.hpp"
#include "rover/base/status.hpp"
#include "rover/sim/sensors/imu_model.hpp"
#include "rover/geometry/mars_sun.hpp"
#include "rover/sim/sensors/motor_telemetry_model.hpp"
#include "rover/sim/sensors/pot_model.hpp"
#include "rover/sim/sensors/sun_sensor_model.hpp"

namespace rover::sim::sensors {

struct SimSensorOptions {
  std::uint64_t seed = 1;
  double noise_scale = 1.0;  ///< multiplies every white-noise and random-walk sigma; 0 = none
  ImuErrors imu;
  PotErrors pots;
  MotorTelemetryErrors motors;
  SunSensorErrors sun_sensor;
  geometry::SunEphemerisOptions ephemeris;

  SimSensorOptions();  ///< small realistic errors (see sim/sensors/README.md)
  /// No errors, no noise, clear sky: hw values are the ideal quantised ones.
  static SimSensorOptions Ideal();
  /// Finite values, noise_scale >= 0, sigmas >= 0, optical depth >= 0, ephemeris valid.
  Status Validate() const;
};

/// Declares keys `<prefix>.seed`, `<prefix>.noise_scale`, `<prefix>.imu.gyro_bias_error`, ...,
/// `<prefix>.ephemeris.mode` (see README.md for the list).
void DeclareSimSensorParams(ParamSet& params, const std::string& prefix = "sensors");
/// Reads them back (runs params.Validate(); errors name file:line: key).
Result<SimSensorOptions> SimSensorOptionsFromParams(const ParamSet& params,
                                                    const std::string& prefix = "sensors");

}  // namespace rover::sim::sensors
