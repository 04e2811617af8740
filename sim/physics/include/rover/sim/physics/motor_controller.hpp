#pragma once
/// @file
/// The simulated motor controller of one actuator, as MER's motor-control FPGA ran it: a PID
/// at 1 kHz on an encoder-count goal (position or velocity), a DC motor behind a gearhead with a
/// torque (current) limit, current draw, stall detection, an over-current trip and a winding
/// temperature with an over-temperature trip. Pure C++ (no Simbody): the physics asks it for the
/// output torque once per control period and holds that torque for the period (zero-order hold).
///
/// Units and signs: angles and rates at the *output* shaft (joint) in rad and rad/s; goals and
/// readings in encoder counts (the encoder sits on the motor shaft, so
///   counts_per_rad = encoder_counts_per_motor_rev * gear_ratio / (2 pi)).
/// Torque [N m] at the output shaft; current [A] in the motor winding; temperature [deg C].
///
/// Motor model (per control period, motor side: w_m = N w, k_e = k_t in SI):
///   tau_cmd = kp e + I + kd (v_ref - w),  e = r - theta,  I += ki e dt, |I| <= integral_limit
///   i_cmd   = tau_cmd / (eta N k_t)
///   i_lo    = clamp((-V - k_t w_m) / R, +-I_lim),  i_hi = clamp((V - k_t w_m) / R, +-I_lim)
///   i       = clamp(i_cmd, i_lo, i_hi)   (the driver limits the current both ways; the bus
///                                         voltage and back-EMF: the torque-speed curve)
///   tau     = eta N k_t i                      (torque applied to the joint for the period)
///   current = |i| + i0 [if |w| > stall_speed]  (reported bus-side magnitude)
///   T'      = (T_amb + current^2 R R_th - T) / tau_th   (integrated exactly over the period)
/// r, v_ref: reference trajectory. Velocity mode ramps v_ref to the goal at max_acceleration and
/// integrates r; position mode runs a trapezoidal profile to the goal at the commanded speed.
/// The reference waits for the joint when |r - theta| > max_following_error (no wind-up).
///
/// Faults latch, disable the motor (brake engaged, zero current) and must be cleared with
/// ClearFaults() before a new goal is accepted:
///   stall:           motion commanded (|v_ref| > stall_speed or |e| > stall_error) while
///                    |w| < stall_speed, continuously for stall_time;
///   over-current:    current > overcurrent_trip continuously for overcurrent_time;
///   over-temperature: winding temperature > max_temperature.
/// Mode kOff and any fault engage the power-off brake: a stiff hold of the angle at which it
/// engaged, limited to brake_torque (MER actuators were not back-drivable through their gears).

#include <cstdint>
#include <limits>
#include <string>

#include "rover/base/status.hpp"

namespace rover::sim::physics {

enum class MotorMode : std::uint8_t {
  kOff = 0,       ///< unpowered, brake engaged
  kPosition = 1,  ///< move to an absolute count at a commanded speed, then hold
  kVelocity = 2,  ///< run at a commanded count rate (reference position integrates it)
};
const char* MotorModeName(MotorMode m);

/// Fault bits (latched).
enum MotorFault : std::uint32_t {
  kMotorFaultNone = 0,
  kMotorFaultStall = 1u << 0,
  kMotorFaultOverCurrent = 1u << 1,
  kMotorFaultOverTemperature = 1u << 2,
};

struct MotorParams {
  // Gearhead and encoder.
  double gear_ratio = 1500.0;                  ///< motor turns per output turn
  double encoder_counts_per_motor_rev = 64.0;  ///< quadrature counts per motor turn
  double gear_efficiency = 0.6;                ///< (0, 1]
  // DC motor.
  double torque_constant = 0.02;        ///< k_t [N m/A] (= back-EMF constant [V s/rad])
  double rotor_inertia = 1.0e-7;        ///< J_m [kg m^2] of rotor and gear input, motor side
  double winding_resistance = 3.0;      ///< R [ohm]
  double bus_voltage = 28.0;            ///< V [V]
  double no_load_current = 0.03;        ///< i0 [A], drawn while turning
  double max_current = 1.5;             ///< driver saturation [A]; goals may not ask for more
  double overcurrent_trip = 1.3;        ///< [A]
  double overcurrent_time = 0.05;       ///< [s]
  double stall_speed = 0.01;            ///< [rad/s] at the output
  double stall_error = 0.05;            ///< [rad] following error that counts as "commanded"
  double stall_time = 0.5;              ///< [s]; 0 disables stall detection
  double thermal_resistance = 8.0;      ///< winding to ambient [K/W]
  double thermal_time_constant = 60.0;  ///< [s]
  double max_temperature = 110.0;       ///< [deg C]
  // PID at the output shaft.
  double kp = 60.0;              ///< [N m/rad]
  double ki = 30.0;              ///< [N m/(rad s)]
  double kd = 8.0;               ///< [N m s/rad]
  double integral_limit = 10.0;  ///< [N m] bound of the integral term
  // Reference profile.
  double max_speed = 0.9;             ///< [rad/s] goals faster than this are rejected
  double max_acceleration = 2.0;      ///< [rad/s^2]
  double max_following_error = 0.2;   ///< [rad]
  double position_tolerance = 0.002;  ///< [rad] "goal reached" band
  // Joint range (position goals outside are rejected); infinite for wheels.
  double min_angle = -std::numeric_limits<double>::infinity();  ///< [rad]
  double max_angle = std::numeric_limits<double>::infinity();   ///< [rad]
  // Power-off brake.
  double brake_torque = 40.0;  ///< [N m] holding limit
  double brake_kp = 400.0;     ///< [N m/rad]
  double brake_kd = 15.0;      ///< [N m s/rad]

