#include "rover/hwconfig/hardware_config.hpp"

#include <Eigen/LU>
#include <cmath>
#include <cstdio>
#include <vector>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/key_checker.hpp"
#include "rover/base/units.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover {
namespace {

constexpr MotorKind kKinds[] = {MotorKind::kDrive,      MotorKind::kSteer,
                                MotorKind::kMastPan,    MotorKind::kMastTilt,
                                MotorKind::kArmAzimuth, MotorKind::kArmShoulder,
                                MotorKind::kArmElbow,   MotorKind::kArmWrist};

std::string Join(const std::string& prefix, const std::string& key) {
  return prefix.empty() ? key : prefix + "." + key;
}

void CheckInertial(KeyChecker& c, const std::string& base, const InertialSensorSpec& s) {
  c.Positive(base + ".lsb", s.lsb);
  c.Positive(base + ".range", s.range);
  if (c.ok() && s.range / s.lsb >= 2147483647.0) {
    c.Fail(base + ".range",
           FormatNumber(s.range) + " is not representable in int32 LSB of " + FormatNumber(s.lsb));
  }
  for (int i = 0; i < 3; ++i) {
    c.Finite(base + ".bias", s.bias[i]);
    c.InRange(base + ".scale", s.scale[i], 0.5, 1.5);
    c.Finite(base + ".misalignment", s.misalignment(i, i));
    if (s.misalignment(i, i) != 0.0) {
      c.Fail(base + ".misalignment", "diagonal element " + std::to_string(i) + " is " +
                                         FormatNumber(s.misalignment(i, i)) +
                                         "; must be 0 (scale factors go in 'scale')");
    }
  }
  for (int i = 0; i < 9; ++i)
    c.InRange(base + ".misalignment", s.misalignment(i / 3, i % 3), -0.1, 0.1);
  c.AtLeast(base + ".noise_density", s.noise_density, 0.0);
  c.AtLeast(base + ".bias_random_walk", s.bias_random_walk, 0.0);
}

bool IsRotation(const Eigen::Matrix3d& r) {
  return r.allFinite() && (r * r.transpose() - Eigen::Matrix3d::Identity()).norm() < 1e-6 &&
         r.determinant() > 0.0;
}

Eigen::Vector3d Vec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }
std::vector<double> List(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }
std::vector<double> List(const Eigen::Matrix3d& m) {
  std::vector<double> out;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) out.push_back(m(r, c));
  }
  return out;
}
Eigen::Matrix3d Mat3(const std::vector<double>& v) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = v[static_cast<std::size_t>(i)];
  return m;
}

// Roll, pitch, yaw [deg] of a rotation (for declaring defaults).
std::vector<double> RpyDeg(const Eigen::Matrix3d& r) {
  const Eigen::Vector3d rpy = geometry::RpyFromRotation(r) / kDegree;
  return {rpy[0], rpy[1], rpy[2]};
}
Eigen::Matrix3d FromRpyDeg(const std::vector<double>& v) {
  return geometry::RotationFromRpy(v[0] * kDegree, v[1] * kDegree, v[2] * kDegree);
}

}  // namespace

namespace internal {
Status ValidateHardwareConfig(const HardwareConfig& config, std::string* bad_key);
}  // namespace internal

// ---- specs -----------------------------------------------------------------------------------

MotorKind MotorKindOf(int motor) {
  ROVER_DEMAND(motor >= 0 && motor < hw::kNumMotors);
  if (motor <= hw::kDriveRR) return MotorKind::kDrive;
  if (motor <= hw::kSteerRR) return MotorKind::kSteer;
  if (motor == hw::kMastPan) return MotorKind::kMastPan;
  if (motor == hw::kMastTilt) return MotorKind::kMastTilt;
  return static_cast<MotorKind>(static_cast<int>(MotorKind::kArmAzimuth) + motor - hw::kArmAzimuth);
}

