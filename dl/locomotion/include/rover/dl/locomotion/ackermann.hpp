#pragma once
/// @file
/// Ackermann and turn-in-place kinematics of the six-wheel rover (MER DRIVE, Biesiadecki &
/// Maimone 2006). Wheel positions p_i = (x_i, y_i) are the steering axes (wheel centres at zero
/// suspension angles, RoverGeometry::wheel_centre); x_m is the middle axle; r the wheel radius.
///
/// Arc of curvature k [1/m] (positive = left, centre at C = (x_m, 1/k)) driven for a distance s
/// [m] by the reference point (x_m, 0):
///   steer angle    d_i = atan2(k (x_i - x_m), 1 - k y_i)                (corner wheels only)
///   path ratio     g_i = sqrt((k (x_i - x_m))^2 + (1 - k y_i)^2)  = |p_i - C| / |C - (x_m,0)|
///   wheel path     s_i = g_i s,   wheel rotation  th_i = s_i / r,   wheel speed  v_i = g_i v
///   heading change dpsi = k s
/// The formulas hold at k = 0 (straight: d_i = 0, g_i = 1). Because min_turn_radius > |y_i|,
/// 1 - k y_i > 0: every wheel rolls forwards for s > 0, and wheels on the outside of the turn
/// (k y_i < 0) have g_i > 1, i.e. turn faster. Each corner wheel's axle line passes through C.
///
/// Turn in place by an angle a [rad] (positive = counter-clockwise) about C0 = (x_m, 0):
///   steer angle    d_i = atan(-(x_i - x_m) / y_i)   (wheel tangent to the circle about C0)
///   signed radius  q_i = t_i . (-y_i, x_i - x_m),  t_i = (cos d_i, sin d_i),  |q_i| = |p_i - C0|
///   wheel path     s_i = q_i a   (left wheels drive backwards for a > 0),  yaw rate w: v_i = q_i w
/// Speeds: for arcs `speed` is the reference point's speed, reduced if needed so that no wheel
/// exceeds max_wheel_speed; for turns in place `speed` is the fastest wheel's rim speed (capped
/// at max_wheel_speed) and the yaw rate is speed / max_i |q_i|.

#include <Eigen/Core>
#include <array>

#include "rover/base/status.hpp"
#include "rover/dl/locomotion/drive_types.hpp"
#include "rover/dl/locomotion/rover_geometry.hpp"

namespace rover::dl::locomotion {

/// Steer angle [rad] of steer actuator j (0..3 = LF LR RF RR) on an arc of curvature k.
double ArcSteerAngle(const RoverGeometry& g, int steer, double curvature);
std::array<double, kNumSteered> ArcSteerAngles(const RoverGeometry& g, double curvature);
/// Path ratio g_i of wheel i (0..5) on an arc of curvature k (1 on a straight line).
double ArcPathRatio(const RoverGeometry& g, int wheel, double curvature);
std::array<double, kNumWheels> ArcPathRatios(const RoverGeometry& g, double curvature);

/// Steer angle [rad] of steer actuator j for a turn in place.
double TurnInPlaceSteerAngle(const RoverGeometry& g, int steer);
std::array<double, kNumSteered> TurnInPlaceSteerAngles(const RoverGeometry& g);
/// Signed wheel path per radian of counter-clockwise rotation, q_i [m/rad].
double TurnInPlaceRadius(const RoverGeometry& g, int wheel);
std::array<double, kNumWheels> TurnInPlaceRadii(const RoverGeometry& g);
/// Drive rates [rad/s] of the six wheels for a yaw rate w [rad/s] in place: q_i w / r.
std::array<double, kNumWheels> TurnInPlaceWheelRates(const RoverGeometry& g, double yaw_rate);

/// Everything a drive primitive needs to command the motors.
struct DrivePlan {
  bool turn_in_place = false;
  double curvature = 0.0;  ///< [1/m] (0 for a turn in place)
  double distance = 0.0;   ///< [m] reference path, signed (0 for a turn in place)
  double angle = 0.0;      ///< [rad] planned heading change: k s, or the turn angle
  double speed = 0.0;      ///< [m/s] reference speed used (arcs) or fastest wheel (turns)
  double yaw_rate = 0.0;   ///< [rad/s] magnitude of the planned yaw rate
  std::array<double, kNumSteered> steer_angle{};    ///< [rad]
  std::array<double, kNumWheels> wheel_distance{};  ///< [m] signed rim path
  std::array<double, kNumWheels> wheel_rotation{};  ///< [rad] signed
  std::array<double, kNumWheels> wheel_speed{};     ///< [m/s] signed
  std::array<double, kNumWheels> wheel_rate{};      ///< [rad/s] signed
  /// Turn centre in the rover frame (x_m, 1/k) or (x_m, 0); undefined (has_centre false) on
  /// a straight line.
  bool has_centre = false;
  Eigen::Vector2d turn_centre = Eigen::Vector2d::Zero();
};

/// Plans an arc (curvature 0 = straight). Errors: non-finite input (InvalidArgument), |k| above
/// MaxCurvature() or speed <= 0 (OutOfRange). Precondition: g.Validate() is ok.
Result<DrivePlan> PlanArc(const RoverGeometry& g, double curvature, double distance, double speed);
/// Plans a turn in place by `angle`. Errors: non-finite input, speed <= 0.
Result<DrivePlan> PlanTurnInPlace(const RoverGeometry& g, double angle, double speed);

}  // namespace rover::dl::locomotion
