#include "rover/sim/physics/motor_controller.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::sim::physics {
namespace {

// Checks lo <= v <= hi (and finite); returns an error naming `name.field`.
double Sign(double v) { return v > 0.0 ? 1.0 : (v < 0.0 ? -1.0 : 0.0); }

}  // namespace

const char* MotorModeName(MotorMode m) {
  switch (m) {
    case MotorMode::kOff:
      return "off";
    case MotorMode::kPosition:
      return "position";
    case MotorMode::kVelocity:
      return "velocity";
  }
  return "?";
}

double MotorParams::CountsPerRad() const {
  return encoder_counts_per_motor_rev * gear_ratio / (2.0 * std::numbers::pi);
}

Status MotorParams::Validate(const std::string& name) const {
  constexpr double kBig = 1e9;
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".gear_ratio", gear_ratio, 1e-3, kBig));
  ROVER_RETURN_IF_ERROR(
      CheckRange(name + ".encoder_counts_per_motor_rev", encoder_counts_per_motor_rev, 1.0, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".gear_efficiency", gear_efficiency, 1e-3, 1.0));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".torque_constant", torque_constant, 1e-6, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".rotor_inertia", rotor_inertia, 0.0, 1.0));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".winding_resistance", winding_resistance, 1e-6, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".bus_voltage", bus_voltage, 1e-3, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".no_load_current", no_load_current, 0.0, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".max_current", max_current, 1e-6, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".overcurrent_trip", overcurrent_trip, 1e-6, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".overcurrent_time", overcurrent_time, 0.0, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".stall_speed", stall_speed, 0.0, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".stall_error", stall_error, 0.0, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".stall_time", stall_time, 0.0, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".thermal_resistance", thermal_resistance, 0.0, kBig));
  ROVER_RETURN_IF_ERROR(
      CheckRange(name + ".thermal_time_constant", thermal_time_constant, 1e-6, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".max_temperature", max_temperature, -273.0, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".kp", kp, 0.0, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".ki", ki, 0.0, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".kd", kd, 0.0, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".integral_limit", integral_limit, 0.0, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".max_speed", max_speed, 1e-9, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".max_acceleration", max_acceleration, 1e-9, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".max_following_error", max_following_error, 1e-9, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".position_tolerance", position_tolerance, 0.0, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".brake_torque", brake_torque, 0.0, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".brake_kp", brake_kp, 0.0, kBig));
  ROVER_RETURN_IF_ERROR(CheckRange(name + ".brake_kd", brake_kd, 0.0, kBig));
  if (std::isnan(min_angle) || std::isnan(max_angle) || !(min_angle < max_angle)) {
    return InvalidArgument(name + ".min_angle/max_angle = [" + FormatNumber(min_angle) + ", " +
                           FormatNumber(max_angle) + "] is not an interval");
  }
  return Status::Ok();
}

MotorController::MotorController(const MotorParams& params, double ambient_c, double angle_rad)
    : params_(params), counts_per_rad_(params.CountsPerRad()) {
  ROVER_DEMAND(params.Validate("motor").ok());
  Reset(ambient_c, angle_rad);
}

void MotorController::Reset(double ambient_c, double angle_rad) {
  mode_ = MotorMode::kOff;
  faults_ = kMotorFaultNone;
  goal_rad_ = goal_rate_ = current_limit_ = 0.0;
  ref_ = angle_rad;
  ref_rate_ = 0.0;
  ref_valid_ = false;
  integral_ = 0.0;
  brake_angle_ = angle_rad;
  angle_ = angle_rad;
  rate_ = 0.0;
  torque_ = current_ = 0.0;
  ambient_c_ = ambient_c;
  temperature_ = ambient_c;
  stall_timer_ = overcurrent_timer_ = 0.0;
}