const char* MotorKindName(MotorKind kind) {
  switch (kind) {
    case MotorKind::kDrive:
      return "drive";
    case MotorKind::kSteer:
      return "steer";
    case MotorKind::kMastPan:
      return "mast_pan";
    case MotorKind::kMastTilt:
      return "mast_tilt";
    case MotorKind::kArmAzimuth:
      return "arm_azimuth";
    case MotorKind::kArmShoulder:
      return "arm_shoulder";
    case MotorKind::kArmElbow:
      return "arm_elbow";
    case MotorKind::kArmWrist:
      return "arm_wrist";
  }
  return "?";
}

double MotorSpec::CountsPerRad() const { return counts_per_rev * gear_ratio / (2.0 * kPi); }
bool MotorSpec::HasLimits() const { return std::isfinite(min_angle) && std::isfinite(max_angle); }

double MotorTelemetrySpec::CurrentFromCounts(double counts) const {
  return (counts - current_offset_counts) / current_counts_per_amp;
}
double MotorTelemetrySpec::CountsFromCurrent(double amps) const {
  return current_offset_counts + current_counts_per_amp * amps;
}
double MotorTelemetrySpec::TemperatureFromCounts(double counts) const {
  return (counts - temperature_offset_counts) / temperature_counts_per_degc;
}
double MotorTelemetrySpec::CountsFromTemperature(double degc) const {
  return temperature_offset_counts + temperature_counts_per_degc * degc;
}

double PotSpec::AngleFromCounts(int pot, double counts) const {
  ROVER_DEMAND(pot >= 0 && pot < hw::kNumPots);
  const auto i = static_cast<std::size_t>(pot);
  return (counts - offset_counts[i]) / gain_counts_per_rad[i];
}
double PotSpec::CountsFromAngle(int pot, double angle) const {
  ROVER_DEMAND(pot >= 0 && pot < hw::kNumPots);
  const auto i = static_cast<std::size_t>(pot);
  return offset_counts[i] + gain_counts_per_rad[i] * angle;
}
double PotSpec::Limit(int pot) const {
  return (pot == hw::kLeftRocker || pot == hw::kRightRocker) ? rocker_limit : bogie_limit;
}

Eigen::Matrix3d InertialSensorSpec::ScaleMisalignment() const {
  return (Eigen::Matrix3d::Identity() + misalignment) * scale.asDiagonal();
}
double InertialSensorSpec::SampleSigma(double rate_hz) const {
  return noise_density * std::sqrt(rate_hz);
}

ImuSpec::ImuSpec() {
  // LN-200-like: gyro 1000 deg/s, ARW 0.07 deg/sqrt(h); accel 40 g, 50 ug/sqrt(Hz).
  rover_from_case = geometry::RotationFromRpy(0.0, 0.0, 90.0 * kDegree);
  gyro.lsb = 1.0e-6;
  gyro.range = 17.45;
  gyro.bias = Eigen::Vector3d(3.0e-6, -2.0e-6, 1.5e-6);
  gyro.scale = Eigen::Vector3d(1.0001, 0.99985, 1.00005);
  gyro.misalignment << 0.0, 1.0e-4, -5.0e-5, -8.0e-5, 0.0, 1.2e-4, 6.0e-5, -1.0e-4, 0.0;
  gyro.noise_density = 2.04e-5;
  gyro.bias_random_walk = 5.0e-8;
  accel.lsb = 1.0e-5;
  accel.range = 392.0;
  accel.bias = Eigen::Vector3d(2.0e-3, -1.5e-3, 3.0e-3);
  accel.scale = Eigen::Vector3d(1.0002, 0.9998, 1.0001);
  accel.misalignment << 0.0, -1.0e-4, 7.0e-5, 9.0e-5, 0.0, -6.0e-5, -4.0e-5, 1.1e-4, 0.0;
  accel.noise_density = 4.9e-4;
  accel.bias_random_walk = 1.0e-5;
}

SunSensorSpec::SunSensorSpec() {
  // Boresight up; detector columns to the rover's right, rows forward.
  rover_from_sensor = geometry::RotationFromRpy(0.0, 0.0, -90.0 * kDegree);
}

