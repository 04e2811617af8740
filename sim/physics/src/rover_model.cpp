#include "rover/sim/physics/rover_model.hpp"

#include <cmath>
#include <sstream>
#include <string>

namespace rover::sim {
namespace {

std::string Num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

Status CheckRange(const char* name, double v, double lo, double hi) {
  if (!std::isfinite(v) || v < lo || v > hi) {
    return InvalidArgument(std::string(name) + " = " + Num(v) + " is outside [" + Num(lo) + ", " +
                           Num(hi) + "]");
  }
  return Status::Ok();
}

Status CheckVector(const char* name, const Eigen::Vector3d& v, double lo, double hi) {
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(v[i]) || v[i] < lo || v[i] > hi) {
      return InvalidArgument(std::string(name) + "[" + std::to_string(i) + "] = " + Num(v[i]) +
                             " is outside [" + Num(lo) + ", " + Num(hi) + "]");
    }
  }
  return Status::Ok();
}

}  // namespace

const char* MotorName(int motor) {
  static constexpr const char* kNames[kNumMotors] = {
      "drive_lf", "drive_lm", "drive_lr", "drive_rf", "drive_rm", "drive_rr",
      "steer_lf", "steer_lr", "steer_rf", "steer_rr", "mast_pan", "mast_tilt"};
  return (motor >= 0 && motor < kNumMotors) ? kNames[motor] : "?";
}

int SteeredWheel(int motor) {
  switch (motor) {
    case kSteerLF:
      return kWheelLF;
    case kSteerLR:
      return kWheelLR;
    case kSteerRF:
      return kWheelRF;
    case kSteerRR:
      return kWheelRR;
    default:
      return -1;
  }
}

Status RoverGeometry::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckRange("geometry.wheel_radius", wheel_radius, 0.01, 2.0));
  ROVER_RETURN_IF_ERROR(CheckRange("geometry.wheel_width", wheel_width, 0.005, 2.0));
  ROVER_RETURN_IF_ERROR(CheckRange("geometry.front_wheel_x", front_wheel_x, -5.0, 5.0));
  ROVER_RETURN_IF_ERROR(CheckRange("geometry.middle_wheel_x", middle_wheel_x, -5.0, 5.0));
  ROVER_RETURN_IF_ERROR(CheckRange("geometry.rear_wheel_x", rear_wheel_x, -5.0, 5.0));
  if (!(front_wheel_x > middle_wheel_x && middle_wheel_x > rear_wheel_x)) {
    return InvalidArgument("geometry: wheel x positions must satisfy front (" + Num(front_wheel_x) +
                           ") > middle (" + Num(middle_wheel_x) + ") > rear (" + Num(rear_wheel_x) +
                           ")");
  }
  if (!(bogie_pivot_x > rear_wheel_x && bogie_pivot_x < middle_wheel_x)) {
    return InvalidArgument("geometry.bogie_pivot_x = " + Num(bogie_pivot_x) +
                           " must lie between the rear and middle wheels");
  }
  ROVER_RETURN_IF_ERROR(CheckRange("geometry.half_track", half_track, wheel_width, 5.0));
  ROVER_RETURN_IF_ERROR(CheckRange("geometry.rocker_pivot_x", rocker_pivot_x, -5.0, 5.0));
  ROVER_RETURN_IF_ERROR(CheckRange("geometry.rocker_pivot_y", rocker_pivot_y, 0.0, 5.0));
  ROVER_RETURN_IF_ERROR(CheckRange("geometry.rocker_pivot_z", rocker_pivot_z, wheel_radius, 5.0));
  ROVER_RETURN_IF_ERROR(CheckRange("geometry.bogie_pivot_z", bogie_pivot_z, wheel_radius, 5.0));
  ROVER_RETURN_IF_ERROR(CheckRange("geometry.steer_height", steer_height, 0.0, 2.0));
  ROVER_RETURN_IF_ERROR(CheckVector("geometry.chassis_box_size", chassis_box_size, 0.01, 10.0));
  ROVER_RETURN_IF_ERROR(
      CheckVector("geometry.chassis_box_center", chassis_box_center, -10.0, 10.0));
  ROVER_RETURN_IF_ERROR(CheckVector("geometry.mast_base", mast_base, -10.0, 10.0));
  ROVER_RETURN_IF_ERROR(CheckRange("geometry.mast_height", mast_height, 0.0, 10.0));
  ROVER_RETURN_IF_ERROR(CheckVector("geometry.hazcam_front", hazcam_front, -10.0, 10.0));
  ROVER_RETURN_IF_ERROR(CheckVector("geometry.hazcam_rear", hazcam_rear, -10.0, 10.0));
  ROVER_RETURN_IF_ERROR(
      CheckRange("geometry.hazcam_depression", hazcam_depression, -1.5708, 1.5708));
  ROVER_RETURN_IF_ERROR(CheckVector("geometry.imu_station", imu_station, -10.0, 10.0));
  ROVER_RETURN_IF_ERROR(CheckRange("geometry.rocker_limit", rocker_limit, 0.01, 1.5));
  ROVER_RETURN_IF_ERROR(CheckRange("geometry.bogie_limit", bogie_limit, 0.01, 1.5));
  return Status::Ok();
}