Status MotorController::SetGoal(MotorMode mode, double position_counts,
                                double velocity_counts_per_s, double current_limit_a) {
  if (faults_ != kMotorFaultNone) {
    return FailedPrecondition("motor has latched faults (0x" + FormatNumber(faults_) +
                              "); clear them before a new goal");
  }
  if (mode == MotorMode::kOff) {
    if (mode_ != MotorMode::kOff) {
      mode_ = MotorMode::kOff;
      brake_angle_ = angle_;
      ref_valid_ = false;
      integral_ = 0.0;
    }
    return Status::Ok();
  }
  if (mode != MotorMode::kPosition && mode != MotorMode::kVelocity) {
    return InvalidArgument("unknown motor mode " + FormatNumber(static_cast<int>(mode)));
  }
  if (!std::isfinite(position_counts) || !std::isfinite(velocity_counts_per_s) ||
      !std::isfinite(current_limit_a)) {
    return InvalidArgument("motor goal has a non-finite value");
  }
  if (!(current_limit_a > 0.0) || current_limit_a > params_.max_current) {
    return OutOfRange("current_limit " + FormatNumber(current_limit_a) + " A is outside (0, " +
                      FormatNumber(params_.max_current) + "]");
  }
  const double rate = velocity_counts_per_s / counts_per_rad_;
  if (std::abs(rate) > params_.max_speed * (1.0 + 1e-9)) {
    return OutOfRange("velocity " + FormatNumber(velocity_counts_per_s) +
                      " counts/s exceeds the maximum " +
                      FormatNumber(params_.max_speed * counts_per_rad_) + " counts/s");
  }
  const double goal = position_counts / counts_per_rad_;
  if (mode == MotorMode::kPosition) {
    if (!(rate > 0.0)) {
      return InvalidArgument("position goal needs a positive profile velocity, got " +
                             FormatNumber(velocity_counts_per_s) + " counts/s");
    }
    if (goal < params_.min_angle || goal > params_.max_angle) {
      return OutOfRange("position " + FormatNumber(position_counts) + " counts (" +
                        FormatNumber(goal) + " rad) is outside the joint range [" +
                        FormatNumber(params_.min_angle) + ", " + FormatNumber(params_.max_angle) +
                        "] rad");
    }
  }
  if (!ref_valid_) {
    ref_ = angle_;
    ref_rate_ = 0.0;
    integral_ = 0.0;
    ref_valid_ = true;
  }
  mode_ = mode;
  goal_rad_ = goal;
  goal_rate_ = rate;
  current_limit_ = current_limit_a;
  stall_timer_ = 0.0;
  return Status::Ok();
}

void MotorController::ClearFaults() {
  faults_ = kMotorFaultNone;
  stall_timer_ = overcurrent_timer_ = 0.0;
}

void MotorController::Trip(std::uint32_t fault) {
  faults_ |= fault;
  mode_ = MotorMode::kOff;
  brake_angle_ = angle_;
  ref_valid_ = false;
  integral_ = 0.0;
}

