#include "rover/dl/mast/mast_executor.hpp"

#include <cmath>
#include <utility>

#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::dl::mast {
namespace {

// After the motor driver reports DONE, the joints have this long to show the goal [s]
// (ddl/joint_state and ddl/motor_status come from different services).
constexpr double kSettleS = 1.0;

std::string DegWithUnit(double rad) { return FormatNumber(rad / kDegree, 4) + " deg"; }

}  // namespace

Result<MastExecutor> MastExecutor::Create(const hwconfig::RoverDescription& rover,
                                          const MastOptions& options) {
  ROVER_RETURN_IF_ERROR(rover.Validate());
  ROVER_RETURN_IF_ERROR(options.Validate());
  return MastExecutor(rover, options);
}

void MastExecutor::OnJoints(const msg::JointState& j) {
  if (!msg::IsUsable(j.health) || !std::isfinite(j.mast_pan) || !std::isfinite(j.mast_tilt)) {
    return;
  }
  if (joints_.has_value() && j.stamp < joints_->stamp) return;
  joints_ = Joints{j.stamp, j.mast_pan, j.mast_tilt};
  status_.pan = j.mast_pan;
  status_.tilt = j.mast_tilt;
}

void MastExecutor::OnPose(const msg::PoseSample& p) {
  if (!p.site_from_rover.matrix().allFinite()) return;
  if (pose_.has_value() && p.stamp < pose_->stamp) return;
  pose_ = p;
}

bool MastExecutor::JointsFresh(Time now) const {
  return joints_.has_value() && ToSeconds(now - joints_->stamp) <= options_.joint_stale_s;
}

bool MastExecutor::WithinTolerance() const {
  return joints_.has_value() && std::abs(joints_->pan - status_.pan_goal) <= options_.tolerance &&
         std::abs(joints_->tilt - status_.tilt_goal) <= options_.tolerance;
}

std::uint32_t MastExecutor::NextMotorId() {
  const std::uint32_t id = next_motor_id_++;
  if (next_motor_id_ == 0) next_motor_id_ = kMotorIdBase;  // wrapped: start the range again
  return id;
}

void MastExecutor::SetStatus(MastState state, std::string message, Time now, MastOutput* out) {
  status_.stamp = now;
  status_.state = state;
  status_.message = std::move(message);
  last_status_ = now;
  out->statuses.push_back(status_);
}

void MastExecutor::Reject(const MastCommand& c, const Status& why, Time now, MastOutput* out) {
  // The status of the rejected command; a running move keeps its goal and carries on, and
  // its next periodic status reports it again.
  MastStatus s = status_;
  s.stamp = now;
  s.command_id = c.command_id;
  s.state = MastState::kRejected;
  s.message = "rejected: " + why.message();
  out->statuses.push_back(s);
  if (!moving()) {
    status_ = s;
    last_status_ = now;
  }
}

msg::MotorCommand MastExecutor::MotorCommand(msg::GroupMode mode, Time now) {
  msg::MotorCommand m;
  m.stamp = now;
  m.command_id = NextMotorId();
  m.motor_mask = kMastMotorMask;
  m.mode = mode;
  m.timeout_s = 0.0;  // the motor driver derives it from the planned move
  return m;
}

void MastExecutor::Fault(std::string message, Time now, MastOutput* out) {
  out->motor_commands.push_back(MotorCommand(msg::GroupMode::kStop, now));
  motor_id_ = 0;
  SetStatus(MastState::kFault, std::move(message), now, out);
}

Result<PanTilt> MastExecutor::GoalOf(const MastCommand& c, Time now) const {
  ROVER_RETURN_IF_ERROR(CheckFinite("timeout_s", c.timeout_s));
  ROVER_RETURN_IF_ERROR(
      CheckRange("timeout_s", c.timeout_s, Bounds::Closed(0.0, options_.max_timeout_s), "s"));
  if (!JointsFresh(now)) {
    return InvalidArgument(
        joints_.has_value()
            ? "ddl/joint_state is stale (latest " +
                  FormatNumber(ToSeconds(now - joints_->stamp), 3) + " s old, joint_stale_s = " +
                  FormatNumber(options_.joint_stale_s) + " s)"
            : "no ddl/joint_state received yet: the mast angles are unknown");
  }
  switch (c.pointing) {
    case MastPointing::kAngles: {
      ROVER_RETURN_IF_ERROR(CheckFinite("pan", c.pan));
      ROVER_RETURN_IF_ERROR(CheckFinite("tilt", c.tilt));
      const PanTilt a{c.pan, c.tilt};
      ROVER_RETURN_IF_ERROR(CheckMastLimits(a, options_, "pan", "tilt"));
      return a;
    }
    case MastPointing::kLookAt: {
      if (!pose_.has_value()) {
        return InvalidArgument("look_at needs dl/pose, none received yet");
      }
      const double age = ToSeconds(now - pose_->stamp);
      if (age > options_.pose_stale_s) {
        return InvalidArgument("look_at needs a fresh dl/pose (latest " + FormatNumber(age, 3) +
                               " s old, pose_stale_s = " + FormatNumber(options_.pose_stale_s) +
                               " s)");
      }
      return LookAtAngles(rover_, pose_->site_from_rover, c.look_at, options_);
    }
  }
  return InvalidArgument("pointing = " + std::to_string(static_cast<std::int32_t>(c.pointing)) +
                         " is not a MastPointing value (0 ANGLES, 1 LOOK_AT)");
}

