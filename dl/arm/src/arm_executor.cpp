#include "rover/dl/arm/arm_executor.hpp"

#include <algorithm>
#include <opencv2/core.hpp>
#include <cmath>
#include <span>
#include <utility>

#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::dl::arm {
namespace {

// After the motor driver reports a leg DONE, the joints have this long to show its goal [s]
// (ddl/joint_state and ddl/motor_status come from different services).
constexpr double kArmSettleS = 1.0;
// The instrument counts as face down when its look direction has z below this.
constexpr double kFaceDownLookZ = -0.9;

std::string ArmPointText(const Eigen::Vector3d& p) {
  return "(" + FormatNumber(p.x(), 4) + ", " + FormatNumber(p.y(), 4) + ", " +
         FormatNumber(p.z(), 4) + ")";
}

std::string ArmAnglesText(const ArmAngles& q) { return FormatList(std::span(q), 4); }

// `why` with `context` appended, same code.
Status WithContext(const Status& why, const std::string& context) {
  return Status(why.code(), why.message() + " (" + context + ")");
}

}  // namespace

Result<ArmExecutor> ArmExecutor::Create(const hwconfig::RoverDescription& rover,
                                        const ArmOptions& options) {
  ROVER_RETURN_IF_ERROR(rover.Validate());
  ROVER_RETURN_IF_ERROR(options.Validate());
  return ArmExecutor(rover, options);
}

bool ArmExecutor::JointsFresh(Time now) const {
  return joints_.has_value() && ToSeconds(now - joints_->stamp) <= options_.joint_stale_s;
}

bool ArmExecutor::WithinTolerance(const ArmAngles& goal) const {
  if (!joints_.has_value()) return false;
  for (std::size_t k = 0; k < goal.size(); ++k) {
    if (!(std::abs(joints_->q[k] - goal[k]) <= options_.tolerance)) return false;
  }
  return true;
}

std::uint32_t ArmExecutor::NextMotorId() {
  const std::uint32_t id = next_motor_id_++;
  if (next_motor_id_ == 0) next_motor_id_ = kMotorIdBase;  // wrapped: start the range again
  return id;
}

void ArmExecutor::Fill(ArmStatus* s) const {
  if (!joints_.has_value()) return;
  s->joints = joints_->q;
  s->tool_point = rover_.arm.Forward(joints_->q).face;
  s->contact = joints_->contact;
  bool stowed = true;
  for (std::size_t k = 0; k < joints_->q.size(); ++k) {
    stowed = stowed && std::abs(joints_->q[k] - rover_.arm.stow[k]) <= options_.tolerance;
  }
  s->stowed = stowed;
}

void ArmExecutor::SetStatus(ArmState state, std::string message, Time now, ArmOutput* out) {
  status_.stamp = now;
  status_.state = state;
  status_.message = std::move(message);
  Fill(&status_);
  last_status_ = now;
  out->statuses.push_back(status_);
}

void ArmExecutor::Reject(const ArmCommand& c, const Status& why, Time now, ArmOutput* out) {
  // The status of the rejected command; a running command keeps its goal and carries on, and
  // its next periodic status reports it again.
  ArmStatus s = status_;
  Fill(&s);
  s.stamp = now;
  s.command_id = c.command_id;
  s.state = ArmState::kRejected;
  s.message = "rejected: " + why.message();
  out->statuses.push_back(s);
  if (!moving()) {
    status_ = s;
    last_status_ = now;
  }
}

msg::MotorCommand ArmExecutor::MotorCommand(msg::GroupMode mode, Time now) {
  msg::MotorCommand m;
  m.stamp = now;
  m.command_id = NextMotorId();
  m.motor_mask = kArmMotorMask;
  m.mode = mode;
  m.timeout_s = 0.0;  // the motor driver derives it from the planned move
  return m;
}

void ArmExecutor::Fault(std::string message, Time now, ArmOutput* out) {
  out->motor_commands.push_back(MotorCommand(msg::GroupMode::kStop, now));
  motor_id_ = 0;
  SetStatus(ArmState::kFault, std::move(message), now, out);
}