double MotorController::Update(double angle_rad, double rate_rad_s, double dt_s) {
  ROVER_DEMAND(dt_s > 0.0);
  angle_ = angle_rad;
  rate_ = rate_rad_s;
  const MotorParams& p = params_;
  double current_signed = 0.0;

  if (mode_ == MotorMode::kOff) {
    // Power-off brake: stiff hold, slipping (moving its anchor) above the holding torque.
    double t = -p.brake_kp * (angle_ - brake_angle_) - p.brake_kd * rate_;
    if (std::abs(t) > p.brake_torque) {
      t = Sign(t) * p.brake_torque;
      if (p.brake_kp > 0.0) {
        const double stretch = angle_ - brake_angle_;
        const double max_stretch = p.brake_torque / p.brake_kp;
        if (std::abs(stretch) > max_stretch) brake_angle_ = angle_ - Sign(stretch) * max_stretch;
      }
    }
    torque_ = t;
  } else {
    // Reference profile.
    const double a_step = p.max_acceleration * dt_s;
    if (mode_ == MotorMode::kVelocity) {
      ref_rate_ += std::clamp(goal_rate_ - ref_rate_, -a_step, a_step);
      ref_ += ref_rate_ * dt_s;
    } else {
      const double d = goal_rad_ - ref_;
      const double v_des =
          Sign(d) * std::min(goal_rate_, std::sqrt(2.0 * p.max_acceleration * std::abs(d)));
      ref_rate_ += std::clamp(v_des - ref_rate_, -a_step, a_step);
      const double step = ref_rate_ * dt_s;
      if (d == 0.0 || (d > 0.0 && step >= d) || (d < 0.0 && step <= d) || (std::abs(d) < 1e-9)) {
        ref_ = goal_rad_;
        ref_rate_ = 0.0;
      } else {
        ref_ += step;
      }
    }
    // The reference waits for a blocked joint.
    const double fe = ref_ - angle_;
    if (std::abs(fe) > p.max_following_error) ref_ = angle_ + Sign(fe) * p.max_following_error;

    // PID at the output shaft.
    const double e = ref_ - angle_;
    integral_ = std::clamp(integral_ + p.ki * e * dt_s, -p.integral_limit, p.integral_limit);
    const double tau_cmd = p.kp * e + integral_ + p.kd * (ref_rate_ - rate_);

    // DC motor: current limit and the voltage (torque-speed) limit.
    const double k_t = p.torque_constant;
    const double w_m = p.gear_ratio * rate_;
    const double i_cmd = tau_cmd / p.TorquePerAmp();
    const double lo = std::clamp((-p.bus_voltage - k_t * w_m) / p.winding_resistance,
                                 -current_limit_, current_limit_);
    const double hi = std::clamp((p.bus_voltage - k_t * w_m) / p.winding_resistance,
                                 -current_limit_, current_limit_);
    current_signed = std::clamp(i_cmd, lo, hi);
    torque_ = current_signed * p.TorquePerAmp();

    // Stall: commanded to move but not moving.
    const bool commanded = std::abs(ref_rate_) > p.stall_speed || std::abs(e) > p.stall_error;
    if (commanded && std::abs(rate_) < p.stall_speed) {
      stall_timer_ += dt_s;
    } else {
      stall_timer_ = 0.0;
    }
  }

  const bool moving = std::abs(rate_) > p.stall_speed;
  current_ =
      std::abs(current_signed) + ((mode_ != MotorMode::kOff && moving) ? p.no_load_current : 0.0);

  // Winding temperature: first order, exact over the period for constant power.
  const double power = current_ * current_ * p.winding_resistance;
  const double t_ss = ambient_c_ + power * p.thermal_resistance;
  temperature_ += (t_ss - temperature_) * (1.0 - std::exp(-dt_s / p.thermal_time_constant));

  // Faults (the torque already computed is still applied for this period; the motor is off
  // from the next one, as a real controller notices a fault only after sampling it).
  if (mode_ != MotorMode::kOff) {
    overcurrent_timer_ = current_ > p.overcurrent_trip ? overcurrent_timer_ + dt_s : 0.0;
    if (overcurrent_timer_ >= p.overcurrent_time && current_ > p.overcurrent_trip) {
      Trip(kMotorFaultOverCurrent);
    }
    if (stall_timer_ >= p.stall_time && p.stall_time > 0.0) Trip(kMotorFaultStall);
  } else {
    overcurrent_timer_ = 0.0;
  }
  if (temperature_ > p.max_temperature) {
    if (mode_ != MotorMode::kOff || (faults_ & kMotorFaultOverTemperature) == 0) {
      Trip(kMotorFaultOverTemperature);
    }
  }
  return torque_;
}

MotorReading MotorController::Reading() const {
  MotorReading r;
  r.mode = mode_;
  r.faults = faults_;
  r.position_counts = angle_ * counts_per_rad_;
  r.velocity_counts_per_s = rate_ * counts_per_rad_;
  r.reference_counts = (mode_ == MotorMode::kOff ? angle_ : ref_) * counts_per_rad_;
  r.current_a = current_;
  r.temperature_c = temperature_;
  r.torque_nm = torque_;
  r.goal_reached = mode_ == MotorMode::kPosition && ref_ == goal_rad_ &&
                   std::abs(angle_ - goal_rad_) <= params_.position_tolerance;
  return r;
}

}  // namespace rover::sim::physics
