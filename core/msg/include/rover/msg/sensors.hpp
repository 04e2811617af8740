#pragma once
/// @file
/// The device drivers' sensor streams as plain values (idl/rover_ddl.idl): ddl/imu,
/// ddl/sun_sensor and ddl/joint_state, in engineering units in the rover frame, with health.
/// The ddl drivers produce them, the dl services consume them; rover/msg/sensors_idl.hpp
/// converts them.
///
/// Index conventions (rover_ddl.idl): wheels LF LM LR RF RM RR; steering LF LR RF RR; rocker and
/// bogie left, right. Angles [rad]: steering positive turns the wheel's front to the left, rocker
/// and bogie positive raise the front of the link, mast pan positive left, tilt positive up.

#include <Eigen/Core>
#include <array>

#include "rover/base/time.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/msg/health.hpp"

namespace rover::msg {

// The counts are the rover description's (core/hwconfig rover_description.hpp).
using hwconfig::kNumSteered;
using hwconfig::kNumWheels;

/// ddl/imu: calibrated, in the rover frame.
struct Imu {
  Time stamp;
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();     ///< [rad/s]
  Eigen::Vector3d linear_acceleration = Eigen::Vector3d::Zero();  ///< [m/s^2] specific force
  double temperature = 0.0;                                       ///< [deg C]
  SensorHealth health = SensorHealth::kOk;
};

/// ddl/sun_sensor.
struct SunSensor {
  Time stamp;
  Eigen::Vector3d sun_vector = Eigen::Vector3d::Zero();  ///< unit, rover frame; 0 if !valid
  bool valid = false;      ///< false: sun outside the field of view or too dim
  double intensity = 0.0;  ///< [0..1] relative brightness
  SensorHealth health = SensorHealth::kOk;
};

/// ddl/joint_state: encoder and potentiometer readings.
struct JointState {
  Time stamp;
  std::array<double, kNumWheels> wheel_angle{};   ///< [rad] cumulative drive rotation
  std::array<double, kNumWheels> wheel_rate{};    ///< [rad/s]
  std::array<double, kNumSteered> steer_angle{};  ///< [rad]
  std::array<double, 2> rocker_angle{};           ///< [rad] left, right
  std::array<double, 2> bogie_angle{};            ///< [rad] left, right, relative to the rocker
  double mast_pan = 0.0;                          ///< [rad]
  double mast_tilt = 0.0;                         ///< [rad]
  std::array<double, 4> arm_angle{};  ///< [rad] azimuth, shoulder, elbow, wrist (arm_description.hpp)
  bool arm_contact = false;           ///< the arm instrument's contact switch is closed
  SensorHealth health = SensorHealth::kOk;

  /// True when every wheel, steering and suspension angle and rate is finite (the mast angles
  /// are not part of it: mobility does not use them).
  bool AllFinite() const;
};

}  // namespace rover::msg