MastOutput MastExecutor::Submit(const MastCommand& c, Time now) {
  MastOutput out;
  const Result<PanTilt> goal = GoalOf(c, now);
  if (!goal.ok()) {
    Reject(c, goal.status(), now, &out);
    return out;
  }
  const std::uint32_t superseded = moving() ? status_.command_id : 0;
  msg::MotorCommand m = MotorCommand(msg::GroupMode::kPosition, now);
  m.goal[hw::kMastPan] = goal->pan;
  m.goal[hw::kMastTilt] = goal->tilt;
  m.max_rate[hw::kMastPan] = options_.speed;
  m.max_rate[hw::kMastTilt] = options_.speed;
  out.motor_commands.push_back(m);
  motor_id_ = m.command_id;
  motors_done_ = false;
  move_start_ = now;
  move_timeout_s_ = c.timeout_s > 0.0 ? c.timeout_s : options_.timeout_s;
  status_.command_id = c.command_id;
  status_.pan_goal = goal->pan;
  status_.tilt_goal = goal->tilt;
  std::string msg = "moving to pan " + DegWithUnit(goal->pan) + ", tilt " + DegWithUnit(goal->tilt);
  if (superseded != 0) msg += " (supersedes command " + std::to_string(superseded) + ")";
  SetStatus(MastState::kMoving, std::move(msg), now, &out);
  return out;
}

MastOutput MastExecutor::OnMotorStatus(const msg::MotorStatus& r, Time now) {
  MastOutput out;
  if (!moving() || r.command_id != motor_id_) return out;
  if (r.state == msg::GroupState::kFault || r.state == msg::GroupState::kRejected) {
    std::string why = std::string("motor driver ") + msg::GroupStateName(r.state);
    if (r.fault != msg::MotorFault::kNone) why += std::string(" ") + msg::MotorFaultName(r.fault);
    if (r.fault_motor >= 0) why += " on " + std::string(hw::MotorName(r.fault_motor));
    if (!r.message.empty()) why += ": " + r.message;
    motor_id_ = 0;  // the driver has braked the group already
    SetStatus(MastState::kFault, std::move(why), now, &out);
    return out;
  }
  if (r.state == msg::GroupState::kDone) {
    if (!motors_done_) done_at_ = now;
    motors_done_ = true;
    if (WithinTolerance()) SetStatus(MastState::kAtGoal, "at goal", now, &out);
  }
  return out;
}

MastOutput MastExecutor::Step(Time now) {
  MastOutput out;
  if (!moving()) return out;
  if (!JointsFresh(now)) {
    Fault("ddl/joint_state went stale during the move (" +
              (joints_.has_value() ? FormatNumber(ToSeconds(now - joints_->stamp), 3) + " s old"
                                   : std::string("none")) +
              ", joint_stale_s = " + FormatNumber(options_.joint_stale_s) + " s)",
          now, &out);
    return out;
  }
  if (motors_done_ && WithinTolerance()) {
    SetStatus(MastState::kAtGoal, "at goal", now, &out);
    return out;
  }
  const double elapsed = ToSeconds(now - move_start_);
  if (elapsed > move_timeout_s_) {
    Fault("timeout after " + FormatNumber(elapsed, 4) +
              " s (timeout_s = " + FormatNumber(move_timeout_s_) + "): pan " +
              DegWithUnit(joints_->pan) + " of " + DegWithUnit(status_.pan_goal) + ", tilt " +
              DegWithUnit(joints_->tilt) + " of " + DegWithUnit(status_.tilt_goal),
          now, &out);
    return out;
  }
  if (motors_done_ && ToSeconds(now - done_at_) > kSettleS) {
    Fault("motors done but pan " + DegWithUnit(joints_->pan) + ", tilt " +
              DegWithUnit(joints_->tilt) + " are not within tolerance " +
              DegWithUnit(options_.tolerance) + " of the goal",
          now, &out);
    return out;
  }
  if (ToSeconds(now - last_status_) >= 1.0 / options_.status_rate_hz - 1e-9) {
    SetStatus(MastState::kMoving, status_.message, now, &out);
  }
  return out;
}

MastOutput MastExecutor::Stop(const std::string& why, Time now) {
  MastOutput out;
  if (moving()) Fault("stopped: " + why, now, &out);
  return out;
}

}  // namespace rover::dl::mast
