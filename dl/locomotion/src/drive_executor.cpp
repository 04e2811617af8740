#include "rover/dl/locomotion/drive_executor.hpp"

#include "rover/dl/locomotion/wheel_odometry.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/units.hpp"

namespace rover::dl::locomotion {
namespace {

double Wrap(double a) {
  if (!std::isfinite(a)) return a;
  a = std::remainder(a, 2.0 * std::numbers::pi);
  if (a <= -std::numbers::pi) a += 2.0 * std::numbers::pi;
  return a;
}

bool AttitudeFinite(const msg::AttitudeSample& a) {
  return std::isfinite(a.roll) && std::isfinite(a.pitch) && std::isfinite(a.yaw);
}

}  // namespace

// ---- options ----------------------------------------------------------------------------------

Status DriveOptions::Validate() const {
  auto positive = [](double v, const char* name) -> Status {
    if (!std::isfinite(v) || v <= 0.0) {
      return InvalidArgument(std::string("DriveOptions.") + name + ": " + FormatNumber(v) +
                             " must be > 0");
    }
    return Status::Ok();
  };
  ROVER_RETURN_IF_ERROR(positive(check_rate_hz, "check_rate_hz"));
  ROVER_RETURN_IF_ERROR(positive(default_speed, "default_speed"));
  ROVER_RETURN_IF_ERROR(positive(max_speed, "max_speed"));
  ROVER_RETURN_IF_ERROR(positive(max_distance, "max_distance"));
  ROVER_RETURN_IF_ERROR(positive(max_turn_angle, "max_turn_angle"));
  ROVER_RETURN_IF_ERROR(positive(max_timeout_s, "max_timeout_s"));
  ROVER_RETURN_IF_ERROR(positive(steer_tolerance, "steer_tolerance"));
  ROVER_RETURN_IF_ERROR(positive(steer_rate, "steer_rate"));
  ROVER_RETURN_IF_ERROR(positive(wheel_goal_tolerance, "wheel_goal_tolerance"));
  ROVER_RETURN_IF_ERROR(positive(heading_tolerance, "heading_tolerance"));
  ROVER_RETURN_IF_ERROR(positive(turn_gain, "turn_gain"));
  ROVER_RETURN_IF_ERROR(positive(min_turn_rate, "min_turn_rate"));
  ROVER_RETURN_IF_ERROR(positive(max_tilt, "max_tilt"));
  ROVER_RETURN_IF_ERROR(positive(joint_stale_s, "joint_stale_s"));
  ROVER_RETURN_IF_ERROR(positive(attitude_stale_s, "attitude_stale_s"));
  ROVER_RETURN_IF_ERROR(positive(timeout_factor, "timeout_factor"));
  if (!std::isfinite(timeout_margin_s) || timeout_margin_s < 0.0) {
    return InvalidArgument("DriveOptions.timeout_margin_s: " + FormatNumber(timeout_margin_s) +
                           " must be >= 0");
  }
  if (default_speed > max_speed) {
    return InvalidArgument("DriveOptions.default_speed: " + FormatNumber(default_speed) +
                           " exceeds max_speed " + FormatNumber(max_speed));
  }
  if (tilt_cycles < 1) return InvalidArgument("DriveOptions.tilt_cycles: must be >= 1");
  if (suspension_cycles < 1) {
    return InvalidArgument("DriveOptions.suspension_cycles: must be >= 1");
  }
  if (!(rocker_min < rocker_max)) {
    return InvalidArgument("DriveOptions.rocker_min: " + FormatNumber(rocker_min) +
                           " must be below rocker_max " + FormatNumber(rocker_max));
  }
  if (!(bogie_min < bogie_max)) {
    return InvalidArgument("DriveOptions.bogie_min: " + FormatNumber(bogie_min) +
                           " must be below bogie_max " + FormatNumber(bogie_max));
  }
  return Status::Ok();
}

// ---- construction and inputs ------------------------------------------------------------------

Result<DriveExecutor> DriveExecutor::Create(const RoverGeometry& geometry,
                                            const DriveOptions& options) {
  ROVER_RETURN_IF_ERROR(geometry.Validate());
  ROVER_RETURN_IF_ERROR(options.Validate());
  return DriveExecutor(geometry, options);
}

Status DriveExecutor::OnJointState(const msg::JointState& sample) {
  if (!msg::IsUsable(sample.health) || !sample.AllFinite()) return Status::Ok();
  if (joint_.has_value() && sample.stamp < joint_->stamp) return Status::Ok();
  if (joint_.has_value()) ROVER_RETURN_IF_ERROR(CheckWheelJump(*joint_, sample));
  joint_ = sample;
  return Status::Ok();
}

void DriveExecutor::OnAttitude(const msg::AttitudeSample& sample) {
  if (!sample.healthy || !AttitudeFinite(sample)) return;
  if (attitude_.has_value() && sample.stamp < attitude_->stamp) return;
  if (phase_ != Phase::kIdle) {
    heading_change_ += Wrap(sample.yaw - last_yaw_);
    last_yaw_ = sample.yaw;
  }
  attitude_ = sample;
}

void DriveExecutor::OnMotorStatus(const msg::MotorStatus& status) { motor_status_ = status; }

// ---- command checking -------------------------------------------------------------------------

InvalidReason DriveExecutor::CheckCommand(const DriveCommand& c, std::string* message) const {
  std::string dummy;
  std::string& m = message != nullptr ? *message : dummy;
  if (!IsKnownPrimitive(c.primitive)) {
    m = "unknown primitive " + std::to_string(static_cast<std::int32_t>(c.primitive));
    return InvalidReason::kUnknownPrimitive;
  }
  const DrivePrimitive p = c.primitive;
  if (p == DrivePrimitive::kStop) return InvalidReason::kNone;
  const bool uses_curvature = p == DrivePrimitive::kArc || p == DrivePrimitive::kSteer;
  const bool uses_distance = p == DrivePrimitive::kArc || p == DrivePrimitive::kStraight;
  const bool uses_angle = p == DrivePrimitive::kTurnInPlace;
  const bool uses_speed = p != DrivePrimitive::kSteer;
  struct Field {
    bool used;
    const char* name;
    double value;
  };
  const Field fields[] = {{uses_curvature, "curvature", c.curvature},
                          {uses_distance, "distance", c.distance},
                          {uses_angle, "angle", c.angle},
                          {uses_speed, "speed", c.speed},
                          {true, "timeout_s", c.timeout_s}};
  for (const Field& f : fields) {
    if (f.used && !std::isfinite(f.value)) {
      m = std::string(f.name) + " is " + FormatNumber(f.value) + " (must be finite)";
      return InvalidReason::kNonFinite;
    }
  }
  if (uses_curvature && std::abs(c.curvature) > geometry_.MaxCurvature() * (1.0 + 1e-12)) {
    m = "curvature " + FormatNumber(c.curvature) +
        " 1/m: |curvature| must be <= " + FormatNumber(geometry_.MaxCurvature()) +
        " (min turn radius " + FormatNumber(geometry_.min_turn_radius) + " m)";
    return InvalidReason::kCurvatureOutOfRange;
  }
  if (uses_distance && std::abs(c.distance) > options_.max_distance) {
    m = "distance " + FormatNumber(c.distance) +
        " m: |distance| must be <= " + FormatNumber(options_.max_distance);
    return InvalidReason::kDistanceOutOfRange;
  }
  if (uses_angle && std::abs(c.angle) > options_.max_turn_angle) {
    m = "angle " + FormatNumber(c.angle) +
        " rad: |angle| must be <= " + FormatNumber(options_.max_turn_angle);
    return InvalidReason::kAngleOutOfRange;
  }
  if (uses_speed && (c.speed < 0.0 || c.speed > options_.max_speed)) {
    m = "speed " + FormatNumber(c.speed) + " m/s must be in [0, " +
        FormatNumber(options_.max_speed) + "] (0 = default)";
    return InvalidReason::kSpeedOutOfRange;
  }
  if (c.timeout_s < 0.0 || c.timeout_s > options_.max_timeout_s) {
    m = "timeout_s " + FormatNumber(c.timeout_s) + " must be in [0, " +
        FormatNumber(options_.max_timeout_s) + "] (0 = derived)";
    return InvalidReason::kTimeoutOutOfRange;
  }
  return InvalidReason::kNone;
}

// ---- helpers ----------------------------------------------------------------------------------

msg::MotorCommand DriveExecutor::NewCommand(Time now, std::uint16_t mask, GroupMode mode) {
  msg::MotorCommand c;
  c.stamp = now;
  c.command_id = next_motor_id_++;
  if (next_motor_id_ == 0) next_motor_id_ = 1;  // 0 is never used
  c.motor_mask = mask;
  c.mode = mode;
  last_motor_id_ = c.command_id;
  return c;
}

msg::MotorCommand DriveExecutor::StopCommand(Time now) {
  return NewCommand(now, kMobilityMotorMask, GroupMode::kStop);
}

msg::MotorCommand DriveExecutor::SteerCommand(Time now) {
  msg::MotorCommand c = NewCommand(now, kSteerMotorMask, GroupMode::kPosition);
  for (int j = 0; j < kNumSteered; ++j) {
    const auto m = static_cast<std::size_t>(SteerMotor(j));
    c.goal[m] = plan_.steer_angle[static_cast<std::size_t>(j)];
    c.max_rate[m] = options_.steer_rate;
  }
  // Position groups: the motor driver derives its own hardware time-out from the synchronised
  // move it plans; the drive's time-out is this executor's (TIMEOUT termination), so a command
  // time-out shorter than the move ends the drive here instead of being refused by the driver.
  c.timeout_s = 0.0;
  return c;
}

msg::MotorCommand DriveExecutor::DrivePositionCommand(Time now) {
  msg::MotorCommand c = NewCommand(now, kDriveMotorMask, GroupMode::kPosition);
  for (std::size_t i = 0; i < kNumWheels; ++i) {
    c.goal[i] = wheel_start_[i] + plan_.wheel_rotation[i];
    c.max_rate[i] = std::abs(plan_.wheel_rate[i]);
  }
  c.timeout_s = 0.0;  // see SteerCommand
  return c;
}

msg::MotorCommand DriveExecutor::TurnVelocityCommand(Time now, double yaw_rate) {
  msg::MotorCommand c = NewCommand(now, kDriveMotorMask, GroupMode::kVelocity);
  const std::array<double, kNumWheels> rates = TurnInPlaceWheelRates(geometry_, yaw_rate);
  for (std::size_t i = 0; i < kNumWheels; ++i) c.goal[i] = rates[i];
  c.timeout_s = RemainingTimeout(now);
  return c;
}

DriveStatus DriveExecutor::MakeStatus(Time now, std::uint32_t command_id, DrivePrimitive primitive,
                                      DriveState state, DriveTermination termination,
                                      std::string message) const {
  DriveStatus s;
  s.stamp = now;
  s.command_id = command_id;
  s.primitive = primitive;
  s.state = state;
  s.termination = termination;
  s.message = std::move(message);
  return s;
}

double DriveExecutor::RemainingTimeout(Time now) const {
  return std::max(0.0, timeout_s_ - ToSeconds(now - start_time_));
}

bool DriveExecutor::SensorsFresh(Time now, std::string* why) const {
  if (!joint_.has_value()) {
    *why = "no joint state received";
    return false;
  }
  const double joint_age = ToSeconds(now - joint_->stamp);
  if (joint_age > options_.joint_stale_s) {
    *why = "joint state is " + FormatNumber(joint_age) + " s old (limit " +
           FormatNumber(options_.joint_stale_s) + " s)";
    return false;
  }
  if (!attitude_.has_value()) {
    *why = "no attitude received";
    return false;
  }
  const double att_age = ToSeconds(now - attitude_->stamp);
  if (att_age > options_.attitude_stale_s) {
    *why = "attitude is " + FormatNumber(att_age) + " s old (limit " +
           FormatNumber(options_.attitude_stale_s) + " s)";
    return false;
  }
  return true;
}

bool DriveExecutor::SteeringReached() const {
  for (std::size_t j = 0; j < kNumSteered; ++j) {
    if (std::abs(joint_->steer_angle[j] - plan_.steer_angle[j]) > options_.steer_tolerance) {
      return false;
    }
  }
  return true;
}

double DriveExecutor::DistanceDone() const {
  if (phase_ != Phase::kDriving || !joint_.has_value()) return status_.distance_done;
  double sum = 0.0;
  for (std::size_t i = 0; i < kNumWheels; ++i) {
    sum += (joint_->wheel_angle[i] - wheel_start_[i]) * geometry_.wheel_radius / path_ratio_[i];
  }
  return sum / kNumWheels;
}

void DriveExecutor::Reject(const DriveCommand& command, Time now, DriveTermination termination,
                           InvalidReason reason, std::string message, DriveOutput* out) {
  DriveStatus s = MakeStatus(now, command.command_id, command.primitive, DriveState::kRejected,
                             termination, std::move(message));
  s.invalid_reason = reason;
  if (!busy()) {
    out->motor_commands.push_back(StopCommand(now));  // stay braked
    status_ = s;
  }
  out->statuses.push_back(std::move(s));
}

void DriveExecutor::Terminate(Time now, DriveTermination termination, std::string message,
                              DriveOutput* out) {
  status_.distance_done = DistanceDone();
  out->motor_commands.push_back(StopCommand(now));
  status_.stamp = now;
  status_.state =
      termination == DriveTermination::kNominal ? DriveState::kDone : DriveState::kFailed;
  status_.termination = termination;
  status_.heading_change = heading_change_;
  status_.message = std::move(message);
  phase_ = Phase::kIdle;
  out->statuses.push_back(status_);
}

// ---- commands ---------------------------------------------------------------------------------

DriveOutput DriveExecutor::Submit(const DriveCommand& command, Time now) {
  DriveOutput out;
  std::string why;
  const InvalidReason reason = CheckCommand(command, &why);
  if (reason != InvalidReason::kNone) {
    Reject(command, now, DriveTermination::kRejectedInvalid, reason,
           std::string("rejected: ") + why, &out);
    return out;
  }
  if (command.primitive == DrivePrimitive::kStop) {
    if (busy()) {
      Terminate(now, DriveTermination::kStopCommand,
                "stopped by command " + std::to_string(command.command_id), &out);
    } else {
      out.motor_commands.push_back(StopCommand(now));
    }
    status_ = MakeStatus(now, command.command_id, command.primitive, DriveState::kDone,
                         DriveTermination::kNominal, "all mobility motors stopped");
    out.statuses.push_back(status_);
    return out;
  }
  if (busy()) {
    Reject(command, now, DriveTermination::kRejectedBusy, InvalidReason::kNone,
           "rejected: busy with command " + std::to_string(command_.command_id) + " (" +
               DrivePrimitiveName(command_.primitive) + ")",
           &out);
    return out;
  }
  if (!SensorsFresh(now, &why)) {
    Reject(command, now, DriveTermination::kStaleSensor, InvalidReason::kNone, "rejected: " + why,
           &out);
    return out;
  }
  if (options_.require_arm_stowed && joint_) {
    for (std::size_t j = 0; j < geometry_.arm_stow.size(); ++j) {
      const double off = joint_->arm_angle[j] - geometry_.arm_stow[j];
      if (!(std::abs(off) <= options_.arm_stow_tolerance)) {
        static constexpr const char* kJoint[] = {"azimuth", "shoulder", "elbow", "wrist"};
        Reject(command, now, DriveTermination::kRejectedInvalid, InvalidReason::kArmNotStowed,
               std::string("rejected: the arm is not stowed (") + kJoint[j] + " " +
                   FormatNumber(off, 3) + " rad from its stowed angle): stow it first",
               &out);
        return out;
      }
    }
  }

  const double speed = command.speed > 0.0 ? command.speed : options_.default_speed;
  Result<DrivePlan> plan = Internal("no plan");
  switch (command.primitive) {
    case DrivePrimitive::kArc:
      plan = PlanArc(geometry_, command.curvature, command.distance, speed);
      break;
    case DrivePrimitive::kStraight:
      plan = PlanArc(geometry_, 0.0, command.distance, speed);
      break;
    case DrivePrimitive::kTurnInPlace:
      plan = PlanTurnInPlace(geometry_, command.angle, speed);
      break;
    case DrivePrimitive::kSteer:
      plan = PlanArc(geometry_, command.curvature, 0.0, speed);
      break;
    case DrivePrimitive::kStop:
      ROVER_UNREACHABLE();
  }
  if (!plan.ok()) {
    Reject(command, now, DriveTermination::kRejectedInvalid, InvalidReason::kNonFinite,
           "rejected: " + plan.status().message(), &out);
    return out;
  }
  command_ = command;
  plan_ = std::move(plan).value();
  path_ratio_ = ArcPathRatios(geometry_, plan_.curvature);
  start_time_ = now;
  heading_change_ = 0.0;
  last_yaw_ = attitude_->yaw;
  commanded_yaw_rate_ = 0.0;
  tilt_count_ = 0;
  suspension_count_ = 0;
  last_cycle_ = now;
  wheel_start_ = joint_->wheel_angle;

  if (command.timeout_s > 0.0) {
    timeout_s_ = command.timeout_s;
  } else {
    double steer_s = 0.0;
    for (std::size_t j = 0; j < kNumSteered; ++j) {
      steer_s = std::max(
          steer_s, std::abs(plan_.steer_angle[j] - joint_->steer_angle[j]) / options_.steer_rate);
    }
    double drive_s = 0.0;
    if (plan_.turn_in_place) {
      drive_s = std::abs(plan_.angle) / plan_.yaw_rate;
    } else if (command.primitive != DrivePrimitive::kSteer) {
      drive_s = std::abs(plan_.distance) / plan_.speed;
    }
    timeout_s_ = options_.timeout_factor * (steer_s + drive_s) + options_.timeout_margin_s;
  }

  phase_ = Phase::kSteering;
  first_motor_id_ = next_motor_id_;
  out.motor_commands.push_back(SteerCommand(now));
  status_ = MakeStatus(now, command.command_id, command.primitive, DriveState::kSteering,
                       DriveTermination::kNone, "steering");
  out.statuses.push_back(status_);
  return out;
}

DriveOutput DriveExecutor::Step(Time now) {
  DriveOutput out;
  if (phase_ == Phase::kIdle) return out;
  const double period = 1.0 / options_.check_rate_hz;
  if (last_cycle_.has_value() && ToSeconds(now - *last_cycle_) < 0.9 * period) return out;
  last_cycle_ = now;
  RunCycle(now, &out);
  return out;
}

void DriveExecutor::RunCycle(Time now, DriveOutput* out) {
  // 1. Motor group faults on a group of this primitive.
  if (motor_status_.has_value()) {
    const msg::MotorStatus& m = *motor_status_;
    const bool ours = m.command_id >= first_motor_id_ && m.command_id <= last_motor_id_;
    const bool superseded_stop = m.fault == MotorFault::kStopped && m.command_id != last_motor_id_;
    if (ours && !superseded_stop &&
        (m.state == GroupState::kFault || m.state == GroupState::kRejected)) {
      DriveTermination t = DriveTermination::kMotorFault;
      if (m.fault == MotorFault::kStall) t = DriveTermination::kMotorStall;
      if (m.fault == MotorFault::kOverCurrent) t = DriveTermination::kMotorCurrent;
      std::string msg = std::string("motor group ") + std::to_string(m.command_id) +
                        (m.state == GroupState::kRejected ? " rejected" : " fault ") +
                        (m.state == GroupState::kRejected ? "" : MotorFaultName(m.fault));
      if (m.fault_motor >= 0) msg += " on motor " + std::to_string(m.fault_motor);
      if (!m.message.empty()) msg += ": " + m.message;
      Terminate(now, t, msg, out);
      return;
    }
  }
  // 2. Staleness.
  std::string why;
  if (!SensorsFresh(now, &why)) {
    Terminate(now, DriveTermination::kStaleSensor, "stale sensor: " + why, out);
    return;
  }
  // 3. Tilt.
  const double tilt =
      std::acos(std::clamp(std::cos(attitude_->roll) * std::cos(attitude_->pitch), -1.0, 1.0));
  tilt_count_ = tilt > options_.max_tilt ? tilt_count_ + 1 : 0;
  if (tilt_count_ >= options_.tilt_cycles) {
    Terminate(now, DriveTermination::kTilt,
              "tilt " + FormatNumber(tilt / kDegree) + " deg over " +
                  FormatNumber(options_.max_tilt / kDegree) + " deg for " +
                  std::to_string(tilt_count_) + " cycles",
              out);
    return;
  }
  // 4. Suspension.
  std::string bad;
  for (std::size_t s = 0; s < 2 && bad.empty(); ++s) {
    const char* side = s == 0 ? "left" : "right";
    const double r = joint_->rocker_angle[s];
    const double b = joint_->bogie_angle[s];
    if (r < options_.rocker_min || r > options_.rocker_max) {
      bad = std::string(side) + " rocker " + FormatNumber(r / kDegree) + " deg";
    } else if (b < options_.bogie_min || b > options_.bogie_max) {
      bad = std::string(side) + " bogie " + FormatNumber(b / kDegree) + " deg";
    }
  }
  suspension_count_ = bad.empty() ? 0 : suspension_count_ + 1;
  if (suspension_count_ >= options_.suspension_cycles) {
    Terminate(now, DriveTermination::kSuspension, "suspension out of range: " + bad, out);
    return;
  }
  // Progress.
  switch (phase_) {
    case Phase::kSteering:
      if (SteeringReached()) {
        if (command_.primitive == DrivePrimitive::kSteer) {
          Terminate(now, DriveTermination::kNominal, "steering reached", out);
          return;
        }
        if (plan_.turn_in_place) {
          phase_ = Phase::kTurning;
          status_.state = DriveState::kTurning;
          status_.message = "turning";
        } else {
          phase_ = Phase::kDriving;
          status_.state = DriveState::kDriving;
          status_.message = "driving";
          wheel_start_ = joint_->wheel_angle;
          out->motor_commands.push_back(DrivePositionCommand(now));
        }
      }
      break;
    case Phase::kDriving:
    case Phase::kTurning:
    case Phase::kIdle:
      break;
  }
  if (phase_ == Phase::kDriving) {
    int reached = 0;
    for (std::size_t i = 0; i < kNumWheels; ++i) {
      const double planned = plan_.wheel_rotation[i];
      const double turned = joint_->wheel_angle[i] - wheel_start_[i];
      const double progress = planned >= 0.0 ? turned : -turned;
      if (progress >= std::abs(planned) - options_.wheel_goal_tolerance) ++reached;
    }
    if (2 * reached >= kNumWheels) {
      Terminate(now, DriveTermination::kNominal,
                std::to_string(reached) + " of 6 wheels turned their planned rotation", out);
      return;
    }
  }
  if (phase_ == Phase::kTurning) {
    const double e = plan_.angle - heading_change_;
    if (std::abs(e) <= options_.heading_tolerance) {
      Terminate(now, DriveTermination::kNominal,
                "heading reached (error " + FormatNumber(e / kDegree) + " deg)", out);
      return;
    }
    const double magnitude =
        std::clamp(options_.turn_gain * std::abs(e),
                   std::min(options_.min_turn_rate, plan_.yaw_rate), plan_.yaw_rate);
    const double rate = e > 0.0 ? magnitude : -magnitude;
    const bool sign_flip = rate * commanded_yaw_rate_ <= 0.0;
    if (sign_flip || std::abs(rate - commanded_yaw_rate_) > 0.1 * std::abs(commanded_yaw_rate_)) {
      commanded_yaw_rate_ = rate;
      out->motor_commands.push_back(TurnVelocityCommand(now, rate));
    }
  }
  // 5. Time-out.
  const double elapsed = ToSeconds(now - start_time_);
  if (elapsed > timeout_s_) {
    Terminate(
        now, DriveTermination::kTimeout,
        "time-out after " + FormatNumber(elapsed) + " s (limit " + FormatNumber(timeout_s_) + " s)",
        out);
    return;
  }
  status_.stamp = now;
  status_.distance_done = DistanceDone();
  status_.heading_change = heading_change_;
  out->statuses.push_back(status_);
}

// ---- parameters -------------------------------------------------------------------------------

void DeclareDriveParams(ParamSet& params, const std::string& prefix) {
  const DriveOptions d;
  auto decl = [&](const char* key, double v, const char* doc) -> ParamSet::Spec& {
    return params.Declare(prefix + key, v, doc);
  };
  decl("check_rate_hz", d.check_rate_hz, "[Hz] reactive-check rate").Range(1.0, 100.0);
  decl("default_speed", d.default_speed, "[m/s] speed when a command gives 0").Range(1e-4, 5.0);
  decl("max_speed", d.max_speed, "[m/s] largest accepted command speed").Range(1e-4, 5.0);
  decl("max_distance", d.max_distance, "[m] largest accepted |distance|").Range(0.01, 1000.0);
  decl("max_turn_angle_deg", d.max_turn_angle / kDegree, "[deg] largest accepted |angle|")
      .Range(1.0, 3600.0);
  decl("max_timeout_s", d.max_timeout_s, "[s] largest accepted timeout_s").Range(1.0, 86400.0);
  decl("steer_tolerance_deg", d.steer_tolerance / kDegree, "[deg] steering reached")
      .Range(0.01, 20.0);
  decl("steer_rate_deg", d.steer_rate / kDegree, "[deg/s] steer motor rate").Range(0.1, 360.0);
  decl("wheel_goal_tolerance", d.wheel_goal_tolerance, "[rad] a wheel turned its planned rotation")
      .Range(1e-4, 1.0);
  decl("heading_tolerance_deg", d.heading_tolerance / kDegree, "[deg] turn-in-place goal")
      .Range(0.01, 20.0);
  decl("turn_gain", d.turn_gain, "[1/s] yaw-rate command per rad of heading error")
      .Range(0.01, 100.0);
  decl("min_turn_rate_deg", d.min_turn_rate / kDegree, "[deg/s] smallest commanded yaw rate")
      .Range(0.001, 90.0);
  decl("max_tilt_deg", d.max_tilt / kDegree, "[deg] tilt limit").Range(1.0, 89.0);
  params.Declare(prefix + "tilt_cycles", 3, "consecutive 8 Hz cycles over the tilt limit")
      .Range(1, 1000);
  params
      .Declare(prefix + "rocker_range_deg",
               std::vector<double>{d.rocker_min / kDegree, d.rocker_max / kDegree},
               "[deg] allowed rocker angles [min, max]")
      .Size(2)
      .Range(-90.0, 90.0);
  params
      .Declare(prefix + "bogie_range_deg",
               std::vector<double>{d.bogie_min / kDegree, d.bogie_max / kDegree},
               "[deg] allowed bogie angles [min, max]")
      .Size(2)
      .Range(-90.0, 90.0);
  params.Declare(prefix + "suspension_cycles", 1, "consecutive cycles out of range").Range(1, 1000);
  decl("joint_stale_s", d.joint_stale_s, "[s] joint state staleness limit").Range(0.01, 60.0);
  decl("attitude_stale_s", d.attitude_stale_s, "[s] attitude staleness limit").Range(0.01, 60.0);
  decl("timeout_factor", d.timeout_factor, "derived time-out = factor * duration + margin")
      .Range(1.0, 100.0);
  decl("timeout_margin_s", d.timeout_margin_s, "[s] derived time-out margin").Range(0.0, 3600.0);
  params.Declare(prefix + "require_arm_stowed", d.require_arm_stowed,
                 "refuse drive primitives while an arm joint is off its stowed angle");
  decl("arm_stow_tolerance", d.arm_stow_tolerance,
       "[rad] an arm joint this close to its stowed angle counts as stowed")
      .Range(0.001, 1.0);
}

Result<DriveOptions> DriveOptionsFromParams(const ParamSet& params, const std::string& prefix) {
  ROVER_RETURN_IF_ERROR(params.Validate());
  auto where = [&](const char* key) {
    return params.Origin(prefix + key).ToString() + ": key '" + prefix + key + "': ";
  };
  DriveOptions o;
  o.check_rate_hz = params.GetDouble(prefix + "check_rate_hz");
  o.default_speed = params.GetDouble(prefix + "default_speed");
  o.max_speed = params.GetDouble(prefix + "max_speed");
  o.max_distance = params.GetDouble(prefix + "max_distance");
  o.max_turn_angle = params.GetDouble(prefix + "max_turn_angle_deg") * kDegree;
  o.max_timeout_s = params.GetDouble(prefix + "max_timeout_s");
  o.steer_tolerance = params.GetDouble(prefix + "steer_tolerance_deg") * kDegree;
  o.steer_rate = params.GetDouble(prefix + "steer_rate_deg") * kDegree;
  o.wheel_goal_tolerance = params.GetDouble(prefix + "wheel_goal_tolerance");
  o.heading_tolerance = params.GetDouble(prefix + "heading_tolerance_deg") * kDegree;
  o.turn_gain = params.GetDouble(prefix + "turn_gain");
  o.min_turn_rate = params.GetDouble(prefix + "min_turn_rate_deg") * kDegree;
  o.max_tilt = params.GetDouble(prefix + "max_tilt_deg") * kDegree;
  o.tilt_cycles = static_cast<int>(params.GetInt(prefix + "tilt_cycles"));
  const auto& rr = params.GetDoubleList(prefix + "rocker_range_deg");
  const auto& br = params.GetDoubleList(prefix + "bogie_range_deg");
  o.rocker_min = rr[0] * kDegree;
  o.rocker_max = rr[1] * kDegree;
  o.bogie_min = br[0] * kDegree;
  o.bogie_max = br[1] * kDegree;
  o.suspension_cycles = static_cast<int>(params.GetInt(prefix + "suspension_cycles"));
  o.joint_stale_s = params.GetDouble(prefix + "joint_stale_s");
  o.attitude_stale_s = params.GetDouble(prefix + "attitude_stale_s");
  o.timeout_factor = params.GetDouble(prefix + "timeout_factor");
  o.timeout_margin_s = params.GetDouble(prefix + "timeout_margin_s");
  o.require_arm_stowed = params.GetBool(prefix + "require_arm_stowed");
  o.arm_stow_tolerance = params.GetDouble(prefix + "arm_stow_tolerance");
  if (o.default_speed > o.max_speed) {
    return InvalidArgument(where("default_speed") + FormatNumber(o.default_speed) +
                           " exceeds max_speed " + FormatNumber(o.max_speed));
  }
  if (!(rr[0] < rr[1])) {
    return InvalidArgument(where("rocker_range_deg") + "min " + FormatNumber(rr[0]) +
                           " must be below max " + FormatNumber(rr[1]));
  }
  if (!(br[0] < br[1])) {
    return InvalidArgument(where("bogie_range_deg") + "min " + FormatNumber(br[0]) +
                           " must be below max " + FormatNumber(br[1]));
  }
  ROVER_RETURN_IF_ERROR(o.Validate());
  return o;
}

}  // namespace rover::dl::locomotion