bool SunSensorSpec::SpotInFieldOfView(double col, double row) const {
  const double tx = (col - principal_point.x()) / focal_counts;
  const double ty = (row - principal_point.y()) / focal_counts;
  return std::atan(std::sqrt(tx * tx + ty * ty)) <= fov;
}

MotorSpec DefaultMotorSpec(MotorKind kind) {
  MotorSpec s;  // drive: 64 counts/rev, 1500:1 (matches sim/physics' defaults)
  switch (kind) {
    case MotorKind::kDrive:
      break;
    case MotorKind::kSteer:
      s.gear_ratio = 2500.0;
      s.max_rate = 0.5;
      s.default_rate = 0.4;
      s.min_angle = -1.6;
      s.max_angle = 1.6;
      s.current_limit = 0.9;
      s.position_tolerance = 0.01;  // a loaded actuator settles ~0.007 rad short (rover_hardware.yaml)
      break;
    case MotorKind::kMastPan:
    case MotorKind::kMastTilt:
      s.gear_ratio = 1000.0;
      s.max_rate = 1.0;
      s.default_rate = 0.6;
      s.max_acceleration = 3.0;
      s.min_angle = kind == MotorKind::kMastPan ? -3.1 : -1.5;
      s.max_angle = kind == MotorKind::kMastPan ? 3.1 : 1.5;
      s.current_limit = 0.9;
      s.position_tolerance = 0.003;
      break;
    case MotorKind::kArmAzimuth:
    case MotorKind::kArmShoulder:
    case MotorKind::kArmElbow:
    case MotorKind::kArmWrist: {
      // The joint limits are the arm description's (rover_description.hpp: arm).
      const hwconfig::ArmDescription arm;
      const auto j = static_cast<std::size_t>(static_cast<int>(kind) -
                                              static_cast<int>(MotorKind::kArmAzimuth));
      s.gear_ratio = 1500.0;
      s.max_rate = 0.5;
      s.default_rate = 0.25;
      s.max_acceleration = 1.0;
      s.min_angle = arm.min_angle[j];
      s.max_angle = arm.max_angle[j];
      s.current_limit = 0.9;
      s.position_tolerance = 0.002;
      break;
    }
  }
  return s;
}

HardwareConfig::HardwareConfig() {
  for (int i = 0; i < hw::kNumMotors; ++i) {
    motors[static_cast<std::size_t>(i)] = DefaultMotorSpec(MotorKindOf(i));
  }
  pots.offset_counts = {2041.0, 2057.0, 2036.0, 2060.0};
}

Status HardwareConfig::Validate() const { return internal::ValidateHardwareConfig(*this, nullptr); }

