#pragma once
/// @file
/// Synchronised multi-motor moves (MER's MOT): every motor of a group runs a trapezoidal
/// profile (acceleration a, cruise rate v, deceleration a) and the rates are chosen so that all
/// profiles END AT THE SAME TIME.
///
/// One profile over distance d >= 0:
///   trapezoid (d >= v^2 / a): T(v) = d / v + v / a
///   triangle  (d <  v^2 / a): peak rate sqrt(a d), T = 2 sqrt(d / a)
/// Synchronisation: T* = max_i T_i(v_max,i) (the slowest motor at its rate limit); every motor
/// then gets the rate v_i with T_i(v_i) = T*, the smaller root of  v^2 - a T* v + a d = 0:
///   v_i = (a T* - sqrt(a^2 T*^2 - 4 a d)) / 2     (real since T* >= 2 sqrt(d / a); v_i <=
///   sqrt(a d), so the profile is a trapezoid or the limiting triangle).
/// This assumes the controller ramps every motor with its configured acceleration
/// (MotorSpec::max_acceleration), as the simulated controller does.

#include <vector>

namespace rover::ddl::motor {

struct AxisMove {
  double distance = 0.0;      ///< [rad] >= 0
  double max_rate = 1.0;      ///< [rad/s] > 0
  double acceleration = 1.0;  ///< [rad/s^2] > 0
};

struct SyncPlan {
  double duration_s = 0.0;    ///< common finishing time T*
  std::vector<double> rates;  ///< [rad/s] per axis; 0 for axes with zero distance
};

/// Duration of one profile at rate limit `rate`. Preconditions: distance >= 0, rate > 0, accel > 0.
double ProfileDuration(double distance, double rate, double acceleration);

/// Distance covered by the profile (distance, rate, acceleration) after `t` seconds (0 for
/// t <= 0, `distance` after the profile ends).
double ProfilePosition(double distance, double rate, double acceleration, double t);

/// Distance covered after `t` seconds by a velocity ramp from rest to `rate` at `acceleration`.
double RampPosition(double rate, double acceleration, double t);

/// The synchronised plan. Preconditions as ProfileDuration for every axis.
SyncPlan PlanSynchronisedMove(const std::vector<AxisMove>& axes);

}  // namespace rover::ddl::motor