double ArmExecutor::DescentRate(const ArmAngles& from, const ArmAngles& to) const {
  const double distance = (rover_.arm.Forward(to).face - rover_.arm.Forward(from).face).norm();
  double travel = 0.0;
  for (std::size_t k = 0; k < from.size(); ++k)
    travel = std::max(travel, std::abs(to[k] - from[k]));
  if (distance < 1e-6 || travel <= 0.0) return options_.speed;
  // The synchronised move takes travel / rate = distance / descent_speed.
  return std::min(options_.speed, travel * options_.descent_speed / distance);
}

Result<ArmExecutor::Plan> ArmExecutor::PlacePlan(const Eigen::Vector3d& target) const {
  const Eigen::Vector3d up(0.0, 0.0, options_.hover_height);
  const Eigen::Vector3d down(0.0, 0.0, options_.overdrive);
  const Result<ArmAngles> hover = rover_.arm.FaceDown(target + up);
  if (!hover.ok()) {
    return Status(hover.status().code(), "hover point " + FormatNumber(options_.hover_height) +
                                             " m above the target: " + hover.status().message());
  }
  const Result<ArmAngles> end = rover_.arm.FaceDown(target - down);
  if (!end.ok()) {
    return Status(end.status().code(), "descent end " + FormatNumber(options_.overdrive) +
                                           " m below the target: " + end.status().message());
  }
  Status st = rover_.CheckArmMove(joints_->q, *hover);
  if (!st.ok()) return WithContext(st, "move above the target");
  st = rover_.CheckArmMove(*hover, *end);
  if (!st.ok()) {
    return WithContext(st,
                       "descent to " + FormatNumber(options_.overdrive) + " m below the target");
  }
  Plan plan;
  plan.legs = {{Stage::kHover, *hover}, {Stage::kDescent, *end}};
  plan.target = target;
  return plan;
}

Result<ArmExecutor::Plan> ArmExecutor::StowPlan() const {
  const ArmAngles& q = joints_->q;
  const hwconfig::ArmPoints p = rover_.arm.Forward(q);
  Plan plan;
  ArmAngles from = q;
  if (p.look.z() < kFaceDownLookZ && p.face.z() < rover_.arm.shoulder.z()) {
    // Face down and low: lift the instrument straight off whatever it touches first.
    const Result<ArmAngles> lift =
        rover_.arm.FaceDown(p.face + Eigen::Vector3d(0.0, 0.0, options_.hover_height));
    if (lift.ok()) {
      const Status st = rover_.CheckArmMove(q, *lift);
      if (!st.ok()) return WithContext(st, "lift before stowing");
      plan.legs.push_back({Stage::kLift, *lift});
      from = *lift;
    }
  }
  const Status st = rover_.CheckArmMove(from, rover_.arm.stow);
  if (!st.ok()) return WithContext(st, "move to stow");
  plan.legs.push_back({Stage::kStow, rover_.arm.stow});
  return plan;
}

Result<ArmExecutor::Plan> ArmExecutor::AutofocusPlan(const ArmCommand& c) const {
  const int n = c.focus_steps > 0 ? c.focus_steps : options_.focus_steps;
  const double span = c.focus_span > 0.0 ? c.focus_span : options_.focus_span;
  const double s = rover_.arm.imager.working_distance;
  Plan plan;
  plan.target = c.target;
  ArmAngles from = joints_->q;
  for (int k = 0; k < n; ++k) {
    const double h = s + 0.5 * span - k * span / (n - 1);
    const Result<ArmAngles> q = rover_.arm.FaceDown(c.target + Eigen::Vector3d(0.0, 0.0, h));
    if (!q.ok()) {
      return Status(q.status().code(), "focus frame " + std::to_string(k + 1) + " of " +
                                           std::to_string(n) + ", face " + FormatNumber(h, 4) +
                                           " m above the target: " + q.status().message());
    }
    const Status st = rover_.CheckArmMove(from, *q);
    if (!st.ok()) {
      return WithContext(st, k == 0 ? std::string("move to the top of the focus sweep")
                                    : "focus step " + std::to_string(k + 1));
    }
    plan.legs.push_back({k == 0 ? Stage::kFocusMove : Stage::kFocusStep, *q, Frame::kSweep});
    from = *q;
  }
  return plan;
}