  double CountsPerRad() const;
  /// Torque at the output per ampere of winding current: eta N k_t [N m/A].
  double TorquePerAmp() const { return gear_efficiency * gear_ratio * torque_constant; }
  /// Rotor inertia seen at the output, J_m N^2 [kg m^2] (the physics adds it to the joint).
  double ReflectedInertia() const { return rotor_inertia * gear_ratio * gear_ratio; }
  /// `name` prefixes the messages (e.g. "motors[3]").
  Status Validate(const std::string& name) const;
};

/// Ideal readings of one motor (no noise, no quantisation).
struct MotorReading {
  MotorMode mode = MotorMode::kOff;
  std::uint32_t faults = kMotorFaultNone;
  double position_counts = 0.0;  ///< joint angle * counts_per_rad
  double velocity_counts_per_s = 0.0;
  double reference_counts = 0.0;  ///< the profile's current reference
  double current_a = 0.0;
  double temperature_c = 0.0;
  double torque_nm = 0.0;     ///< output torque applied this period
  bool goal_reached = false;  ///< position mode: profile done and |e| < tolerance
};

class MotorController {
 public:
  MotorController() = default;
  /// Preconditions: params.Validate() is ok.
  MotorController(const MotorParams& params, double ambient_c, double angle_rad);

  /// Resets to kOff (brake at `angle_rad`), clears faults, temperature to ambient.
  void Reset(double ambient_c, double angle_rad);

  /// Sets a goal. position_counts: absolute target (kPosition); velocity_counts_per_s: profile
  /// speed (> 0) in kPosition, signed rate in kVelocity; current_limit_a in (0, max_current].
  /// kOff ignores the numbers. Errors: non-finite or out-of-range values (kInvalidArgument /
  /// kOutOfRange); latched faults (kFailedPrecondition).
  Status SetGoal(MotorMode mode, double position_counts, double velocity_counts_per_s,
                 double current_limit_a);

  /// One control period: measured output angle [rad] and rate [rad/s] -> output torque [N m] to
  /// hold for the next `dt_s` seconds. Updates current, temperature and faults.
  double Update(double angle_rad, double rate_rad_s, double dt_s);

  void ClearFaults();
  /// Sets the ambient temperature used by the thermal model [deg C].
  void set_ambient_c(double ambient_c) { ambient_c_ = ambient_c; }

  MotorReading Reading() const;
  const MotorParams& params() const { return params_; }
  std::uint32_t faults() const { return faults_; }
  MotorMode mode() const { return mode_; }

 private:
  void Trip(std::uint32_t fault);

  MotorParams params_;
  double counts_per_rad_ = 1.0;
  MotorMode mode_ = MotorMode::kOff;
  std::uint32_t faults_ = kMotorFaultNone;
  double goal_rad_ = 0.0;   // position goal
  double goal_rate_ = 0.0;  // velocity goal or profile speed
  double current_limit_ = 0.0;
  double ref_ = 0.0;        // reference angle
  double ref_rate_ = 0.0;   // reference rate
  bool ref_valid_ = false;  // reference initialised from the measured angle
  double integral_ = 0.0;   // integral term [N m]
  double brake_angle_ = 0.0;
  double angle_ = 0.0, rate_ = 0.0;  // last measurement
  double torque_ = 0.0, current_ = 0.0;
  double temperature_ = 0.0, ambient_c_ = 0.0;
  double stall_timer_ = 0.0, overcurrent_timer_ = 0.0;
};

}  // namespace rover::sim::physics