Status internal::ValidateHardwareConfig(const HardwareConfig& config, std::string* bad_key) {
  const auto& motors = config.motors;
  const auto& telemetry = config.telemetry;
  const auto& pots = config.pots;
  const auto& imu = config.imu;
  const auto& sun_sensor = config.sun_sensor;
  KeyChecker c;
  for (int i = 0; i < hw::kNumMotors; ++i) {
    const MotorSpec& m = motors[static_cast<std::size_t>(i)];
    const std::string base = std::string("motors.") + MotorKindName(MotorKindOf(i));
    c.Positive(base + ".counts_per_rev", m.counts_per_rev);
    c.Positive(base + ".gear_ratio", m.gear_ratio);
    c.Positive(base + ".max_rate", m.max_rate);
    c.Positive(base + ".default_rate", m.default_rate);
    if (c.ok() && m.default_rate > m.max_rate) {
      c.Fail(base + ".default_rate",
             FormatNumber(m.default_rate) + " exceeds max_rate " + FormatNumber(m.max_rate));
    }
    c.Positive(base + ".max_acceleration", m.max_acceleration);
    c.Positive(base + ".current_limit", m.current_limit);
    if (c.ok() && m.current_limit * 1000.0 > 65535.0) {
      c.Fail(base + ".current_limit",
             FormatNumber(m.current_limit) + " A does not fit the uint16 mA goal");
    }
    c.Finite(base + ".max_temperature", m.max_temperature);
    c.Positive(base + ".position_tolerance", m.position_tolerance);
    if (i >= hw::kSteerLF) {
      c.Finite(base + ".min_angle", m.min_angle);
      c.Finite(base + ".max_angle", m.max_angle);
      if (c.ok() && !(m.min_angle < m.max_angle)) {
        c.Fail(base + ".min_angle",
               FormatNumber(m.min_angle) + " must be below max_angle " + FormatNumber(m.max_angle));
      }
      if (c.ok() &&
          std::max(std::abs(m.min_angle), std::abs(m.max_angle)) * m.CountsPerRad() > 2.0e9) {
        c.Fail(base + ".max_angle", "joint range does not fit int32 encoder counts");
      }
    }
    if (c.ok() && m.max_rate * m.CountsPerRad() > 2.0e9) {
      c.Fail(base + ".max_rate", "rate does not fit int32 counts/s");
    }
  }
  const MotorTelemetrySpec& t = telemetry;
  c.Positive("motors.telemetry.rate_hz", t.rate_hz);
  c.Positive("motors.telemetry.current_counts_per_amp", t.current_counts_per_amp);
  c.InRange("motors.telemetry.current_offset_counts", t.current_offset_counts, 0.0, hw::kAdcMax);
  c.Positive("motors.telemetry.temperature_counts_per_degc", t.temperature_counts_per_degc);
  c.InRange("motors.telemetry.temperature_offset_counts", t.temperature_offset_counts, 0.0,
            hw::kAdcMax);
  c.AtLeast("motors.telemetry.adc_noise_counts", t.adc_noise_counts, 0.0);
  for (int i = 0; i < hw::kNumMotors && c.ok(); ++i) {
    const MotorSpec& m = motors[static_cast<std::size_t>(i)];
    const std::string base = std::string("motors.") + MotorKindName(MotorKindOf(i));
    if (t.CountsFromCurrent(m.current_limit) >= hw::kAdcMax) {
      c.Fail(base + ".current_limit", FormatNumber(m.current_limit) +
                                          " A is beyond the current ADC's full scale " +
                                          FormatNumber(t.CurrentFromCounts(hw::kAdcMax)) + " A");
    }
    const double tc = t.CountsFromTemperature(m.max_temperature);
    if (c.ok() && (tc <= 0.0 || tc >= hw::kAdcMax)) {
      c.Fail(base + ".max_temperature",
             FormatNumber(m.max_temperature) + " degC is outside the temperature ADC's range [" +
                 FormatNumber(t.TemperatureFromCounts(0)) + ", " +
                 FormatNumber(t.TemperatureFromCounts(hw::kAdcMax)) + "]");
    }
  }

  c.Positive("pots.rate_hz", pots.rate_hz);
  for (int i = 0; i < hw::kNumPots; ++i) {
    const auto k = static_cast<std::size_t>(i);
    c.InRange("pots.offset_counts", pots.offset_counts[k], 0.0, hw::kAdcMax);
    c.Finite("pots.gain_counts_per_rad", pots.gain_counts_per_rad[k]);
    if (c.ok() && std::abs(pots.gain_counts_per_rad[k]) < 1.0) {
      c.Fail("pots.gain_counts_per_rad", std::string(hw::PotName(i)) + " gain " +
                                             FormatNumber(pots.gain_counts_per_rad[k]) +
                                             " is below 1 count/rad in magnitude");
    }
  }
  c.InRange("pots.rocker_limit", pots.rocker_limit, 0.01, 1.5);
  c.InRange("pots.bogie_limit", pots.bogie_limit, 0.01, 1.5);
  c.AtLeast("pots.noise_counts", pots.noise_counts, 0.0);
  c.Positive("pots.differential_tolerance", pots.differential_tolerance);

  c.Positive("imu.rate_hz", imu.rate_hz);
  if (c.ok() && !IsRotation(imu.rover_from_case)) {
    c.Fail("imu.mounting_rpy_deg", "is not a rotation");
  }
  CheckInertial(c, "imu.gyro", imu.gyro);
  CheckInertial(c, "imu.accel", imu.accel);
  if (c.ok() && std::abs(imu.gyro.ScaleMisalignment().determinant()) < 0.5) {
    c.Fail("imu.gyro.misalignment", "scale/misalignment matrix is (nearly) singular");
  }
  if (c.ok() && std::abs(imu.accel.ScaleMisalignment().determinant()) < 0.5) {
    c.Fail("imu.accel.misalignment", "scale/misalignment matrix is (nearly) singular");
  }
  c.AtLeast("imu.temperature_noise", imu.temperature_noise, 0.0);

  const SunSensorSpec& s = sun_sensor;
  c.Positive("sun_sensor.rate_hz", s.rate_hz);
  if (c.ok() && !IsRotation(s.rover_from_sensor)) {
    c.Fail("sun_sensor.mounting_rpy_deg", "is not a rotation");
  }
  c.Positive("sun_sensor.focal_counts", s.focal_counts);
  c.Finite("sun_sensor.principal_point", s.principal_point.x());
  c.Finite("sun_sensor.principal_point", s.principal_point.y());
  c.InRange("sun_sensor.fov_deg", s.fov / kDegree, 1.0, 85.0);
  if (c.ok() &&
      s.focal_counts * std::tan(s.fov) + s.principal_point.cwiseAbs().maxCoeff() > 32000.0) {
    c.Fail("sun_sensor.focal_counts",
           "the field of view does not fit the int16 spot counts (focal * tan(fov) > 32000)");
  }
  c.InRange("sun_sensor.full_scale_intensity", s.full_scale_intensity, 1.0, hw::kAdcMax);
  c.InRange("sun_sensor.min_intensity", s.min_intensity, 0.0, hw::kAdcMax);
  if (c.ok() && s.min_intensity >= s.full_scale_intensity) {
    c.Fail("sun_sensor.min_intensity", FormatNumber(s.min_intensity) +
                                           " must be below full_scale_intensity " +
                                           FormatNumber(s.full_scale_intensity));
  }
  c.AtLeast("sun_sensor.spot_noise_counts", s.spot_noise_counts, 0.0);
  c.AtLeast("sun_sensor.intensity_noise_counts", s.intensity_noise_counts, 0.0);
  if (bad_key != nullptr) *bad_key = c.key();
  return c.status();
}