Result<ArmExecutor::Plan> ArmExecutor::PlanOf(const ArmCommand& c, Time now) const {
  if (!msg::IsKnownArmMode(c.mode)) {
    return InvalidArgument("mode = " + std::to_string(static_cast<std::int32_t>(c.mode)) +
                           " is not an ArmMode value (0 JOINTS, 1 PLACE, 2 STOW, 3 STOP, "
                           "4 AUTOFOCUS)");
  }
  ROVER_RETURN_IF_ERROR(CheckFinite("timeout_s", c.timeout_s));
  ROVER_RETURN_IF_ERROR(
      CheckRange("timeout_s", c.timeout_s, Bounds::Closed(0.0, options_.max_timeout_s), "s"));
  if (c.mode == ArmMode::kJoints) {
    ROVER_RETURN_IF_ERROR(CheckAllFinite("joints", std::span(c.joints)));
  } else if (c.mode == ArmMode::kPlace || c.mode == ArmMode::kAutofocus) {
    ROVER_RETURN_IF_ERROR(CheckAllFinite("target", std::span(c.target.data(), 3)));
  }
  if (c.mode == ArmMode::kAutofocus) {
    if (c.focus_steps != 0) ROVER_RETURN_IF_ERROR(CheckIntRange("focus_steps", c.focus_steps, 3, 30));
    ROVER_RETURN_IF_ERROR(CheckFinite("focus_span", c.focus_span));
    ROVER_RETURN_IF_ERROR(CheckRange("focus_span", c.focus_span, 0.0, 0.3, "m"));
  }
  if (!JointsFresh(now)) {
    return InvalidArgument(
        joints_.has_value()
            ? "ddl/joint_state is stale (latest " +
                  FormatNumber(ToSeconds(now - joints_->stamp), 3) +
                  " s old, joint_stale_s = " + FormatNumber(options_.joint_stale_s) + " s)"
            : "no ddl/joint_state received yet: the arm angles are unknown");
  }
  if (c.mode != ArmMode::kStow) {
    if (const std::string driving = Driving(); !driving.empty()) {
      return FailedPrecondition("the rover is driving (" + driving +
                                "): the arm moves out only while the wheels stand still (STOW "
                                "and STOP are accepted)");
    }
  }
  switch (c.mode) {
    case ArmMode::kJoints: {
      ROVER_RETURN_IF_ERROR(rover_.arm.CheckLimits(c.joints));
      const Status st = rover_.CheckArmMove(joints_->q, c.joints);
      if (!st.ok()) return WithContext(st, "move to joints " + ArmAnglesText(c.joints));
      Plan plan;
      plan.legs = {{Stage::kJoints, c.joints}};
      return plan;
    }
    case ArmMode::kPlace:
      return PlacePlan(c.target);
    case ArmMode::kStow:
      return StowPlan();
    case ArmMode::kAutofocus:
      return AutofocusPlan(c);
    case ArmMode::kStop:
      break;  // Submit handles it
  }
  return InvalidArgument("mode " + std::string(msg::ArmModeName(c.mode)) + " has no plan");
}

void ArmExecutor::StartLeg(std::size_t index, Time now, std::string message, ArmOutput* out) {
  leg_ = index;
  const Leg& l = leg();
  double rate = options_.speed;
  if (l.stage == Stage::kDescent) {
    if (joints_->contact) {
      Fault("contact switch closed " + FormatNumber(options_.hover_height) +
                " m above the target, before the descent: face at " +
                ArmPointText(rover_.arm.Forward(joints_->q).face) + " m",
            now, out);
      return;
    }
    rate = DescentRate(joints_->q, l.goal);
  } else if (l.stage == Stage::kFocusStep) {
    if (joints_->contact) {
      FocusOnContact(now, out);
      return;
    }
    rate = DescentRate(joints_->q, l.goal);
  }
  msg::MotorCommand m = MotorCommand(msg::GroupMode::kPosition, now);
  for (int j = 0; j < hwconfig::kArmJoints; ++j) {
    const auto k = static_cast<std::size_t>(j);
    const auto motor = static_cast<std::size_t>(hw::kArmAzimuth + j);
    m.goal[motor] = l.goal[k];
    m.max_rate[motor] = rate;
  }
  out->motor_commands.push_back(m);
  motor_id_ = m.command_id;
  motors_done_ = false;
  status_.joint_goals = l.goal;
  SetStatus(ArmState::kMoving, std::move(message), now, out);
}

