#include "rover/sim/sensors/sim_sensor_options.hpp"

#include <cmath>
#include <vector>

#include "rover/base/units.hpp"

namespace rover::sim::sensors {
namespace {

std::string Join(const std::string& prefix, const std::string& key) {
  return prefix.empty() ? key : prefix + "." + key;
}
std::vector<double> List(const Eigen::Vector3d& v) { return {v[0], v[1], v[2]}; }
Eigen::Vector3d Vec3(const std::vector<double>& v) { return {v[0], v[1], v[2]}; }

bool Finite(const Eigen::Vector3d& v) { return v.allFinite(); }

}  // namespace

SimSensorOptions::SimSensorOptions() {
  imu.gyro_bias_error = Eigen::Vector3d(4.0e-6, -3.0e-6, 2.0e-6);
  imu.accel_bias_error = Eigen::Vector3d(3.0e-3, -2.0e-3, 4.0e-3);
  imu.gyro_scale_error = Eigen::Vector3d(1.0e-4, -5.0e-5, 8.0e-5);
  imu.accel_scale_error = Eigen::Vector3d(2.0e-4, -1.0e-4, 1.0e-4);
  imu.mounting_error_rpy = Eigen::Vector3d(0.05, -0.03, 0.08) * kDegree;
  pots.offset_error_counts = {4.0, -3.0, 5.0, -2.0};
  pots.gain_error = {0.005, -0.004, 0.006, -0.003};
  motors.current_gain_error = 0.01;
  motors.current_offset_error_counts = 3.0;
  motors.temperature_offset_error_c = 1.5;
  sun_sensor.mounting_error_rpy = Eigen::Vector3d(0.2, -0.15, 0.3) * kDegree;
  sun_sensor.principal_point_error = Eigen::Vector2d(3.0, -2.0);
  sun_sensor.focal_error = 0.002;
  sun_sensor.optical_depth = 0.5;
}

SimSensorOptions SimSensorOptions::Ideal() {
  SimSensorOptions o;
  o.noise_scale = 0.0;
  o.imu = ImuErrors{};
  o.pots = PotErrors{};
  o.motors = MotorTelemetryErrors{};
  o.sun_sensor = SunSensorErrors{};
  o.sun_sensor.optical_depth = 0.0;
  return o;
}

Status SimSensorOptions::Validate() const {
  if (!std::isfinite(noise_scale) || noise_scale < 0.0) {
    return InvalidArgument("noise_scale: " + std::to_string(noise_scale) + " must be >= 0");
  }
  if (!Finite(imu.gyro_bias_error) || !Finite(imu.accel_bias_error) ||
      !Finite(imu.gyro_scale_error) || !Finite(imu.accel_scale_error) ||
      !Finite(imu.mounting_error_rpy)) {
    return InvalidArgument("imu: calibration errors must be finite");
  }
  if (!(imu.gyro_bias_sigma >= 0.0) || !(imu.accel_bias_sigma >= 0.0) ||
      !std::isfinite(imu.gyro_bias_sigma) || !std::isfinite(imu.accel_bias_sigma)) {
    return InvalidArgument("imu: bias sigmas must be finite and >= 0");
  }
  for (std::size_t i = 0; i < 4; ++i) {
    if (!std::isfinite(pots.offset_error_counts[i]) || !std::isfinite(pots.gain_error[i]) ||
        pots.gain_error[i] <= -1.0) {
      return InvalidArgument("pots: errors must be finite and gain_error > -1");
    }
  }
  if (!std::isfinite(motors.current_gain_error) || motors.current_gain_error <= -1.0 ||
      !std::isfinite(motors.current_offset_error_counts) ||
      !std::isfinite(motors.temperature_offset_error_c)) {
    return InvalidArgument("motors: errors must be finite and current_gain_error > -1");
  }
  if (!Finite(sun_sensor.mounting_error_rpy) || !sun_sensor.principal_point_error.allFinite() ||
      !std::isfinite(sun_sensor.focal_error) || sun_sensor.focal_error <= -1.0 ||
      !std::isfinite(sun_sensor.optical_depth) || sun_sensor.optical_depth < 0.0) {
    return InvalidArgument(
        "sun_sensor: errors must be finite, focal_error > -1 and optical_depth >= 0");
  }
  return ephemeris.Validate();
}

void DeclareSimSensorParams(ParamSet& ps, const std::string& prefix) {
  const SimSensorOptions d;
  auto key = [&prefix](const std::string& k) { return Join(prefix, k); };
  ps.Declare(key("seed"), std::int64_t{1}, "seed of every sensor's noise").Min(0);
  ps.Declare(key("noise_scale"), d.noise_scale,
             "multiplies every noise sigma of the hardware file (0 = noise-free)")
      .Range(0.0, 100.0);
  ps.Declare(key("imu.gyro_bias_error"), List(d.imu.gyro_bias_error),
             "[rad/s] true - nominal gyro bias, case frame")
      .Size(3)
      .Range(-0.1, 0.1);
  ps.Declare(key("imu.accel_bias_error"), List(d.imu.accel_bias_error),
             "[m/s^2] true - nominal accelerometer bias, case frame")
      .Size(3)
      .Range(-10.0, 10.0);
  ps.Declare(key("imu.gyro_bias_sigma"), d.imu.gyro_bias_sigma,
             "[rad/s] turn-on gyro bias repeatability (drawn from the seed)")
      .Range(0.0, 0.1);
  ps.Declare(key("imu.accel_bias_sigma"), d.imu.accel_bias_sigma,
             "[m/s^2] turn-on accelerometer bias repeatability")
      .Range(0.0, 10.0);
  ps.Declare(key("imu.gyro_scale_error"), List(d.imu.gyro_scale_error),
             "relative true - nominal gyro scale per case axis")
      .Size(3)
      .Range(-0.1, 0.1);
  ps.Declare(key("imu.accel_scale_error"), List(d.imu.accel_scale_error),
             "relative true - nominal accelerometer scale per case axis")
      .Size(3)
      .Range(-0.1, 0.1);
  ps.Declare(key("imu.mounting_error_rpy_deg"), List(d.imu.mounting_error_rpy / kDegree),
             "[deg] rotation of the true IMU case relative to the nominal mounting")
      .Size(3)
      .Range(-10.0, 10.0);
  ps.Declare(
        key("pots.offset_error_counts"),
        std::vector<double>(d.pots.offset_error_counts.begin(), d.pots.offset_error_counts.end()),
        "[counts] true - nominal pot offsets (left/right rocker, left/right bogie)")
      .Size(4)
      .Range(-1000.0, 1000.0);
  ps.Declare(key("pots.gain_error"),
             std::vector<double>(d.pots.gain_error.begin(), d.pots.gain_error.end()),
             "relative true - nominal pot gains")
      .Size(4)
      .Range(-0.5, 0.5);
  ps.Declare(key("motors.current_gain_error"), d.motors.current_gain_error,
             "relative error of the current ADC gain")
      .Range(-0.5, 0.5);
  ps.Declare(key("motors.current_offset_error_counts"), d.motors.current_offset_error_counts,
             "[counts] error of the current ADC offset")
      .Range(-1000.0, 1000.0);
  ps.Declare(key("motors.temperature_offset_error_c"), d.motors.temperature_offset_error_c,
             "[degC] error of the temperature sensors")
      .Range(-100.0, 100.0);
  ps.Declare(key("sun_sensor.mounting_error_rpy_deg"),
             List(d.sun_sensor.mounting_error_rpy / kDegree),
             "[deg] rotation of the true sun sensor relative to the nominal mounting")
      .Size(3)
      .Range(-10.0, 10.0);
  ps.Declare(key("sun_sensor.principal_point_error"),
             std::vector<double>{d.sun_sensor.principal_point_error.x(),
                                 d.sun_sensor.principal_point_error.y()},
             "[counts] true - nominal principal point")
      .Size(2)
      .Range(-1000.0, 1000.0);
  ps.Declare(key("sun_sensor.focal_error"), d.sun_sensor.focal_error,
             "relative true - nominal focal length")
      .Range(-0.5, 0.5);
  ps.Declare(key("sun_sensor.optical_depth"), d.sun_sensor.optical_depth,
             "atmospheric dust optical depth tau (0.3 clear .. 5 dust storm)")
      .Range(0.0, 10.0);
  const geometry::SunEphemerisOptions& e = d.ephemeris;
  ps.Declare(key("ephemeris.mode"), "season",
             "'season': Ls and local true solar time given at t = 0; 'date': J2000 TT days")
      .OneOf({"season", "date"});
  ps.Declare(key("ephemeris.latitude_deg"), e.latitude_deg, "[deg] site latitude (+ north)")
      .Range(-90.0, 90.0);
  ps.Declare(key("ephemeris.east_longitude_deg"), e.east_longitude_deg,
             "[deg] site east longitude (mode 'date')")
      .Range(-360.0, 360.0);
  ps.Declare(key("ephemeris.ls_deg"), e.ls_deg, "[deg] areocentric solar longitude at t = 0")
      .Range(0.0, 359.999999);
  ps.Declare(key("ephemeris.ltst_hours"), e.ltst_hours, "[h] local true solar time at t = 0")
      .Range(0.0, 23.999999);
  ps.Declare(key("ephemeris.j2000_tt_days"), e.j2000_tt_days,
             "[days] TT days since J2000 at t = 0 (mode 'date')")
      .Range(-1.0e6, 1.0e6);
}

Result<SimSensorOptions> SimSensorOptionsFromParams(const ParamSet& ps, const std::string& prefix) {
  ROVER_RETURN_IF_ERROR(ps.Validate());
  auto key = [&prefix](const std::string& k) { return Join(prefix, k); };
  auto d = [&](const std::string& k) { return ps.GetDouble(key(k)); };
  auto v3 = [&](const std::string& k) { return Vec3(ps.GetDoubleList(key(k))); };
  SimSensorOptions o;
  o.seed = static_cast<std::uint64_t>(ps.GetInt(key("seed")));
  o.noise_scale = d("noise_scale");
  o.imu.gyro_bias_error = v3("imu.gyro_bias_error");
  o.imu.accel_bias_error = v3("imu.accel_bias_error");
  o.imu.gyro_bias_sigma = d("imu.gyro_bias_sigma");
  o.imu.accel_bias_sigma = d("imu.accel_bias_sigma");
  o.imu.gyro_scale_error = v3("imu.gyro_scale_error");
  o.imu.accel_scale_error = v3("imu.accel_scale_error");
  o.imu.mounting_error_rpy = v3("imu.mounting_error_rpy_deg") * kDegree;
  const auto& off = ps.GetDoubleList(key("pots.offset_error_counts"));
  const auto& gain = ps.GetDoubleList(key("pots.gain_error"));
  for (std::size_t i = 0; i < 4; ++i) {
    o.pots.offset_error_counts[i] = off[i];
    o.pots.gain_error[i] = gain[i];
  }
  o.motors.current_gain_error = d("motors.current_gain_error");
  o.motors.current_offset_error_counts = d("motors.current_offset_error_counts");
  o.motors.temperature_offset_error_c = d("motors.temperature_offset_error_c");
  o.sun_sensor.mounting_error_rpy = v3("sun_sensor.mounting_error_rpy_deg") * kDegree;
  const auto& pp = ps.GetDoubleList(key("sun_sensor.principal_point_error"));
  o.sun_sensor.principal_point_error = Eigen::Vector2d(pp[0], pp[1]);
  o.sun_sensor.focal_error = d("sun_sensor.focal_error");
  o.sun_sensor.optical_depth = d("sun_sensor.optical_depth");
  o.ephemeris.mode = ps.GetString(key("ephemeris.mode")) == "date"
                         ? geometry::SunEphemerisOptions::Mode::kDate
                         : geometry::SunEphemerisOptions::Mode::kSeason;
  o.ephemeris.latitude_deg = d("ephemeris.latitude_deg");
  o.ephemeris.east_longitude_deg = d("ephemeris.east_longitude_deg");
  o.ephemeris.ls_deg = d("ephemeris.ls_deg");
  o.ephemeris.ltst_hours = d("ephemeris.ltst_hours");
  o.ephemeris.j2000_tt_days = d("ephemeris.j2000_tt_days");
  const Status s = o.Validate();
  if (!s.ok()) return Status(s.code(), prefix + ": " + s.message());
  return o;
}

}  // namespace rover::sim::sensors