// ---- parameters -------------------------------------------------------------------------------

void DeclareHardwareParams(ParamSet& ps, const std::string& prefix) {
  const HardwareConfig d;
  auto key = [&prefix](const std::string& k) { return Join(prefix, k); };
  for (MotorKind kind : kKinds) {
    const MotorSpec m = DefaultMotorSpec(kind);
    const std::string b = std::string("motors.") + MotorKindName(kind) + ".";
    ps.Declare(key(b + "counts_per_rev"), m.counts_per_rev,
               "encoder counts per motor-shaft revolution (quadrature)")
        .Range(1.0, 1.0e6);
    ps.Declare(key(b + "gear_ratio"), m.gear_ratio, "gearhead ratio (motor turns per output turn)")
        .Range(1.0, 1.0e6);
    ps.Declare(key(b + "max_rate"), m.max_rate, "[rad/s] maximum output rate").Range(1e-4, 100.0);
    ps.Declare(key(b + "default_rate"), m.default_rate,
               "[rad/s] rate limit of position goals when the command gives none")
        .Range(1e-4, 100.0);
    ps.Declare(key(b + "max_acceleration"), m.max_acceleration,
               "[rad/s^2] acceleration of the controller's trapezoidal profile")
        .Range(1e-3, 1.0e3);
    if (kind != MotorKind::kDrive) {
      ps.Declare(key(b + "min_angle"), m.min_angle, "[rad] lower joint limit").Range(-7.0, 7.0);
      ps.Declare(key(b + "max_angle"), m.max_angle, "[rad] upper joint limit").Range(-7.0, 7.0);
    }
    ps.Declare(key(b + "current_limit"), m.current_limit, "[A] over-current trip level")
        .Range(0.01, 60.0);
    ps.Declare(key(b + "max_temperature"), m.max_temperature, "[degC] over-temperature trip level")
        .Range(-150.0, 300.0);
    ps.Declare(key(b + "position_tolerance"), m.position_tolerance,
               "[rad] band around a position goal that counts as reached")
        .Range(1e-6, 1.0);
  }
  const MotorTelemetrySpec& t = d.telemetry;
  ps.Declare(key("motors.telemetry.rate_hz"), t.rate_hz, "[Hz] motor telemetry rate")
      .Range(1.0, 10000.0);
  ps.Declare(key("motors.telemetry.current_counts_per_amp"), t.current_counts_per_amp,
             "[counts/A] current ADC gain")
      .Range(1.0, 1.0e5);
  ps.Declare(key("motors.telemetry.current_offset_counts"), t.current_offset_counts,
             "[counts] current ADC reading at 0 A")
      .Range(0.0, 4095.0);
  ps.Declare(key("motors.telemetry.temperature_counts_per_degc"), t.temperature_counts_per_degc,
             "[counts/degC] temperature ADC gain")
      .Range(0.1, 1000.0);
  ps.Declare(key("motors.telemetry.temperature_offset_counts"), t.temperature_offset_counts,
             "[counts] temperature ADC reading at 0 degC")
      .Range(0.0, 4095.0);
  ps.Declare(key("motors.telemetry.adc_noise_counts"), t.adc_noise_counts,
             "[counts] 1-sigma noise of the telemetry ADCs")
      .Range(0.0, 100.0);

  const PotSpec& p = d.pots;
  ps.Declare(key("pots.rate_hz"), p.rate_hz, "[Hz] suspension pot sample rate").Range(1.0, 10000.0);
  ps.Declare(key("pots.offset_counts"),
             std::vector<double>(p.offset_counts.begin(), p.offset_counts.end()),
             "[counts] ADC reading at 0 rad: left rocker, right rocker, left bogie, right bogie")
      .Size(4)
      .Range(0.0, 4095.0);
  ps.Declare(key("pots.gain_counts_per_rad"),
             std::vector<double>(p.gain_counts_per_rad.begin(), p.gain_counts_per_rad.end()),
             "[counts/rad] pot gains (negative = mounted mirrored), same order")
      .Size(4)
      .Range(-1.0e5, 1.0e5);
  ps.Declare(key("pots.rocker_limit"), p.rocker_limit, "[rad] rocker mechanical stops at +-limit")
      .Range(0.01, 1.5);
  ps.Declare(key("pots.bogie_limit"), p.bogie_limit, "[rad] bogie mechanical stops at +-limit")
      .Range(0.01, 1.5);
  ps.Declare(key("pots.noise_counts"), p.noise_counts, "[counts] 1-sigma pot ADC noise")
      .Range(0.0, 100.0);
  ps.Declare(key("pots.differential_tolerance"), p.differential_tolerance,
             "[rad] largest |left + right| rocker angle consistent with the differential")
      .Range(1e-4, 1.0);

  const ImuSpec& imu = d.imu;
  ps.Declare(key("imu.rate_hz"), imu.rate_hz, "[Hz] IMU sample rate").Range(1.0, 10000.0);
  ps.Declare(key("imu.mounting_rpy_deg"), RpyDeg(imu.rover_from_case),
             "[deg] roll, pitch, yaw of the IMU case axes in the rover frame (rover_from_case)")
      .Size(3)
      .Range(-360.0, 360.0);
  ps.Declare(key("imu.temperature_noise"), imu.temperature_noise,
             "[degC] 1-sigma temperature noise")
      .Range(0.0, 10.0);
  for (const char* which : {"gyro", "accel"}) {
    const bool g = std::string(which) == "gyro";
    const InertialSensorSpec& s = g ? imu.gyro : imu.accel;
    const std::string u = g ? "rad/s" : "m/s^2";
    const std::string b = std::string("imu.") + which + ".";
    ps.Declare(key(b + "lsb"), s.lsb, "[" + u + "] value of one LSB").Range(1e-12, 1.0);
    ps.Declare(key(b + "range"), s.range, "[" + u + "] full scale (saturation)").Range(1e-3, 1e4);
    ps.Declare(key(b + "bias"), List(s.bias), "[" + u + "] nominal bias, case frame x, y, z")
        .Size(3)
        .Range(-100.0, 100.0);
    ps.Declare(key(b + "scale"), List(s.scale), "scale factors x, y, z (1 = ideal)")
        .Size(3)
        .Range(0.5, 1.5);
    ps.Declare(key(b + "misalignment"), List(s.misalignment),
               "[rad] axis misalignment M (row-major 3x3, zero diagonal); K = (I + M) diag(scale)")
        .Size(9)
        .Range(-0.1, 0.1);
    ps.Declare(key(b + "noise_density"), s.noise_density,
               "[" + u + "/sqrt(Hz)] white noise density")
        .Range(0.0, 10.0);
    ps.Declare(key(b + "bias_random_walk"), s.bias_random_walk,
               "[" + u + "/sqrt(s)] bias random walk")
        .Range(0.0, 10.0);
  }

  const SunSensorSpec& s = d.sun_sensor;
  ps.Declare(key("sun_sensor.rate_hz"), s.rate_hz, "[Hz] sun sensor sample rate")
      .Range(0.01, 1000.0);
  ps.Declare(key("sun_sensor.mounting_rpy_deg"), RpyDeg(s.rover_from_sensor),
             "[deg] roll, pitch, yaw of the sensor axes (x col, y row, z boresight) in the rover "
             "frame")
      .Size(3)
      .Range(-360.0, 360.0);
  ps.Declare(key("sun_sensor.focal_counts"), s.focal_counts,
             "[counts] focal length in detector counts")
      .Range(1.0, 1.0e5);
  ps.Declare(key("sun_sensor.principal_point"),
             std::vector<double>{s.principal_point.x(), s.principal_point.y()},
             "[counts] spot of a sun on the boresight (column, row)")
      .Size(2)
      .Range(-30000.0, 30000.0);
  ps.Declare(key("sun_sensor.fov_deg"), s.fov / kDegree, "[deg] half angle of the field of view")
      .Range(1.0, 85.0);
  ps.Declare(key("sun_sensor.full_scale_intensity"), s.full_scale_intensity,
             "[counts] intensity of the zenith sun on the boresight")
      .Range(1.0, 4095.0);
  ps.Declare(key("sun_sensor.min_intensity"), s.min_intensity,
             "[counts] dimmer spots are not accepted as the sun")
      .Range(0.0, 4095.0);
  ps.Declare(key("sun_sensor.spot_noise_counts"), s.spot_noise_counts,
             "[counts] 1-sigma centroid noise")
      .Range(0.0, 1000.0);
  ps.Declare(key("sun_sensor.intensity_noise_counts"), s.intensity_noise_counts,
             "[counts] 1-sigma intensity noise")
      .Range(0.0, 1000.0);
}