void ArmExecutor::CheckArrival(Time now, ArmOutput* out) {
  if (!moving() || awaiting_frame_ != 0 || !motors_done_ || !WithinTolerance(leg().goal)) return;
  if (leg().frame != Frame::kNone) {
    RequestFrame(now, out);
    return;
  }
  if (leg_ + 1 < plan_.legs.size()) {
    const Stage next = plan_.legs[leg_ + 1].stage;
    StartLeg(leg_ + 1, now,
             next == Stage::kDescent
                 ? "descending at " + FormatNumber(options_.descent_speed) + " m/s to " +
                       FormatNumber(options_.overdrive) + " m below the target " +
                       ArmPointText(plan_.target) + " m"
                 : std::string("stowing"),
             out);
    return;
  }
  switch (leg().stage) {
    case Stage::kJoints:
      SetStatus(ArmState::kAtGoal, "at goal", now, out);
      break;
    case Stage::kStow:
      SetStatus(ArmState::kStowed, "stowed", now, out);
      break;
    default:  // the descent ended without the contact switch closing
      Fault("no contact within " + FormatNumber(options_.overdrive) +
                " m below the target: face at " +
                ArmPointText(rover_.arm.Forward(joints_->q).face) + " m",
            now, out);
      break;
  }
}

void ArmExecutor::OnContact(Time now, ArmOutput* out) {
  const Eigen::Vector3d face = rover_.arm.Forward(joints_->q).face;
  const double dz = face.z() - plan_.target.z();
  const std::string where = "face at " + ArmPointText(face) + " m, " +
                            FormatNumber(std::abs(dz) * 1000.0, 3) + " mm " +
                            (dz >= 0.0 ? "above" : "below") + " the target";
  if (leg().stage == Stage::kDescent) {
    out->motor_commands.push_back(MotorCommand(msg::GroupMode::kStop, now));
    motor_id_ = 0;
    SetStatus(ArmState::kPlaced, "placed: " + where, now, out);
  } else if (leg().stage == Stage::kFocusStep && awaiting_frame_ == 0) {
    FocusOnContact(now, out);
  } else if (leg().stage == Stage::kHover && contact_seen_open_) {
    Fault("unexpected contact on the way above the target: " + where, now, out);
  }
}

ArmOutput ArmExecutor::OnJoints(const msg::JointState& j) {
  ArmOutput out;
  if (!msg::IsUsable(j.health)) return out;
  for (const double a : j.arm_angle) {
    if (!std::isfinite(a)) return out;
  }
  if (joints_.has_value() && j.stamp < joints_->stamp) return out;
  Joints now{j.stamp, j.arm_angle, j.arm_contact};
  for (int w = 0; w < static_cast<int>(j.wheel_rate.size()); ++w) {
    const double r = std::abs(j.wheel_rate[w]);
    if (std::isfinite(r) && r > now.wheel_rate) {
      now.wheel_rate = r;
      now.fastest_wheel = w;
    }
  }
  joints_ = now;
  Fill(&status_);
  if (!j.arm_contact) contact_seen_open_ = true;
  if (MovingOut()) {
    if (const std::string driving = Driving(); !driving.empty()) {
      Fault("the rover started driving during the move (" + driving + "): arm stopped", j.stamp,
            &out);
      return out;
    }
  }
  if (moving() && j.arm_contact) OnContact(j.stamp, &out);
  return out;
}

std::string ArmExecutor::Driving() const {
  if (!joints_ || joints_->wheel_rate <= options_.max_wheel_rate) return "";
  return std::string("wheel ") + hwconfig::WheelName(joints_->fastest_wheel) + " turning at " +
         FormatNumber(joints_->wheel_rate, 3) + " rad/s, max_wheel_rate " +
         FormatNumber(options_.max_wheel_rate) + " rad/s";
}

bool ArmExecutor::MovingOut() const {
  if (!moving() || plan_.legs.empty()) return false;
  return plan_.legs.back().stage != Stage::kStow;
}

