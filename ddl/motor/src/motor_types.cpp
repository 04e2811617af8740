#include "rover/ddl/motor/motor_types.hpp"

#include <cmath>

namespace rover::ddl::motor {

const char* CommandErrorName(CommandError e) {
  switch (e) {
    case CommandError::kNone:
      return "none";
    case CommandError::kUnknownMode:
      return "unknown_mode";
    case CommandError::kEmptyMask:
      return "empty_mask";
    case CommandError::kUnknownMotor:
      return "unknown_motor";
    case CommandError::kNonFiniteGoal:
      return "non_finite_goal";
    case CommandError::kBadRate:
      return "bad_rate";
    case CommandError::kRateAboveLimit:
      return "rate_above_limit";
    case CommandError::kGoalOutOfRange:
      return "goal_out_of_range";
    case CommandError::kBadTimeout:
      return "bad_timeout";
    case CommandError::kTimeoutTooShort:
      return "timeout_too_short";
    case CommandError::kNoTelemetry:
      return "no_telemetry";
  }
  return "?";
}

MotorReadings DecodeMotorTelemetry(const HardwareConfig& config, const hw::MotorTelemetry& t) {
  MotorReadings r;
  r.stamp_ns = t.stamp_ns;
  r.command_id = t.command_id;
  for (std::size_t i = 0; i < t.motors.size(); ++i) {
    const double cpr = config.motors[i].CountsPerRad();
    const hw::MotorReading& m = t.motors[i];
    r.position[i] = m.position / cpr;
    r.velocity[i] = m.velocity / cpr;
    r.current[i] = config.telemetry.CurrentFromCounts(m.current_adc);
    r.temperature[i] = config.telemetry.TemperatureFromCounts(m.temperature_adc);
    r.flags[i] = m.flags;
  }
  return r;
}

Status MotorManagerOptions::Validate() const {
  auto positive = [](const char* k, double v) -> Status {
    if (!std::isfinite(v) || v <= 0.0) {
      return InvalidArgument(std::string("motor_manager.") + k + ": " + std::to_string(v) +
                             " must be finite and > 0");
    }
    return Status::Ok();
  };
  ROVER_RETURN_IF_ERROR(positive("stall_window_s", stall_window_s));
  ROVER_RETURN_IF_ERROR(positive("stall_fraction", stall_fraction));
  if (stall_fraction > 1.0) {
    return InvalidArgument("motor_manager.stall_fraction: " + std::to_string(stall_fraction) +
                           " must be <= 1");
  }
  ROVER_RETURN_IF_ERROR(positive("stall_min_motion", stall_min_motion));
  ROVER_RETURN_IF_ERROR(positive("stall_max_lag", stall_max_lag));
  if (!(overcurrent_margin >= 0.0 && overcurrent_margin <= 2.0)) {
    return InvalidArgument("motor_manager.overcurrent_margin: " +
                           std::to_string(overcurrent_margin) + " must be in [0, 2]");
  }
  ROVER_RETURN_IF_ERROR(positive("overcurrent_time_s", overcurrent_time_s));
  ROVER_RETURN_IF_ERROR(positive("overtemp_time_s", overtemp_time_s));
  ROVER_RETURN_IF_ERROR(positive("telemetry_timeout_s", telemetry_timeout_s));
  ROVER_RETURN_IF_ERROR(positive("apply_timeout_s", apply_timeout_s));
  ROVER_RETURN_IF_ERROR(positive("timeout_factor", timeout_factor));
  if (timeout_factor < 1.0) {
    return InvalidArgument("motor_manager.timeout_factor: " + std::to_string(timeout_factor) +
                           " must be >= 1");
  }
  if (!std::isfinite(timeout_margin_s) || timeout_margin_s < 0.0) {
    return InvalidArgument("motor_manager.timeout_margin_s: must be finite and >= 0");
  }
  ROVER_RETURN_IF_ERROR(positive("velocity_timeout_s", velocity_timeout_s));
  ROVER_RETURN_IF_ERROR(positive("settle_rate", settle_rate));
  return Status::Ok();
}

namespace {
std::string Join(const std::string& prefix, const std::string& key) {
  return prefix.empty() ? key : prefix + "." + key;
}
}  // namespace

void DeclareMotorManagerParams(ParamSet& ps, const std::string& prefix) {
  const MotorManagerOptions d;
  auto key = [&prefix](const char* k) { return Join(prefix, k); };
  ps.Declare(key("stall_window_s"), d.stall_window_s, "[s] window over which progress is judged")
      .Range(0.05, 60.0);
  ps.Declare(key("stall_fraction"), d.stall_fraction,
             "stall if a motor made less than this fraction of its planned progress")
      .Range(0.01, 1.0);
  ps.Declare(key("stall_min_motion"), d.stall_min_motion,
             "[rad] windows with less planned motion are not judged")
      .Range(1e-5, 1.0);
  ps.Declare(key("stall_max_lag"), d.stall_max_lag,
             "[rad] ... and only when the motor is this far behind its planned position since "
             "the group started")
      .Range(1e-3, 100.0);
  ps.Declare(key("overcurrent_margin"), d.overcurrent_margin,
             "the over-current monitor trips above current_limit * (1 + margin); the controller "
             "itself saturates at current_limit (a motor held there is a stall)")
      .Range(0.0, 2.0);
  ps.Declare(key("overcurrent_time_s"), d.overcurrent_time_s,
             "[s] current above the limit this long trips the group")
      .Range(0.001, 10.0);
  ps.Declare(key("overtemp_time_s"), d.overtemp_time_s,
             "[s] temperature above the limit this long trips the group")
      .Range(0.001, 60.0);
  ps.Declare(key("telemetry_timeout_s"), d.telemetry_timeout_s,
             "[s] telemetry silence that stops a running group")
      .Range(0.01, 60.0);
  ps.Declare(key("apply_timeout_s"), d.apply_timeout_s,
             "[s] goals not acknowledged by the controller this long stop the group")
      .Range(0.01, 60.0);
  ps.Declare(key("timeout_factor"), d.timeout_factor,
             "default timeout = factor * planned duration + margin")
      .Range(1.0, 100.0);
  ps.Declare(key("timeout_margin_s"), d.timeout_margin_s, "[s] see timeout_factor")
      .Range(0.0, 3600.0);
  ps.Declare(key("velocity_timeout_s"), d.velocity_timeout_s,
             "[s] run time of velocity groups whose command gives no timeout")
      .Range(0.01, 3600.0);
  ps.Declare(key("settle_rate"), d.settle_rate, "[rad/s] at-goal rate threshold").Range(1e-5, 10.0);
  ps.Declare(key("brake_when_done"), d.brake_when_done,
             "brake a group's motors when it reaches its goals");
}

Result<MotorManagerOptions> MotorManagerOptionsFromParams(const ParamSet& ps,
                                                          const std::string& prefix) {
  ROVER_RETURN_IF_ERROR(ps.Validate());
  auto d = [&](const char* k) { return ps.GetDouble(Join(prefix, k)); };
  MotorManagerOptions o;
  o.stall_window_s = d("stall_window_s");
  o.stall_fraction = d("stall_fraction");
  o.stall_min_motion = d("stall_min_motion");
  o.stall_max_lag = d("stall_max_lag");
  o.overcurrent_margin = d("overcurrent_margin");
  o.overcurrent_time_s = d("overcurrent_time_s");
  o.overtemp_time_s = d("overtemp_time_s");
  o.telemetry_timeout_s = d("telemetry_timeout_s");
  o.apply_timeout_s = d("apply_timeout_s");
  o.timeout_factor = d("timeout_factor");
  o.timeout_margin_s = d("timeout_margin_s");
  o.velocity_timeout_s = d("velocity_timeout_s");
  o.settle_rate = d("settle_rate");
  o.brake_when_done = ps.GetBool(Join(prefix, "brake_when_done"));
  ROVER_RETURN_IF_ERROR(o.Validate());
  return o;
}

}  // namespace rover::ddl::motor
