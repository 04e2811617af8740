#pragma once
/// @file
/// Parameters shared by the DDL driver services: the hardware calibration (core/hwconfig) and
/// the lookup of configuration files named by a parameter.
///
/// Hardware calibration. Every driver declares the keys of DeclareHardwareParams under the
/// prefix "hardware" (`hardware.motors.drive.gear_ratio`, `hardware.imu.gyro.lsb`, ...; defaults
/// = deploy/config/rover_hardware.yaml, so a service without parameter files agrees with the
/// simulator's defaults) and one more key, `hardware_file`: the path of a file in the layout of
/// deploy/config/rover_hardware.yaml (top-level `motors`, `pots`, `imu`, `sun_sensor`). Either
/// source may be used, not both: setting `hardware_file` and any `hardware.*` key is a
/// configuration error that names the key and where it was set.
///
/// Config files. A relative path is looked up in the working directory first, then under
/// $ROVER_SOURCE_DIR (set by roverctl's tests; the repository root), so that the documented
/// defaults (`deploy/config/...`) work from the repository root and in the container
/// (WORKDIR = the source tree), and last in an installed tree: `deploy/config/x.yaml` is
/// `<prefix>/share/rover/config/x.yaml` next to `<prefix>/bin/<service>`.

#include <string>

#include "rover/base/params.hpp"
#include "rover/base/status.hpp"
#include "rover/hwconfig/hardware_config.hpp"

namespace rover::ddl::driver_support {

/// Prefix of the hardware keys in a driver's parameters.
inline constexpr const char* kHardwarePrefix = "hardware";

/// Declares `hardware.*` (rover::DeclareHardwareParams) and `hardware_file`.
void DeclareDriverHardwareParams(ParamSet& params);

/// The hardware calibration from `hardware_file` (when not empty) or from `hardware.*`.
/// Errors: both given (names the first explicitly set `hardware.*` key and its origin), the
/// file missing, or any error of LoadHardwareConfig / HardwareConfigFromParams (file:line: key).
Result<HardwareConfig> DriverHardwareConfig(const ParamSet& params);

/// Resolves a configuration file path as described in the file comment. NotFound names every
/// path tried.
Result<std::string> ResolveConfigFile(const std::string& path);

}  // namespace rover::ddl::driver_support