ArmOutput ArmExecutor::Submit(const ArmCommand& c, Time now) {
  ArmOutput out;
  const std::uint32_t superseded = moving() ? status_.command_id : 0;
  if (c.mode == ArmMode::kStop) {
    status_.command_id = c.command_id;
    Fault("stopped by command " + std::to_string(c.command_id), now, &out);
    plan_ = Plan{};
    return out;
  }
  Result<Plan> plan = PlanOf(c, now);
  if (!plan.ok()) {
    Reject(c, plan.status(), now, &out);
    return out;
  }
  plan_ = std::move(*plan);
  contact_seen_open_ = !joints_->contact;
  awaiting_frame_ = 0;
  focus_samples_.clear();
  focus_extra_steps_ = 0;
  focus_predicted_ = false;
  status_.focus_height = 0.0;
  status_.focus_predicted = false;
  status_.focus_images = 0;
  status_.focus_image_id = 0;
  status_.focus_measure = 0.0;
  if (c.mode == ArmMode::kAutofocus) {
    const int n = static_cast<int>(plan_.legs.size());
    const double span = c.focus_span > 0.0 ? c.focus_span : options_.focus_span;
    focus_step_ = span / (n - 1);
  }
  move_start_ = now;
  move_timeout_s_ = c.timeout_s > 0.0 ? c.timeout_s : options_.timeout_s;
  status_.command_id = c.command_id;
  std::string message;
  switch (plan_.legs.front().stage) {
    case Stage::kHover:
      message = "moving " + FormatNumber(options_.hover_height) + " m above the target " +
                ArmPointText(plan_.target) + " m";
      break;
    case Stage::kLift:
      message =
          "lifting the instrument " + FormatNumber(options_.hover_height) + " m before stowing";
      break;
    case Stage::kStow:
      message = "stowing";
      break;
    case Stage::kFocusMove:
      message = "auto-focus on " + ArmPointText(plan_.target) + " m: " +
                std::to_string(plan_.legs.size()) + " frames from " +
                FormatNumber((rover_.arm.Forward(plan_.legs.front().goal).face.z() -
                              plan_.target.z()) * 1000.0, 3) +
                " mm above it";
      break;
    default:
      message = "moving to joints " + ArmAnglesText(plan_.legs.front().goal) + " rad";
      break;
  }
  if (superseded != 0) message += " (supersedes command " + std::to_string(superseded) + ")";
  StartLeg(0, now, std::move(message), &out);
  return out;
}

ArmOutput ArmExecutor::OnMotorStatus(const msg::MotorStatus& r, Time now) {
  ArmOutput out;
  if (!moving() || r.command_id != motor_id_) return out;
  if (r.state == msg::GroupState::kFault || r.state == msg::GroupState::kRejected) {
    std::string why = std::string("motor driver ") + msg::GroupStateName(r.state);
    if (r.fault != msg::MotorFault::kNone) why += std::string(" ") + msg::MotorFaultName(r.fault);
    if (r.fault_motor >= 0) why += " on " + std::string(hw::MotorName(r.fault_motor));
    if (!r.message.empty()) why += ": " + r.message;
    motor_id_ = 0;  // the driver has braked the group already
    SetStatus(ArmState::kFault, std::move(why), now, &out);
    return out;
  }
  if (r.state == msg::GroupState::kDone) {
    if (!motors_done_) done_at_ = now;
    motors_done_ = true;
    CheckArrival(now, &out);
  }
  return out;
}