Result<HardwareConfig> HardwareConfigFromParams(const ParamSet& ps, const std::string& prefix) {
  ROVER_RETURN_IF_ERROR(ps.Validate());
  auto key = [&prefix](const std::string& k) { return Join(prefix, k); };
  auto d = [&](const std::string& k) { return ps.GetDouble(key(k)); };
  auto list = [&](const std::string& k) { return ps.GetDoubleList(key(k)); };

  HardwareConfig c;
  for (int i = 0; i < hw::kNumMotors; ++i) {
    const MotorKind kind = MotorKindOf(i);
    const std::string b = std::string("motors.") + MotorKindName(kind) + ".";
    MotorSpec& m = c.motors[static_cast<std::size_t>(i)];
    m.counts_per_rev = d(b + "counts_per_rev");
    m.gear_ratio = d(b + "gear_ratio");
    m.max_rate = d(b + "max_rate");
    m.default_rate = d(b + "default_rate");
    m.max_acceleration = d(b + "max_acceleration");
    if (kind != MotorKind::kDrive) {
      m.min_angle = d(b + "min_angle");
      m.max_angle = d(b + "max_angle");
    }
    m.current_limit = d(b + "current_limit");
    m.max_temperature = d(b + "max_temperature");
    m.position_tolerance = d(b + "position_tolerance");
  }
  c.telemetry.rate_hz = d("motors.telemetry.rate_hz");
  c.telemetry.current_counts_per_amp = d("motors.telemetry.current_counts_per_amp");
  c.telemetry.current_offset_counts = d("motors.telemetry.current_offset_counts");
  c.telemetry.temperature_counts_per_degc = d("motors.telemetry.temperature_counts_per_degc");
  c.telemetry.temperature_offset_counts = d("motors.telemetry.temperature_offset_counts");
  c.telemetry.adc_noise_counts = d("motors.telemetry.adc_noise_counts");

  c.pots.rate_hz = d("pots.rate_hz");
  const auto& off = list("pots.offset_counts");
  const auto& gain = list("pots.gain_counts_per_rad");
  for (std::size_t i = 0; i < 4; ++i) {
    c.pots.offset_counts[i] = off[i];
    c.pots.gain_counts_per_rad[i] = gain[i];
  }
  c.pots.rocker_limit = d("pots.rocker_limit");
  c.pots.bogie_limit = d("pots.bogie_limit");
  c.pots.noise_counts = d("pots.noise_counts");
  c.pots.differential_tolerance = d("pots.differential_tolerance");

  c.imu.rate_hz = d("imu.rate_hz");
  c.imu.rover_from_case = FromRpyDeg(list("imu.mounting_rpy_deg"));
  c.imu.temperature_noise = d("imu.temperature_noise");
  for (const char* which : {"gyro", "accel"}) {
    InertialSensorSpec& s = std::string(which) == "gyro" ? c.imu.gyro : c.imu.accel;
    const std::string b = std::string("imu.") + which + ".";
    s.lsb = d(b + "lsb");
    s.range = d(b + "range");
    s.bias = Vec3(list(b + "bias"));
    s.scale = Vec3(list(b + "scale"));
    s.misalignment = Mat3(list(b + "misalignment"));
    s.noise_density = d(b + "noise_density");
    s.bias_random_walk = d(b + "bias_random_walk");
  }

  SunSensorSpec& s = c.sun_sensor;
  s.rate_hz = d("sun_sensor.rate_hz");
  s.rover_from_sensor = FromRpyDeg(list("sun_sensor.mounting_rpy_deg"));
  s.focal_counts = d("sun_sensor.focal_counts");
  const auto& pp = list("sun_sensor.principal_point");
  s.principal_point = Eigen::Vector2d(pp[0], pp[1]);
  s.fov = d("sun_sensor.fov_deg") * kDegree;
  s.full_scale_intensity = d("sun_sensor.full_scale_intensity");
  s.min_intensity = d("sun_sensor.min_intensity");
  s.spot_noise_counts = d("sun_sensor.spot_noise_counts");
  s.intensity_noise_counts = d("sun_sensor.intensity_noise_counts");

  std::string bad_key;
  const Status st = internal::ValidateHardwareConfig(c, &bad_key);
  if (!st.ok()) return AtParamKey(ps, key(bad_key), st);
  return c;
}

Result<HardwareConfig> LoadHardwareConfig(const std::string& path) {
  ParamSet ps("hardware");
  DeclareHardwareParams(ps);
  ROVER_RETURN_IF_ERROR(ps.LoadYamlFile(path));
  return HardwareConfigFromParams(ps);
}

}  // namespace rover
