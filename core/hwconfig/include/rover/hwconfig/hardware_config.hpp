#pragma once
/// @file
/// The rover's hardware description and nominal calibration, shared by the simulator's sensor
/// models (sim/sensors) and the device drivers (ddl/*) so that both sides agree on every count,
/// gain and mounting. Loaded from YAML through rover::ParamSet (deploy/config/
/// rover_hardware.yaml is the default file), so that errors name file:line:key.
///
/// Conventions. Angles in rad (the YAML uses *_deg keys where degrees read better), rates rad/s,
/// currents A, temperatures deg C. Joint angles follow ddl/JointState: steering + turns the
/// wheel's front left, rocker/bogie + raise the front, mast pan + left, tilt + up. Frames: rover
/// x forward, y left, z up. `a_from_b` rotations map vectors of frame b into frame a.
///
/// Encoders sit on the motor shaft behind a gearhead:
///   counts = angle * CountsPerRad(),  CountsPerRad() = counts_per_rev * gear_ratio / (2 pi).
/// Motor telemetry ADCs (12 bit):
///   current_adc = current_offset_counts + current_counts_per_amp * I
///   temperature_adc = temperature_offset_counts + temperature_counts_per_degc * T
/// Suspension potentiometers (12 bit):  adc = offset_counts[i] + gain_counts_per_rad[i] * angle.
/// IMU, per sensor (gyro in rad/s, accel in m/s^2), in the IMU case frame c:
///   raw * lsb = K x_c + bias,   K = (I + misalignment) diag(scale),   x_c = case_from_rover x_r
/// with `misalignment` a small matrix with zero diagonal (axis non-orthogonality, rad) and
/// rover_from_case = RotationFromRpy(mounting_rpy_deg). Noise: white noise density N
/// (per-sample sigma N sqrt(rate_hz)) and bias random walk K_b (bias variance K_b^2 t).
/// Sun sensor: pinhole with sensor frame x = detector columns, y = rows, z = boresight; a sun
/// direction s (sensor frame, s_z > 0) lands at
///   spot = focal_counts (s_x / s_z, s_y / s_z) + principal_point     [detector counts]
/// and is visible while the angle off the boresight is <= fov_deg.

#include <Eigen/Core>
#include <array>
#include <limits>
#include <string>

#include "rover/base/params.hpp"
#include "rover/base/status.hpp"
#include "rover/hwconfig/hw_bus.hpp"
#include "rover/hwconfig/rover_description.hpp"

namespace rover {

/// The kinds of actuator; each has one block of parameters in the YAML.
enum class MotorKind {
  kDrive,
  kSteer,
  kMastPan,
  kMastTilt,
  kArmAzimuth,
  kArmShoulder,
  kArmElbow,
  kArmWrist
};
/// Kind of motor index 0..15 (rover_hw.idl order). Precondition: 0 <= motor < 16.
MotorKind MotorKindOf(int motor);
/// "drive", "steer", "mast_pan", "mast_tilt", "arm_azimuth", "arm_shoulder", "arm_elbow",
/// "arm_wrist".
const char* MotorKindName(MotorKind kind);

/// One actuator: gearhead, encoder, motion limits, protection limits.
struct MotorSpec {
  double counts_per_rev = 64.0;   ///< encoder counts per motor-shaft turn (quadrature)
  double gear_ratio = 1500.0;     ///< motor turns per output turn
  double max_rate = 0.9;          ///< [rad/s] at the output; faster goals are rejected
  double default_rate = 0.5;      ///< [rad/s] rate limit of position goals when none is given
  double max_acceleration = 2.0;  ///< [rad/s^2] the controller's profile acceleration
  double min_angle = -std::numeric_limits<double>::infinity();  ///< [rad]; -inf for wheels
  double max_angle = std::numeric_limits<double>::infinity();   ///< [rad]; +inf for wheels
  double current_limit = 1.3;  ///< [A] the controller saturates here; over-current trips 15 % above
  double max_temperature = 110.0;     ///< [deg C] over-temperature trip level
  double position_tolerance = 0.005;  ///< [rad] "at goal" band used by the driver

  /// counts_per_rev * gear_ratio / (2 pi) [counts/rad].
  double CountsPerRad() const;
  /// True if min_angle/max_angle are finite (steering, mast).
  bool HasLimits() const;
};

/// Motor-controller telemetry board: rates and the current / temperature ADCs.
struct MotorTelemetrySpec {
  double rate_hz = 100.0;
  double current_counts_per_amp = 1000.0;     ///< [counts/A]
  double current_offset_counts = 20.0;        ///< [counts] at 0 A
  double temperature_counts_per_degc = 16.0;  ///< [counts/deg C]
  double temperature_offset_counts = 2048.0;  ///< [counts] at 0 deg C
  double adc_noise_counts = 1.0;              ///< [counts] 1-sigma ADC noise