ArmOutput ArmExecutor::Step(Time now) {
  ArmOutput out;
  if (!moving()) return out;
  if (!JointsFresh(now)) {
    Fault("ddl/joint_state went stale during the move (" +
              (joints_.has_value() ? FormatNumber(ToSeconds(now - joints_->stamp), 3) + " s old"
                                   : std::string("none")) +
              ", joint_stale_s = " + FormatNumber(options_.joint_stale_s) + " s)",
          now, &out);
    return out;
  }
  if (awaiting_frame_ != 0 &&
      ToSeconds(now - frame_requested_) > options_.focus_image_timeout_s) {
    Fault("microscopic-imager frame " + std::to_string(awaiting_frame_) + " not received within " +
              FormatNumber(options_.focus_image_timeout_s) + " s (focus_image_timeout_s)",
          now, &out);
    awaiting_frame_ = 0;
    return out;
  }
  CheckArrival(now, &out);
  if (!out.statuses.empty()) return out;
  const double elapsed = ToSeconds(now - move_start_);
  if (elapsed > move_timeout_s_) {
    static constexpr const char* kLegName[] = {"move to the joint goal", "move above the target",
                                               "descent", "lift", "move to stow",
                                               "auto-focus move", "auto-focus step"};
    Fault("timeout after " + FormatNumber(elapsed, 4) +
              " s (timeout_s = " + FormatNumber(move_timeout_s_) + ") in the " +
              kLegName[static_cast<int>(leg().stage)] + ": face at " +
              ArmPointText(rover_.arm.Forward(joints_->q).face) + " m",
          now, &out);
    return out;
  }
  if (awaiting_frame_ == 0 && motors_done_ && ToSeconds(now - done_at_) > kArmSettleS) {
    std::size_t worst = 0;
    for (std::size_t k = 1; k < leg().goal.size(); ++k) {
      if (std::abs(joints_->q[k] - leg().goal[k]) >
          std::abs(joints_->q[worst] - leg().goal[worst])) {
        worst = k;
      }
    }
    Fault("motors done but the " + std::string(hwconfig::ArmJointName(static_cast<int>(worst))) +
              " is " + FormatNumber(std::abs(joints_->q[worst] - leg().goal[worst]), 3) +
              " rad from its goal (tolerance " + FormatNumber(options_.tolerance) + " rad)",
          now, &out);
    return out;
  }
  if (ToSeconds(now - last_status_) >= 1.0 / options_.status_rate_hz - 1e-9) {
    SetStatus(ArmState::kMoving, status_.message, now, &out);
  }
  return out;
}

double ArmExecutor::FaceHeight() const {
  return rover_.arm.Forward(joints_->q).face.z() - plan_.target.z();
}

void ArmExecutor::RequestFrame(Time now, ArmOutput* out) {
  msg::MiRequest r;
  r.stamp = now;
  r.request_id = next_mi_id_++;
  if (next_mi_id_ == 0) next_mi_id_ = kMiRequestIdBase;
  out->mi_requests.push_back(r);
  awaiting_frame_ = r.request_id;
  frame_requested_ = now;
  frame_height_ = FaceHeight();
  const int k = static_cast<int>(focus_samples_.size()) + 1;
  SetStatus(ArmState::kMoving,
            (leg().frame == Frame::kFinal ? std::string("final focus frame")
                                          : "focus frame " + std::to_string(k)) +
                " at " + FormatNumber(frame_height_ * 1000.0, 3) + " mm above the target",
            now, out);
}

ArmOutput ArmExecutor::OnMiFrame(const msg::MiFrame& frame, Time now) {
  ArmOutput out;
  if (!moving() || awaiting_frame_ == 0 || frame.request_id != awaiting_frame_) return out;
  awaiting_frame_ = 0;
  if (!msg::IsUsable(frame.health)) {
    Fault("microscopic-imager frame " + std::to_string(frame.request_id) + " is " +
              msg::SensorHealthName(frame.health),
          now, &out);
    return out;
  }
  const cv::Mat image(frame.height, frame.width, CV_8UC1,
                      const_cast<std::uint8_t*>(frame.image.data()));
  const Result<double> measure = WaveletFocusMeasure(image);
  if (!measure.ok()) {
    Fault("microscopic-imager frame " + std::to_string(frame.request_id) + ": " +
              measure.status().message(),
          now, &out);
    return out;
  }
  focus_samples_.push_back({frame_height_, *measure});
  status_.focus_images = static_cast<int>(focus_samples_.size());
  if (leg().frame == Frame::kFinal) {
    status_.focus_height = frame_height_;
    status_.focus_predicted = focus_predicted_;
    status_.focus_image_id = frame.request_id;
    status_.focus_measure = *measure;
    SetStatus(ArmState::kFocused,
              std::string(focus_predicted_ ? "focused (predicted from the contact)" : "focused") +
                  ": face " + FormatNumber(frame_height_ * 1000.0, 3) +
                  " mm above the target, measure " + FormatNumber(*measure, 4) + " after " +
                  std::to_string(focus_samples_.size()) + " frames",
              now, &out);
    return out;
  }
  if (leg_ + 1 < plan_.legs.size()) {
    StartLeg(leg_ + 1, now,
             "focus step " + std::to_string(leg_ + 2) + " of " +
                 std::to_string(plan_.legs.size()) + " (frame " +
                 std::to_string(focus_samples_.size()) + " measured " +
                 FormatNumber(*measure, 4) + ")",
             &out);
    return out;
  }
  DecideFocus(now, &out);
  return out;
}