Status RoverMasses::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckRange("masses.chassis", chassis, 1.0, 1e4));
  ROVER_RETURN_IF_ERROR(CheckRange("masses.rocker", rocker, 0.01, 1e3));
  ROVER_RETURN_IF_ERROR(CheckRange("masses.bogie", bogie, 0.01, 1e3));
  ROVER_RETURN_IF_ERROR(CheckRange("masses.steer_bracket", steer_bracket, 0.01, 1e3));
  ROVER_RETURN_IF_ERROR(CheckRange("masses.wheel", wheel, 0.01, 1e3));
  ROVER_RETURN_IF_ERROR(CheckRange("masses.mast_pan", mast_pan, 0.01, 1e3));
  ROVER_RETURN_IF_ERROR(CheckRange("masses.mast_head", mast_head, 0.01, 1e3));
  return Status::Ok();
}

Status IntegratorParams::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckRange("integrator.accuracy", accuracy, 1e-8, 0.1));
  ROVER_RETURN_IF_ERROR(CheckRange("integrator.control_rate_hz", control_rate_hz, 10.0, 1e5));
  ROVER_RETURN_IF_ERROR(CheckRange("integrator.settle_time", settle_time, 0.0, 60.0));
  ROVER_RETURN_IF_ERROR(CheckRange("integrator.max_advance", max_advance, 1e-3, 1e6));
  return Status::Ok();
}

MotorParams DefaultDriveMotorParams() { return MotorParams{}; }

MotorParams DefaultSteerMotorParams() {
  MotorParams p;
  p.gear_ratio = 2500.0;
  p.max_current = 1.0;
  p.overcurrent_trip = 0.9;
  p.kp = 400.0;
  p.ki = 10.0;  // small: the scrub torque vanishes when the wheel stops (no overshoot)
  p.kd = 25.0;
  p.integral_limit = 10.0;
  p.max_speed = 0.5;
  p.max_acceleration = 2.0;
  p.min_angle = -1.6;
  p.max_angle = 1.6;
  p.brake_torque = 30.0;
  p.brake_kp = 300.0;
  p.brake_kd = 20.0;
  return p;
}

MotorParams DefaultMastPanMotorParams() {
  MotorParams p;
  p.gear_ratio = 1000.0;
  p.torque_constant = 0.01;
  p.winding_resistance = 4.0;
  p.no_load_current = 0.02;
  p.max_current = 1.0;
  p.overcurrent_trip = 0.9;
  p.kp = 40.0;
  p.ki = 20.0;
  p.kd = 4.0;
  p.integral_limit = 3.0;
  p.max_speed = 1.0;
  p.max_acceleration = 3.0;
  p.max_following_error = 0.2;
  p.min_angle = -3.1;
  p.max_angle = 3.1;
  p.brake_torque = 10.0;
  p.brake_kp = 100.0;
  p.brake_kd = 5.0;
  return p;
}

MotorParams DefaultMastTiltMotorParams() {
  MotorParams p = DefaultMastPanMotorParams();
  p.min_angle = -1.5;
  p.max_angle = 1.5;
  return p;
}

std::array<MotorParams, kNumMotors> RoverModelParams::DefaultMotors() {
  std::array<MotorParams, kNumMotors> m;
  for (int i = kDriveLF; i <= kDriveRR; ++i) m[i] = DefaultDriveMotorParams();
  for (int i = kSteerLF; i <= kSteerRR; ++i) m[i] = DefaultSteerMotorParams();
  m[kMastPan] = DefaultMastPanMotorParams();
  m[kMastTilt] = DefaultMastTiltMotorParams();
  return m;
}

Status RoverModelParams::Validate() const {
  ROVER_RETURN_IF_ERROR(geometry.Validate());
  ROVER_RETURN_IF_ERROR(masses.Validate());
  ROVER_RETURN_IF_ERROR(contact.Validate());
  ROVER_RETURN_IF_ERROR(belly.Validate());
  for (int i = 0; i < kNumMotors; ++i) {
    ROVER_RETURN_IF_ERROR(
        motors[i].Validate("motors[" + std::to_string(i) + "] (" + MotorName(i) + ")"));
  }
  ROVER_RETURN_IF_ERROR(integrator.Validate());
  ROVER_RETURN_IF_ERROR(CheckRange("differential_stiffness", differential_stiffness, 1.0, 1e9));
  ROVER_RETURN_IF_ERROR(CheckRange("differential_damping", differential_damping, 0.0, 1e7));
  ROVER_RETURN_IF_ERROR(CheckRange("gravity", gravity, 0.0, 100.0));
  ROVER_RETURN_IF_ERROR(CheckRange("ambient_temperature_c", ambient_temperature_c, -200, 200));
  return Status::Ok();
}

}  // namespace rover::sim