  double CurrentFromCounts(double counts) const;
  double CountsFromCurrent(double amps) const;  ///< unclamped, unrounded
  double TemperatureFromCounts(double counts) const;
  double CountsFromTemperature(double degc) const;  ///< unclamped, unrounded
};

/// Rocker and bogie potentiometers (order hw::PotIndex).
struct PotSpec {
  double rate_hz = 50.0;
  std::array<double, hw::kNumPots> offset_counts{2048.0, 2048.0, 2048.0, 2048.0};  ///< at 0 rad
  /// [counts/rad]; negative for a pot mounted mirrored.
  std::array<double, hw::kNumPots> gain_counts_per_rad{690.0, -690.0, 690.0, -690.0};
  /// [rad] mechanical stops at +-limit (defaults: the rover description's).
  double rocker_limit = hwconfig::RoverDescription().rocker_limit;
  double bogie_limit = hwconfig::RoverDescription().bogie_limit;  ///< [rad]
  double noise_counts = 1.5;  ///< [counts] 1-sigma
  /// [rad] |left + right| rocker angle above this is inconsistent with the differential.
  double differential_tolerance = 0.03;

  double AngleFromCounts(int pot, double counts) const;
  double CountsFromAngle(int pot, double angle) const;  ///< unclamped, unrounded
  /// Mechanical limit of pot i (rocker_limit or bogie_limit).
  double Limit(int pot) const;
};

/// One inertial sensor triad (gyro or accelerometer) of the IMU.
struct InertialSensorSpec {
  double lsb = 1.0e-6;   ///< [rad/s or m/s^2 per LSB]
  double range = 17.45;  ///< [rad/s or m/s^2] full scale; beyond it the output saturates
  Eigen::Vector3d bias = Eigen::Vector3d::Zero();          ///< nominal bias, case frame
  Eigen::Vector3d scale = Eigen::Vector3d::Ones();         ///< scale factors (1 = ideal)
  Eigen::Matrix3d misalignment = Eigen::Matrix3d::Zero();  ///< zero diagonal, small [rad]
  double noise_density = 2.0e-5;                           ///< white noise [unit/sqrt(Hz)]
  double bias_random_walk = 5.0e-8;                        ///< [unit/sqrt(s)]

  /// K = (I + misalignment) diag(scale).
  Eigen::Matrix3d ScaleMisalignment() const;
  /// Per-sample white-noise sigma at `rate_hz`: noise_density sqrt(rate_hz).
  double SampleSigma(double rate_hz) const;
};

/// LN-200-like IMU.
struct ImuSpec {
  double rate_hz = 100.0;
  /// rover_from_case (the IMU case axes expressed in the rover frame).
  Eigen::Matrix3d rover_from_case = Eigen::Matrix3d::Identity();
  InertialSensorSpec gyro;
  InertialSensorSpec accel;
  double temperature_noise = 0.02;  ///< [deg C] 1-sigma

  ImuSpec();
};

/// Sun sensor (MER-like: a small camera behind a neutral-density filter, pointing up).
struct SunSensorSpec {
  double rate_hz = 2.0;
  /// rover_from_sensor (sensor axes in the rover frame: x columns, y rows, z boresight).
  Eigen::Matrix3d rover_from_sensor = Eigen::Matrix3d::Identity();
  double focal_counts = 2000.0;  ///< [detector counts per unit tangent]
  Eigen::Vector2d principal_point = Eigen::Vector2d::Zero();  ///< [counts] boresight spot
  double fov = 60.0 * 3.14159265358979323846 / 180.0;         ///< [rad] half angle of the cone
  double full_scale_intensity = 3500.0;  ///< [ADC counts] sun at the zenith on the boresight
  double min_intensity = 300.0;          ///< [ADC counts] dimmer spots are not the sun
  double spot_noise_counts = 0.5;        ///< [counts] 1-sigma centroid noise
  double intensity_noise_counts = 5.0;   ///< [ADC counts] 1-sigma

  SunSensorSpec();
  /// True if `spot` [counts] is within the field of view (angle off boresight <= fov).
  bool SpotInFieldOfView(double col, double row) const;
};

/// Everything about the hardware that the simulator and the drivers must agree on.
struct HardwareConfig {
  std::array<MotorSpec, hw::kNumMotors> motors;
  MotorTelemetrySpec telemetry;
  PotSpec pots;
  ImuSpec imu;
  SunSensorSpec sun_sensor;

  HardwareConfig();  ///< the defaults (same values as deploy/config/rover_hardware.yaml)
  /// Cross-field checks (finite, positive, min < max, default_rate <= max_rate, K
  /// invertible, offsets within the ADC, ...). Errors name the YAML key.
  Status Validate() const;
};

/// Defaults of each motor kind (drive: 1500:1, steer: 2500:1, mast: 1000:1, 64 counts/rev).
MotorSpec DefaultMotorSpec(MotorKind kind);

/// Declares every hardware parameter under `prefix` (e.g. "" or "hardware"): keys such as
/// `motors.drive.gear_ratio`, `pots.offset_counts`, `imu.gyro.bias`, `sun_sensor.fov_deg`.
/// Ranges are declared, so ParamSet::Validate() reports file:line:key for bad values.
void DeclareHardwareParams(ParamSet& params, const std::string& prefix = "");

/// Builds the config from parameters declared by DeclareHardwareParams (runs
/// params.Validate() and HardwareConfig::Validate(); errors carry file:line: key 'name').
Result<HardwareConfig> HardwareConfigFromParams(const ParamSet& params,
                                                const std::string& prefix = "");

/// Convenience: declare, load `path`, build. Errors name the file, line and key.
Result<HardwareConfig> LoadHardwareConfig(const std::string& path);

}  // namespace rover