void ArmExecutor::DecideFocus(Time now, ArmOutput* out) {
  std::vector<FocusSample> by_height = focus_samples_;
  std::sort(by_height.begin(), by_height.end(),
            [](const FocusSample& a, const FocusSample& b) { return a.height < b.height; });
  const Result<FocusPeak> peak = FindFocusPeak(by_height);
  if (!peak.ok()) {
    Fault("auto-focus: " + peak.status().message(), now, out);
    return;
  }
  // An end of the sweep holding the sharpest frame is followed while the measure shows a trend
  // (at least the square root of focus_min_contrast): a flat, featureless view is not.
  const bool extend = !peak->bracketed &&
                      focus_extra_steps_ < options_.focus_max_extra_steps &&
                      peak->contrast >= std::sqrt(options_.focus_min_contrast);
  if (!extend && peak->contrast < options_.focus_min_contrast) {
    Fault("no focus signal: the sharpest of " + std::to_string(by_height.size()) +
              " frames measures only " + FormatNumber(peak->contrast, 3) +
              " times the blurriest (focus_min_contrast " +
              FormatNumber(options_.focus_min_contrast) + ")",
          now, out);
    return;
  }
  if (peak->bracketed) {
    FocusLegTo(peak->best_height, Frame::kFinal, now,
               "moving to best focus, " + FormatNumber(peak->best_height * 1000.0, 3) +
                   " mm above the target",
               out);
    return;
  }
  const bool lowest = peak->peak_index == 0;
  const double edge = lowest ? by_height.front().height : by_height.back().height;
  if (focus_extra_steps_ >= options_.focus_max_extra_steps) {
    Fault("no focus peak: the sharpest of " + std::to_string(by_height.size()) +
              " frames is the " + (lowest ? "lowest" : "highest") + ", face " +
              FormatNumber(edge * 1000.0, 3) + " mm above the target, after " +
              std::to_string(focus_extra_steps_) + " extra steps (focus_max_extra_steps)",
          now, out);
    return;
  }
  ++focus_extra_steps_;
  const double next = lowest ? edge - focus_step_ : edge + focus_step_;
  FocusLegTo(next, Frame::kSweep, now,
             std::string("sharpest frame at the ") + (lowest ? "bottom" : "top") +
                 " of the sweep: one more step to " + FormatNumber(next * 1000.0, 3) +
                 " mm above the target",
             out);
}

void ArmExecutor::FocusLegTo(double height, Frame frame, Time now, std::string message,
                             ArmOutput* out) {
  const Result<ArmAngles> q =
      rover_.arm.FaceDown(plan_.target + Eigen::Vector3d(0.0, 0.0, height));
  if (!q.ok()) {
    Fault("auto-focus: face " + FormatNumber(height * 1000.0, 3) +
              " mm above the target: " + q.status().message(),
          now, out);
    return;
  }
  const Status st = rover_.CheckArmMove(joints_->q, *q);
  if (!st.ok()) {
    Fault("auto-focus: " + st.message(), now, out);
    return;
  }
  const Stage stage = height < FaceHeight() ? Stage::kFocusStep : Stage::kFocusMove;
  plan_.legs.push_back({stage, *q, frame});
  StartLeg(plan_.legs.size() - 1, now, std::move(message), out);
}

void ArmExecutor::FocusOnContact(Time now, ArmOutput* out) {
  // The surface is where the face touched it: best focus one working distance above.
  out->motor_commands.push_back(MotorCommand(msg::GroupMode::kStop, now));
  motor_id_ = 0;
  // The switch closes contact_standoff above the surface.
  const double contact = FaceHeight();
  const double best =
      contact - rover_.arm.contact_standoff + rover_.arm.imager.working_distance;
  focus_predicted_ = true;
  FocusLegTo(best, Frame::kFinal, now,
             "contact " + FormatNumber(contact * 1000.0, 3) +
                 " mm above the target (higher than estimated): best focus predicted " +
                 FormatNumber(best * 1000.0, 3) + " mm above it",
             out);
}

ArmOutput ArmExecutor::Stop(const std::string& why, Time now) {
  ArmOutput out;
  if (moving()) Fault("stopped: " + why, now, &out);
  return out;
}

}  // namespace rover::dl::arm
