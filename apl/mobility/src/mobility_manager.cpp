#include "rover/apl/mobility/mobility_manager.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"
#include "rover/base/units.hpp"

namespace rover::apl::mobility {
namespace {

constexpr double kMaxCurvature = 1.0;  // [1/m] dl/drive_command's limit (1 m turning radius)
constexpr double kMaxDistance = 50.0;  // [m] dl/drive_command's limit (locomotion max_distance)
constexpr double kSteerAllowance_s = 10.0;  // [s] steering before a primitive, for the watchdog
constexpr double kLegTolerance = 0.5;       // [m] long traverse: intermediate waypoints' radius

// Single-arc planners (GESTALT) reach no point inside the rover's tightest turning circle;
// their votes there may prefer backing arcs that reposition the rover, and it circles the goal
// (short_autonav seed 4 drove 9.7 m for a goal 3 m away, backing and arcing 0.7 m to its side).
// The bearing to turn in place by to face a goal that lies more than `tolerance` inside the
// circle of the tightest forward arc the evaluation offers, when the planner's turn in place
// nearest that bearing is allowed (GESTALT's vote for a turn covers the sweep and the straight
// path it leads to); nullopt otherwise.
std::optional<double> FaceGoalInsideTurningCircle(const nav_core::ArcEvaluation& eval,
                                                  const Pose2& here, const Eigen::Vector2d& goal,
                                                  double tolerance) {
  const Eigen::Vector2d g = here.ToRover(goal);
  const double bearing = std::atan2(g.y(), g.x());
  double k_max = 0.0;
  int nearest_turn = -1;
  double nearest_gap = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < eval.candidates.size(); ++k) {
    const nav_core::Candidate& c = eval.candidates[k];
    if (c.kind == nav_core::MotionKind::kPointTurn) {
      const double gap = std::abs(WrapAngle(c.turn_angle - bearing));
      if (gap < nearest_gap) {
        nearest_gap = gap;
        nearest_turn = static_cast<int>(k);
      }
    } else if (c.kind == nav_core::MotionKind::kArc && c.direction > 0) {
      k_max = std::max(k_max, std::abs(c.curvature));
    }
  }
  if (nearest_turn < 0 || k_max <= 1e-6) return std::nullopt;
  if (eval.hazard[static_cast<std::size_t>(nearest_turn)].goodness == 0) return std::nullopt;
  const double r = 1.0 / k_max;
  const Eigen::Vector2d centre(0.0, g.y() >= 0.0 ? r : -r);
  if ((g - centre).norm() >= r - tolerance) return std::nullopt;
  return bearing;
}

std::string Xy(const Eigen::Vector2d& p) {
  return "(" + FormatNumber(p.x(), 4) + ", " + FormatNumber(p.y(), 4) + ")";
}

std::string DescribePrimitive(const Primitive& p) {
  switch (p.kind) {
    case PrimitiveKind::kArc:
      return "ARC k = " + FormatNumber(p.curvature, 3) +
             " 1/m, s = " + FormatNumber(p.distance, 3) + " m";
    case PrimitiveKind::kStraight:
      return "STRAIGHT s = " + FormatNumber(p.distance, 3) + " m";
    case PrimitiveKind::kTurnInPlace:
      return "TURN " + FormatNumber(p.angle * 180.0 / kPi, 3) + " deg";
    default:
      return "primitive " + std::to_string(static_cast<int>(p.kind));
  }
}

bool IsMotion(PrimitiveKind k) {
  return k == PrimitiveKind::kArc || k == PrimitiveKind::kStraight ||
         k == PrimitiveKind::kTurnInPlace;
}

// Splits p into n equal pieces (n >= 1).
void SplitInto(const Primitive& p, int n, std::vector<Primitive>* out) {
  for (int i = 0; i < n; ++i) {
    Primitive q = p;
    q.distance = p.distance / n;
    q.angle = p.angle / n;
    out->push_back(q);
  }
}

int PiecesFor(double amount, double max_piece) {
  return std::max(1, static_cast<int>(std::ceil(std::abs(amount) / max_piece - 1e-9)));
}

Eigen::Isometry3d PoseFromPlanar(const Pose2& p, double z) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(p.heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(p.x, p.y, z);
  return t;
}

bool PoseFinite(const Eigen::Isometry3d& t) { return t.matrix().allFinite(); }

Fault FaultOfTermination(DriveTermination t) {
  switch (t) {
    case DriveTermination::kTilt:
      return Fault::kTilt;
    case DriveTermination::kSuspension:
      return Fault::kSuspension;
    case DriveTermination::kMotorStall:
    case DriveTermination::kMotorCurrent:
    case DriveTermination::kMotorFault:
      return Fault::kMot;
    case DriveTermination::kTimeout:
      return Fault::kDriveTimeout;
    case DriveTermination::kStopCommand:
      return Fault::kStopped;
    case DriveTermination::kRejectedBusy:
      return Fault::kArb;
    case DriveTermination::kRejectedInvalid:
      return Fault::kBadCommand;
    case DriveTermination::kStaleSensor:
      return Fault::kSapp;
    default:
      return Fault::kMot;  // a failure without a reason: treat as a motion fault (safe side)
  }
}

}  // namespace

const char* MobilityInputTopic(MobilityInput input) {
  switch (input) {
    case MobilityInput::kPose: return "dl/pose";
    case MobilityInput::kRangeImage: return "dl/range_image";
    case MobilityInput::kDriveStatus: return "dl/drive_status";
    case MobilityInput::kVisOdom: return "dl/relative_pose";
    case MobilityInput::kMastStatus: return "dl/mast_status";
  }
  return "?";
}

Result<MobilityManager> MobilityManager::Create(const MobilityOptions& options,
                                                std::unique_ptr<nav_core::TerrainAssessor> assessor,
                                                std::unique_ptr<nav_core::ArcSelector> selector,
                                                std::unique_ptr<nav_core::GlobalPlanner> planner) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  if (!assessor) return InvalidArgument("assessor is null (a TerrainAssessor is required)");
  if (!selector) return InvalidArgument("selector is null (an ArcSelector is required)");
  return MobilityManager(options, std::move(assessor), std::move(selector), std::move(planner));
}

MobilityManager::MobilityManager(const MobilityOptions& options,
                                 std::unique_ptr<nav_core::TerrainAssessor> assessor,
                                 std::unique_ptr<nav_core::ArcSelector> selector,
                                 std::unique_ptr<nav_core::GlobalPlanner> planner)
    : options_(options),
      assessor_(std::move(assessor)),
      selector_(std::move(selector)),
      planner_(std::move(planner)),
      software_enable_(options.software_enable),
      next_id_(options.id_base) {}

// ---- command checks ----------------------------------------------------------------------------

Status MobilityManager::ValidateCommand(const MobilityCommand& c) const {
  const int mode = static_cast<int>(c.mode);
  if (mode < 0 || mode >= kModeCount) {
    return InvalidArgument("mode = " + std::to_string(mode) + " is not a MobilityMode (0.." +
                           std::to_string(kModeCount - 1) + ")");
  }
  const int think = static_cast<int>(c.think);
  if (think < 0 || think > 2) {
    return InvalidArgument("think = " + std::to_string(think) + " is not a ThinkMode (0..2)");
  }
  if (c.mode == Mode::kStop || c.mode == Mode::kClearFault) return Status::Ok();
  if (ModeHasGoal(c.mode)) {
    ROVER_RETURN_IF_ERROR(CheckFinite("goal.x", c.goal.x()));
    ROVER_RETURN_IF_ERROR(CheckFinite("goal.y", c.goal.y()));
  }
  ROVER_RETURN_IF_ERROR(CheckNonNegative("tolerance", c.tolerance, "m"));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("time_budget_s", c.time_budget_s, "s"));
  ROVER_RETURN_IF_ERROR(CheckRange("max_tilt", c.max_tilt, 0.0, 0.5 * kPi, "rad"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("min_northerly_tilt", c.min_northerly_tilt, -0.5 * kPi, 0.5 * kPi, "rad"));
  ROVER_RETURN_IF_ERROR(CheckRange("lmst_end_h", c.lmst_end_h, 0.0, 24.0, "h"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("max_steps", c.max_steps, 0, 65535));
  if (ModeHasPrimitives(c.mode)) {
    if (c.primitives.empty() || c.primitives.size() > 32) {
      return InvalidArgument("primitives: " + std::to_string(c.primitives.size()) +
                             " given (mode " + msg::MobilityModeName(c.mode) + " needs 1..32)");
    }
    for (std::size_t i = 0; i < c.primitives.size(); ++i) {
      const Primitive& p = c.primitives[i];
      const std::string f = "primitives[" + std::to_string(i) + "]";
      if (!IsMotion(p.kind)) {
        return InvalidArgument(f + ".primitive = " + std::to_string(static_cast<int>(p.kind)) +
                               " is not ARC, STRAIGHT or TURN_IN_PLACE");
      }
      ROVER_RETURN_IF_ERROR(
          CheckRange(f + ".curvature", p.curvature, -kMaxCurvature, kMaxCurvature, "1/m"));
      ROVER_RETURN_IF_ERROR(
          CheckRange(f + ".distance", p.distance, -kMaxDistance, kMaxDistance, "m"));
      ROVER_RETURN_IF_ERROR(CheckRange(f + ".angle", p.angle, -2.0 * kPi, 2.0 * kPi, "rad"));
      if (p.kind != PrimitiveKind::kTurnInPlace && p.distance == 0.0) {
        return InvalidArgument(f + ".distance = 0 m (an arc or straight must move)");
      }
      if (p.kind == PrimitiveKind::kTurnInPlace && p.angle == 0.0) {
        return InvalidArgument(f + ".angle = 0 rad (a turn in place must turn)");
      }
    }
  }
  if (c.keep_out.size() > 8) {
    return InvalidArgument("keep_out: " + std::to_string(c.keep_out.size()) + " zones (at most 8)");
  }
  for (std::size_t i = 0; i < c.keep_out.size(); ++i) {
    ROVER_RETURN_IF_ERROR(CheckSimplePolygon("keep_out[" + std::to_string(i) + "]", c.keep_out[i]));
  }
  return Status::Ok();
}

bool MobilityManager::PoseFresh(Time now, std::string* why) const {
  if (!pose_) {
    *why = "no dl/pose received";
    return false;
  }
  const double age = ToSeconds(now - pose_->stamp);
  if (age > options_.pose_stale_s) {
    *why = "dl/pose is " + FormatNumber(age, 3) +
           " s old (pose_stale_s = " + FormatNumber(options_.pose_stale_s) + ")";
    return false;
  }
  return true;
}

// ---- inputs ------------------------------------------------------------------------------------

MobilityOutput MobilityManager::OnCommand(const MobilityCommand& c, Time now) {
  Account(now);
  MobilityOutput out;
  const int mode = static_cast<int>(c.mode);
  const bool known_mode = mode >= 0 && mode < kModeCount;
  if (known_mode && c.mode == Mode::kStop) {
    // Acknowledge the STOP first, then the stopped command's end (the latched status).
    status_ = MobilityStatus{
        now,
        c.command_id,
        c.mode,
        State::kSucceeded,
        FaultClass::kNone,
        Fault::kNone,
        run_ ? "stopping command " + std::to_string(run_->command.command_id) : "nothing running",
        -1.0,
        0.0,
        0,
        0,
        motion_error_latched()};
    out.statuses.push_back(status_);
    if (run_) {
      Finish(now, State::kFailed, Fault::kStopped,
             "stopped by command " + std::to_string(c.command_id), &out);
    } else {
      SendStop(now, &out);
    }
    return out;
  }
  if (run_) {
    Reject(c, now, Fault::kBusy,
           "command " + std::to_string(run_->command.command_id) + " (" +
               msg::MobilityModeName(run_->command.mode) + ") is running; send STOP first",
           &out);
    EmitStatus(now, &out);  // the running command stays the latched status
    return out;
  }
  if (const Status s = ValidateCommand(c); !s.ok()) {
    Reject(c, now, Fault::kBadCommand, s.message(), &out);
    return out;
  }
  if (c.mode == Mode::kClearFault) {
    const Fault was = latched_;
    latched_ = Fault::kNone;
    status_ = MobilityStatus{
        now,
        c.command_id,
        c.mode,
        State::kSucceeded,
        FaultClass::kNone,
        Fault::kNone,
        was == Fault::kNone ? "no motion error latched"
                            : "cleared " + std::string(msg::MobilityFaultName(was)),
        -1.0,
        0.0,
        0,
        0,
        false};
    out.statuses.push_back(status_);
    return out;
  }
  if (latched_ != Fault::kNone) {
    Reject(
        c, now, latched_,
        "motion error " + std::string(msg::MobilityFaultName(latched_)) +
            " is latched; send CLEAR_FAULT first",
        &out);
    return out;
  }
  if (!software_enable_) {
    Reject(c, now, Fault::kAcm, "software enable is off (software_enable = false)", &out);
    return out;
  }
  if (c.mode == Mode::kLongTraverse && !planner_) {
    Reject(c, now, Fault::kBadCommand,
           "mode = LONG_TRAVERSE is not supported yet (no global planner)", &out);
    return out;
  }
  std::string why;
  if (!PoseFresh(now, &why)) {
    Reject(c, now, Fault::kSapp, why, &out);
    return out;
  }
  const Pose2 here = PlanarPose(pose_->site_from_rover);
  if (ModeHasGoal(c.mode)) {
    const double d = (c.goal.head<2>() - here.xy()).norm();
    if (d > options_.max_goal_distance) {
      Reject(c, now, Fault::kBadCommand,
             "goal = " + Xy(c.goal.head<2>()) + " is " + FormatNumber(d, 4) +
                 " m from the rover (max_goal_distance_m = " +
                 FormatNumber(options_.max_goal_distance) + ")",
             &out);
      return out;
    }
  }
  const KeepOutHit hit = FirstKeepOutHit({here.xy()}, c.keep_out, options_.keepout_margin);
  if (hit.hit()) {
    Reject(c, now, Fault::kKeepOut,
           "the rover at " + Xy(here.xy()) + " is already within keepout_margin_m = " +
               FormatNumber(options_.keepout_margin) + " of keep_out[" + std::to_string(hit.zone) +
               "] ('" + c.keep_out[hit.zone].name + "')",
           &out);
    return out;
  }
  Start(c, now, &out);
  return out;
}

MobilityOutput MobilityManager::OnPose(const PoseSample& pose, Time now) {
  Account(now);
  MobilityOutput out;
  if (!PoseFinite(pose.site_from_rover)) {
    if (run_) {
      const Eigen::Vector3d t = pose.site_from_rover.translation();
      Finish(now, State::kFailed, Fault::kSapp,
             "dl/pose is not finite (position = (" + FormatNumber(t.x()) + ", " +
                 FormatNumber(t.y()) + ", " + FormatNumber(t.z()) + "))",
             &out);
    }
    return out;  // never stored
  }
  if (pose_ && pose.stamp < pose_->stamp) return out;
  if (pose_) {
    const Pose2 a = PlanarPose(pose_->site_from_rover), b = PlanarPose(pose.site_from_rover);
    const double jump =
        (pose.site_from_rover.translation() - pose_->site_from_rover.translation()).norm();
    const double turn = std::abs(WrapAngle(b.heading - a.heading));
    if (jump > options_.pose_jump || turn > options_.pose_jump_angle) {
      const std::string msg =
          "dl/pose jumped by " + FormatNumber(jump, 3) + " m and " +
          FormatNumber(turn * 180.0 / kPi, 3) +
          " deg between samples (pose_jump_m = " + FormatNumber(options_.pose_jump) + ")";
      pose_ = pose;
      assessor_->Clear();  // the map's registration cannot be trusted any more
      if (run_) Finish(now, State::kFailed, Fault::kSapp, msg, &out);
      return out;
    }
  }
  pose_ = pose;
  return out;
}

MobilityOutput MobilityManager::OnRangeImage(const nav_core::RangeScan& scan, CameraId camera,
                                             std::uint32_t request_id, Time now) {
  Account(now);
  MobilityOutput out;
  if (!run_ || !run_->image || !run_->image->Answers(request_id)) return out;
  const PendingImage pending = *run_->image;
  run_->image.reset();
  const std::string req = "range image for request " + std::to_string(request_id);
  if (camera != pending.camera) {
    Finish(now, State::kFailed, Fault::kImg,
           req + " came from " + std::string(CameraName(camera)) + " (asked " +
               std::string(CameraName(pending.camera)) + ")",
           &out);
    return out;
  }
  if (const Status s = scan.Validate(); !s.ok()) {
    Finish(now, State::kFailed, Fault::kImg, req + ": " + s.message(), &out);
    return out;
  }
  if (std::none_of(scan.valid.begin(), scan.valid.end(), [](std::uint8_t v) { return v != 0; })) {
    Finish(now, State::kFailed, Fault::kImg,
           req + " (" + std::string(CameraName(camera)) + "): all " +
               std::to_string(scan.pixel_count()) + " pixels invalid",
           &out);
    return out;
  }
  const auto stats = assessor_->Update(scan);
  if (!stats.ok()) {
    Finish(now, State::kFailed, Fault::kImg, req + ": " + stats.status().message(), &out);
    return out;
  }
  out.goodness_map = assessor_->goodness_map();
  if (pending.purpose == Purpose::kThink) {
    run_->think_image_merged = true;
    // The drive already ended and the step waited for this image: go on.
    if (!run_->drive && !run_->vo_since) NextStep(now, &out);
    return out;
  }
  if (!run_->camera_queue.empty()) {
    const CameraId next = run_->camera_queue.front();
    run_->camera_queue.pop_front();
    RequestImage(next, Purpose::kStep, now, &out);
    return out;
  }
  if (run_->guarded_next) {
    const Primitive piece = *run_->guarded_next;
    run_->guarded_next.reset();
    const Pose2 here = PlanarPose(pose_->site_from_rover);
    const double spacing = 0.5 * assessor_->goodness_map().resolution;
    const auto pts = SweptCentre(here, piece, spacing);
    for (const Eigen::Vector2d& p : pts) {
      const nav_core::CellValue v = assessor_->GoodnessAt(p);
      if (v.goodness < options_.guard_min_goodness) {
        Finish(now, State::kFailed, Fault::kNoPath,
               "guarded: " + DescribePrimitive(piece) + " vetoed: goodness " +
                   std::to_string(v.goodness) + " at " + Xy(p) +
                   " (guard_min_goodness = " + std::to_string(options_.guard_min_goodness) + ")",
               &out);
        return out;
      }
    }
    SendDrive(piece, now, &out);
    return out;
  }
  auto eval = Evaluate(PlanarPose(pose_->site_from_rover), now);
  if (!eval.ok()) {
    Finish(now, State::kFailed, Fault::kBadCommand, eval.status().message(), &out);
    return out;
  }
  ChooseAndDrive(now, *eval, &out);
  return out;
}

MobilityOutput MobilityManager::OnDriveStatus(const DriveStatus& r, Time now) {
  Account(now);
  MobilityOutput out;
  if (!run_ || !run_->drive || r.command_id != run_->drive->command_id) return out;
  run_->drive->last_report = now;
  run_->drive->rejected_note.clear();
  switch (r.state) {
    case DriveState::kDone: {
      const double done = std::abs(r.distance_done);
      run_->distance_driven += done;
      counters_.distance += done;
      run_->steps += 1;
      run_->drive.reset();
      StepDone(now, &out);
      return out;
    }
    case DriveState::kFailed:
    case DriveState::kRejected: {
      run_->distance_driven += std::abs(r.distance_done);
      counters_.distance += std::abs(r.distance_done);
      const Fault f = FaultOfTermination(r.termination);
      run_->drive.reset();  // it has ended: no STOP needed
      std::string msg = "drive " + std::to_string(r.command_id) + " ";
      msg += r.state == DriveState::kFailed ? "failed" : "rejected";
      msg += ": " + r.message;
      if (f == Fault::kArb) msg += " (locomotion is busy with another client's drive)";
      Finish(now, State::kFailed, f, msg, &out);
      return out;
    }
    default:
      return out;  // still steering or driving
  }
}

MobilityOutput MobilityManager::OnMastStatus(const MastStatus& report, Time now) {
  Account(now);
  (void)report;  // the HAZCAM-only manager does not point the mast yet (README: missing)
  return {};
}

MobilityOutput MobilityManager::OnVisOdom(const RelativePose& result, Time now) {
  Account(now);
  MobilityOutput out;
  if (result.source != msg::MotionSource::kVisualOdometry) return out;
  if (!run_ || !run_->vo_since || result.t_to < run_->vo_after) return out;
  run_->vo_since.reset();
  if (result.status != msg::RelativePoseStatus::kConverged) {
    run_->vo_failures += 1;
    if (run_->vo_failures > options_.max_visodom_failures) {
      Finish(now, State::kFailed, Fault::kVisOdom,
             std::to_string(run_->vo_failures) +
                 " visual odometry steps failed (max_visodom_failures = " +
                 std::to_string(options_.max_visodom_failures) + ")",
             &out);
      return out;
    }
  }
  if (!run_->image) NextStep(now, &out);
  return out;
}

MobilityOutput MobilityManager::OnInputRejected(MobilityInput input, const std::string& why,
                                                Time now, std::uint32_t request_id) {
  Account(now);
  MobilityOutput out;
  if (!run_) return out;  // idle: nothing moves, the next command checks the pose afresh
  const std::string what = std::string(MobilityInputTopic(input)) + " rejected: " + why;
  switch (input) {
    case MobilityInput::kPose:
      // Position unknown: stop now rather than drive on the last good pose.
      Finish(now, State::kFailed, Fault::kSapp, what, &out);
      return out;
    case MobilityInput::kRangeImage:
      if (!run_->image || !run_->image->Answers(request_id)) return out;  // not ours
      Finish(now, State::kFailed, Fault::kImg,
             "range image for request " + std::to_string(request_id) + " (" +
                 std::string(CameraName(run_->image->camera)) + ") " + what,
             &out);
      return out;
    case MobilityInput::kDriveStatus:
      // Whose report it was cannot be told: it refreshes nothing, so a drive whose reports
      // all fail ends MOT at its status time-out (Step), naming this.
      if (run_->drive) run_->drive->rejected_note = why;
      return out;
    case MobilityInput::kVisOdom: {
      if (!run_->vo_since) return out;
      RelativePose failed;  // counts as a failed VO step
      failed.source = msg::MotionSource::kVisualOdometry;
      failed.t_to = now;
      failed.status = msg::RelativePoseStatus::kTooFewFeatures;
      return OnVisOdom(failed, now);
    }
    case MobilityInput::kMastStatus:
      return out;  // the mast is not used yet
  }
  return out;
}

MobilityOutput MobilityManager::Step(Time now) {
  Account(now);
  MobilityOutput out;
  if (!run_) return out;
  if (run_->image && ToSeconds(now - run_->image->first_sent) > options_.image_timeout_s) {
    const PendingImage& img = *run_->image;
    Finish(now, State::kFailed, Fault::kImg,
           "no range image for request " + std::to_string(img.request_id) + " (" +
               std::string(CameraName(img.camera)) + ") in " +
               FormatNumber(options_.image_timeout_s) + " s (image_timeout_s" +
               (img.earlier_ids.empty()
                    ? ")"
                    : ", sent " + std::to_string(img.earlier_ids.size() + 1) + " times)"),
           &out);
    return out;
  }
  if (run_->image && options_.image_resend_s > 0 &&
      static_cast<int>(run_->image->earlier_ids.size()) < options_.max_image_resends &&
      ToSeconds(now - run_->image->sent) > options_.image_resend_s) {
    // Unanswered: a dl-stereo restarted since the request reads only what is written after it
    // started (command readers are fresh only), so the request is asked again, same camera.
    PendingImage& img = *run_->image;
    img.earlier_ids.push_back(img.request_id);
    img.request_id = next_id_++;
    img.sent = now;
    run_->images += 1;
    counters_.images += 1;
    RangeRequest r;
    r.request_id = img.request_id;
    r.camera = img.camera;
    r.width = options_.image_width;
    r.stamp = now;
    out.range_requests.push_back(r);
    out.notes.push_back("range request " + std::to_string(img.earlier_ids.back()) +
                        " unanswered for " + FormatNumber(options_.image_resend_s) +
                        " s: sent again as " + std::to_string(img.request_id));
  }
  if (run_->drive && now > run_->drive->deadline) {
    Finish(now, State::kFailed, Fault::kDriveTimeout,
           "drive " + std::to_string(run_->drive->command_id) + " (" +
               DescribePrimitive(run_->drive->primitive) + ") did not finish in " +
               FormatNumber(ToSeconds(run_->drive->deadline - run_->drive->sent), 4) + " s",
           &out);
    return out;
  }
  if (run_->drive && options_.drive_status_timeout_s > 0.0 &&
      ToSeconds(now - run_->drive->last_report) > options_.drive_status_timeout_s) {
    const PendingDrive& d = *run_->drive;
    Finish(now, State::kFailed, Fault::kMot,
           "no dl/drive_status for drive " + std::to_string(d.command_id) + " (" +
               DescribePrimitive(d.primitive) + ") in " +
               FormatNumber(ToSeconds(now - d.last_report), 3) + " s (drive_status_timeout_s = " +
               FormatNumber(options_.drive_status_timeout_s) + ")" +
               (d.rejected_note.empty() ? "" : "; last one rejected: " + d.rejected_note),
           &out);
    return out;
  }
  if (run_->vo_since && ToSeconds(now - *run_->vo_since) > options_.visodom_timeout_s) {
    RelativePose missing;
    missing.source = msg::MotionSource::kVisualOdometry;
    missing.t_to = now;
    missing.status = msg::RelativePoseStatus::kTooFewFeatures;  // counts as a failed step
    MobilityOutput more = OnVisOdom(missing, now);
    return more;
  }
  if (run_->drive) {
    // While moving: pose freshness, tilt and the command limits stop the drive at once.
    if (!CheckLimits(now, &out)) return out;
  }
  if (ToSeconds(now - run_->last_status) >= options_.status_period_s) EmitStatus(now, &out);
  return out;
}

// ---- command life ------------------------------------------------------------------------------

void MobilityManager::Reject(const MobilityCommand& c, Time now, Fault fault,
                             const std::string& message, MobilityOutput* out) {
  if (FaultClassOf(fault) == FaultClass::kMotionError) latched_ = fault;
  status_ = MobilityStatus{now,
                           c.command_id,
                           c.mode,
                           State::kRejected,
                           FaultClassOf(fault),
                           fault,
                           message,
                           -1.0,
                           0.0,
                           0,
                           0,
                           motion_error_latched()};
  out->statuses.push_back(status_);
}

std::vector<Primitive> MobilityManager::SplitForVisOdom(const Primitive& p) const {
  std::vector<Primitive> pieces;
  if (p.kind == PrimitiveKind::kTurnInPlace) {
    SplitInto(p, PiecesFor(p.angle, options_.visodom_max_turn), &pieces);
  } else {
    SplitInto(p, PiecesFor(p.distance, options_.visodom_max_step), &pieces);
  }
  return pieces;
}

void MobilityManager::Start(const MobilityCommand& c, Time now, MobilityOutput* out) {
  Run run;
  run.command = c;
  run.start = now;
  run.last_status = now;
  run.tolerance = std::max(c.tolerance, options_.min_tolerance);
  run.max_tilt = c.max_tilt > 0.0 ? c.max_tilt : options_.max_tilt;
  run.max_steps = c.max_steps > 0 ? c.max_steps : options_.max_steps;
  run.think = c.think == ThinkMode::kDefault ? options_.drive_while_thinking
                                             : c.think == ThinkMode::kDriveWhileThinking;
  const double budget = c.time_budget_s > 0.0 ? c.time_budget_s : options_.time_budget_s;
  if (budget > 0.0) run.deadline = now + Seconds(budget);
  if (c.lmst_end_h > 0.0) {
    const double unix_s = options_.run_clock_epoch_unix_s + now.seconds();
    const double lmst = MarsLocalMeanSolarTimeHours(unix_s, options_.site_longitude_east);
    const double hours_left = std::fmod(c.lmst_end_h - lmst + 24.0, 24.0);
    run.tod_deadline = now + Seconds(hours_left * kSecondsPerMarsHour);
  }
  const bool guarded =
      c.mode == Mode::kGuarded || c.mode == Mode::kGuardedVisOdom || c.mode == Mode::kGuardedArc;
  for (std::size_t i = 0; i < c.primitives.size(); ++i) {
    const Primitive& p = c.primitives[i];
    std::vector<Primitive> pieces;
    if (ModeUsesVisOdom(c.mode)) {
      pieces = SplitForVisOdom(p);
    } else if (guarded && p.kind != PrimitiveKind::kTurnInPlace) {
      SplitInto(p, PiecesFor(p.distance, options_.guard_segment_length), &pieces);
    } else {
      pieces.push_back(p);
    }
    if (c.mode == Mode::kGuardedArc && i == 0) run.blind_pieces = static_cast<int>(pieces.size());
    for (const Primitive& q : pieces) run.queue.push_back(q);
  }
  if (ModeHasGoal(c.mode)) run.goals.push_back(c.goal.head<2>());
  run_ = std::move(run);
  if (c.mode == Mode::kLongTraverse) {
    nav_core::PlanRequest req;
    req.start = PlanarPose(pose_->site_from_rover).xy();
    req.goal = c.goal.head<2>();
    req.goal_tolerance = run_->tolerance;
    auto plan = planner_->MakePlan(req);
    if (!plan.ok()) {
      const Fault f =
          plan.status().code() == StatusCode::kNotFound ? Fault::kNoPath : Fault::kBadCommand;
      Finish(now, State::kFailed, f, "global planner: " + plan.status().message(), out);
      return;
    }
    run_->goals = plan->waypoints;
    if (run_->goals.empty() || (run_->goals.back() - req.goal).norm() > run_->tolerance) {
      run_->goals.push_back(req.goal);
    }
  }
  if (ModeHasGoal(c.mode)) RecordProgress();
  EmitStatus(now, out);
  NextStep(now, out);
}

void MobilityManager::Finish(Time now, State state, Fault fault, const std::string& message,
                             MobilityOutput* out) {
  ROVER_DEMAND(run_.has_value());
  if (run_->drive) SendStop(now, out);
  if (FaultClassOf(fault) == FaultClass::kMotionError) latched_ = fault;
  status_ = MobilityStatus{now,
                           run_->command.command_id,
                           run_->command.mode,
                           state,
                           FaultClassOf(fault),
                           fault,
                           message,
                           ModeHasGoal(run_->command.mode) ? DistanceToGoal() : -1.0,
                           run_->distance_driven,
                           run_->steps,
                           run_->images,
                           motion_error_latched()};
  out->statuses.push_back(status_);
  run_.reset();
}

void MobilityManager::EmitStatus(Time now, MobilityOutput* out) {
  if (!run_) return;
  run_->last_status = now;
  status_ = MobilityStatus{now,
                           run_->command.command_id,
                           run_->command.mode,
                           State::kRunning,
                           FaultClass::kNone,
                           Fault::kNone,
                           "",
                           ModeHasGoal(run_->command.mode) ? DistanceToGoal() : -1.0,
                           run_->distance_driven,
                           run_->steps,
                           run_->images,
                           motion_error_latched()};
  out->statuses.push_back(status_);
}

// ---- the step loop -----------------------------------------------------------------------------

Eigen::Vector2d MobilityManager::CurrentGoal() const {
  return run_ && !run_->goals.empty() ? run_->goals.front() : Eigen::Vector2d::Zero();
}

double MobilityManager::DistanceToGoal() const {
  if (!run_ || run_->goals.empty() || !pose_) return -1.0;
  return (run_->goals.back() - PlanarPose(pose_->site_from_rover).xy()).norm();
}

void MobilityManager::RecordProgress() {
  run_->goal_distance_history.push_back(DistanceToGoal());
  run_->position_history.push_back(pose_ ? PlanarPose(pose_->site_from_rover).xy()
                                         : Eigen::Vector2d::Zero());
}

void MobilityManager::ResetProgress() {
  run_->goal_distance_history.clear();
  run_->position_history.clear();
  RecordProgress();
}

bool MobilityManager::NoProgress(std::string* why) const {
  const auto& h = run_->goal_distance_history;
  const std::size_t n = static_cast<std::size_t>(options_.progress_steps);
  if (h.size() <= n || h[h.size() - 1 - n] - h.back() >= options_.min_progress) return false;
  *why = "distance to the goal went from " + FormatNumber(h[h.size() - 1 - n], 4) + " to " +
         FormatNumber(h.back(), 4) + " m";
  // Along the planner's cost-to-go, both ends priced over today's map: a detour that runs down
  // it is progress; an oscillation, or a walk that the map now shows leads nowhere, is not.
  const auto& p = run_->position_history;
  const Eigen::Vector2d goal = CurrentGoal();
  const std::optional<double> from = selector_->CostToGo(goal, p[p.size() - 1 - n]);
  const std::optional<double> to = selector_->CostToGo(goal, p.back());
  if (from && to) {
    if (*from - *to >= options_.min_progress) return false;
    *why += " and the planner's cost-to-go from " + FormatNumber(*from, 4) + " to " +
            FormatNumber(*to, 4) + " m";
  }
  *why += " in " + std::to_string(n) + " steps (min_progress_m = " +
          FormatNumber(options_.min_progress) + ")";
  return true;
}

bool MobilityManager::CheckLimits(Time now, MobilityOutput* out) {
  std::string why;
  if (!PoseFresh(now, &why)) {
    Finish(now, State::kFailed, Fault::kSapp, why, out);
    return false;
  }
  const Eigen::Matrix3d r = pose_->site_from_rover.linear();
  const double tilt = std::acos(std::clamp(r(2, 2), -1.0, 1.0));
  if (tilt > run_->max_tilt) {
    Finish(now, State::kFailed, Fault::kTilt,
           "tilt " + FormatNumber(tilt * 180.0 / kPi, 3) + " deg is over max_tilt " +
               FormatNumber(run_->max_tilt * 180.0 / kPi, 3) + " deg",
           out);
    return false;
  }
  if (run_->deadline && now >= *run_->deadline) {
    Finish(now, State::kFailed, Fault::kWaypointTimeout,
           "time budget of " + FormatNumber(ToSeconds(*run_->deadline - run_->start), 4) +
               " s ran out",
           out);
    return false;
  }
  if (run_->tod_deadline && now >= *run_->tod_deadline) {
    Finish(now, State::kFailed, Fault::kTod,
           "Mars local mean solar time reached lmst_end_h = " +
               FormatNumber(run_->command.lmst_end_h) + " h",
           out);
    return false;
  }
  return true;
}

void MobilityManager::NextStep(Time now, MobilityOutput* out) {
  if (!run_) return;
  if (!CheckLimits(now, out)) return;
  const Mode mode = run_->command.mode;
  if (run_->command.min_northerly_tilt != 0.0) {
    const Eigen::Vector3d up = pose_->site_from_rover.linear().col(2);
    const double north = std::atan2(up.x(), up.z());
    if (north < run_->command.min_northerly_tilt) {
      Finish(now, State::kFailed, Fault::kNorth,
             "northerly tilt " + FormatNumber(north * 180.0 / kPi, 3) +
                 " deg is below min_northerly_tilt " +
                 FormatNumber(run_->command.min_northerly_tilt * 180.0 / kPi, 3) + " deg",
             out);
      return;
    }
  }
  if (ModeHasGoal(mode)) {
    const Eigen::Vector2d here = PlanarPose(pose_->site_from_rover).xy();
    while (run_->goals.size() > 1 &&
           (run_->goals.front() - here).norm() <= std::max(kLegTolerance, run_->tolerance)) {
      run_->goals.erase(run_->goals.begin());
      ResetProgress();
    }
    const double d = (run_->goals.front() - here).norm();
    if (run_->goals.size() == 1 && d <= run_->tolerance) {
      Finish(now, State::kSucceeded, Fault::kNone,
             "reached the goal (" + FormatNumber(d, 3) + " m from it)", out);
      return;
    }
    if (static_cast<int>(run_->steps) >= run_->max_steps) {
      Finish(now, State::kFailed, Fault::kNoProgress,
             std::to_string(run_->steps) + " steps taken (max_steps = " +
                 std::to_string(run_->max_steps) + ") without reaching the goal",
             out);
      return;
    }
    if (std::string window; NoProgress(&window)) {
      if (LimitCycleTurn(now, out)) return;
      Finish(now, State::kFailed, Fault::kNoProgress,
             window + (run_->limit_cycle_turns > 0
                           ? " after " + std::to_string(run_->limit_cycle_turns) +
                                 " limit-cycle turn(s)"
                           : std::string()),
             out);
      return;
    }
  }
  EmitStatus(now, out);
  switch (mode) {
    case Mode::kDirected:
    case Mode::kVisOdom:
      if (run_->queue.empty()) {
        Finish(now, State::kSucceeded, Fault::kNone, "all primitives driven", out);
        return;
      }
      {
        const Primitive p = run_->queue.front();
        run_->queue.pop_front();
        SendDrive(p, now, out);
      }
      return;
    case Mode::kGuarded:
    case Mode::kGuardedVisOdom:
    case Mode::kGuardedArc:
      GuardedStep(now, out);
      return;
    case Mode::kGoToWaypoint:
    case Mode::kVisOdomGoToWaypoint:
      WaypointStep(now, out);
      return;
    default:
      AutonavStep(now, out);
      return;
  }
}

void MobilityManager::GuardedStep(Time now, MobilityOutput* out) {
  if (run_->queue.empty()) {
    Finish(now, State::kSucceeded, Fault::kNone, "all primitives driven (none vetoed)", out);
    return;
  }
  const Primitive p = run_->queue.front();
  run_->queue.pop_front();
  if (run_->blind_pieces > 0) {
    run_->blind_pieces -= 1;
    SendDrive(p, now, out);
    return;
  }
  run_->guarded_next = p;
  const bool backward = p.kind != PrimitiveKind::kTurnInPlace && p.distance < 0.0;
  RequestImage(backward ? CameraId::kRearHazcam : CameraId::kFrontHazcam, Purpose::kStep, now,
               out);
}

void MobilityManager::WaypointStep(Time now, MobilityOutput* out) {
  const Pose2 here = PlanarPose(pose_->site_from_rover);
  const Eigen::Vector2d d = CurrentGoal() - here.xy();
  const double c = std::cos(here.heading), s = std::sin(here.heading);
  const Eigen::Vector2d g(c * d.x() + s * d.y(), -s * d.x() + c * d.y());  // rover frame
  const double dist = g.norm();
  const double bearing = std::atan2(g.y(), g.x());
  const bool vo = ModeUsesVisOdom(run_->command.mode);
  Primitive p;
  if (std::abs(bearing) > options_.waypoint_turn_threshold) {
    p.kind = PrimitiveKind::kTurnInPlace;
    p.angle =
        vo ? std::clamp(bearing, -options_.visodom_max_turn, options_.visodom_max_turn) : bearing;
  } else {
    const double k = std::clamp(2.0 * g.y() / (dist * dist), -kMaxCurvature, kMaxCurvature);
    const double arc = std::abs(k) < 1e-9
                           ? dist
                           : 2.0 * std::asin(std::min(1.0, 0.5 * dist * std::abs(k))) / std::abs(k);
    const double step = vo ? std::min(options_.visodom_max_step, options_.waypoint_step_length)
                           : options_.waypoint_step_length;
    p.kind = std::abs(k) < 1e-9 ? PrimitiveKind::kStraight : PrimitiveKind::kArc;
    p.curvature = std::abs(k) < 1e-9 ? 0.0 : k;
    p.distance = std::min(step, arc);
  }
  SendDrive(p, now, out);
}

double MobilityManager::ArcStepLength(const Pose2& from, double curvature, int direction) const {
  const Eigen::Vector2d goal = CurrentGoal();
  const double d = std::max((goal - from.xy()).norm(), 0.05);
  const double most = options_.step_length + run_->tolerance;
  if (run_->goals.size() != 1 || d > most || !selector_->ChecksDriveLength()) {
    return std::min(options_.step_length, d);
  }
  // The last step ends where the arc passes nearest the goal, not at the edge of its tolerance:
  // the tolerance is what the rover accepts, and the estimate's own error adds to wherever it
  // stops. (An arc that bends away passes nearest early; driving it the goal's whole straight
  // distance would carry the rover past.) An arc that does not enter the tolerance within
  // `most` is driven a normal step.
  constexpr double kSearchStep = 0.01;  // [m]
  double best_s = 0.05, best = std::numeric_limits<double>::infinity();
  for (double s = 0.05; s <= most + 1e-9; s += kSearchStep) {
    const double e = (geometry::AlongArc(from, curvature, direction * s).xy() - goal).norm();
    if (e < best) {
      best = e;
      best_s = s;
    }
  }
  return best <= run_->tolerance ? best_s : std::min(options_.step_length, d);
}

Result<nav_core::ArcEvaluation> MobilityManager::Evaluate(const Pose2& from, Time now) const {
  (void)now;
  nav_core::ArcRequest req;
  req.site_from_rover = PoseFromPlanar(from, pose_->site_from_rover.translation().z());
  req.goal = CurrentGoal();
  req.goal_tolerance =
      run_->goals.size() > 1 ? std::max(kLegTolerance, run_->tolerance) : run_->tolerance;
  req.last_direction = run_->last_direction;
  // The most Command() drives of an arc before deciding again (ArcStepLength; VO splits it,
  // never lengthens it).
  const double most = run_->goals.size() == 1 && selector_->ChecksDriveLength()
                          ? options_.step_length + run_->tolerance
                          : options_.step_length;
  req.drive_length = ModeUsesVisOdom(run_->command.mode)
                         ? std::min(most, options_.visodom_max_step)
                         : most;
  return selector_->Plan(*assessor_, req);
}

CameraId MobilityManager::CameraFor(const nav_core::ArcEvaluation& eval) const {
  if (eval.has_choice() && eval.choice().kind == nav_core::MotionKind::kArc &&
      eval.choice().direction < 0) {
    return CameraId::kRearHazcam;
  }
  return CameraId::kFrontHazcam;
}

void MobilityManager::AutonavStep(Time now, MobilityOutput* out) {
  if (run_->path_next) {
    // The chosen path turned in place first; its first arc was checked with it: drive it now.
    const Primitive p = *run_->path_next;
    run_->path_next.reset();
    if (!SendDrive(p, now, out)) return;
    run_->last_direction = p.distance < 0.0 ? -1 : 1;
    if (run_->think) StartThinking(p, now, out);
    return;
  }
  assessor_->Follow(pose_->site_from_rover);
  auto eval = Evaluate(PlanarPose(pose_->site_from_rover), now);
  if (!eval.ok()) {
    Finish(now, State::kFailed, Fault::kBadCommand, eval.status().message(), out);
    return;
  }
  if (run_->think_image_merged || eval->all_paths_safe) {
    if (!run_->think_image_merged) counters_.images_skipped += 1;
    run_->think_image_merged = false;
    ChooseAndDrive(now, *eval, out);
    return;
  }
  const CameraId cam = CameraFor(*eval);
  run_->camera_queue.clear();
  if (eval->image_rear && cam == CameraId::kFrontHazcam) {
    run_->camera_queue.push_back(CameraId::kRearHazcam);
  }
  RequestImage(cam, Purpose::kStep, now, out);
}

bool MobilityManager::LimitCycleTurn(Time now, MobilityOutput* out) {
  const Mode mode = run_->command.mode;
  const bool votes_arcs =
      mode == Mode::kAutoNav || mode == Mode::kAutoNavVisOdom || mode == Mode::kLongTraverse;
  if (!votes_arcs || run_->limit_cycle_turns >= options_.limit_cycle_turns) return false;
  const Pose2 here = PlanarPose(pose_->site_from_rover);
  auto eval = Evaluate(here, now);
  if (!eval.ok()) return false;
  // Planners that check their own turns have already tried every turn; an unchecked turn here
  // would only risk the rover.
  if (selector_->ChecksTurns()) return false;
  // The side of the best forward arcs: the mean curvature of those with the top merged vote.
  int top = -1;
  double k_sum = 0.0;
  int k_count = 0;
  for (std::size_t k = 0; k < eval->candidates.size(); ++k) {
    const nav_core::Candidate& c = eval->candidates[k];
    // Every turn in place sweeps the rover's own cells: one forbidden means all are.
    if (c.kind == nav_core::MotionKind::kPointTurn && eval->hazard[k].goodness == 0) return false;
    if (c.kind != nav_core::MotionKind::kArc || c.direction < 0) continue;
    const int g = eval->merged[k].goodness;
    if (g > top) {
      top = g;
      k_sum = 0.0;
      k_count = 0;
    }
    if (g == top) {
      k_sum += c.curvature;
      k_count += 1;
    }
  }
  const Eigen::Vector2d d = CurrentGoal() - here.xy();
  const double bearing = WrapAngle(std::atan2(d.y(), d.x()) - here.heading);
  Primitive p;
  p.kind = PrimitiveKind::kTurnInPlace;
  if (std::abs(bearing) >= options_.limit_cycle_min_bearing) {
    p.angle = bearing;
  } else {
    const double side = k_count > 0 && k_sum < 0.0 ? -1.0 : 1.0;  // right only if the best lie right
    p.angle = side * options_.limit_cycle_turn;
  }
  if (ModeUsesVisOdom(mode)) {
    p.angle = std::clamp(p.angle, -options_.visodom_max_turn, options_.visodom_max_turn);
  }
  run_->limit_cycle_turns += 1;
  run_->path_next.reset();
  run_->last_direction = 0;
  ResetProgress();
  EmitStatus(now, out);
  SendDrive(p, now, out);  // a keep-out hit ends the command there
  return true;
}

void MobilityManager::ChooseAndDrive(Time now, const nav_core::ArcEvaluation& eval,
                                     MobilityOutput* out) {
  ArcVotesSnapshot snap;
  snap.stamp = now;
  snap.command_id = run_->command.command_id;
  snap.step = run_->steps;
  snap.site_from_rover = pose_->site_from_rover;
  snap.evaluation = eval;
  out->arc_votes.push_back(std::move(snap));
  if (eval.mode == nav_core::GoalMode::kReached) {
    if (run_->goals.size() > 1) {
      run_->goals.erase(run_->goals.begin());
      NextStep(now, out);
      return;
    }
    Finish(now, State::kSucceeded, Fault::kNone,
           "reached the goal (" + FormatNumber(eval.distance_to_goal, 3) + " m from it)", out);
    return;
  }
  if (!eval.has_choice()) {
    // Planners that say why (the ENav-class tree): the first two distinct reasons.
    std::string reasons;
    int distinct = 0;
    for (std::size_t k = 0; k < eval.why.size() && distinct < 2; ++k) {
      if (eval.why[k].empty() || reasons.find(eval.why[k]) != std::string::npos) continue;
      reasons += (distinct == 0 ? " (first refusals: " : "; ") + eval.why[k];
      ++distinct;
    }
    if (distinct > 0) reasons += ")";
    Finish(now, State::kFailed, Fault::kNoPath,
           "no safe path: all " + std::to_string(eval.candidates.size()) +
               " candidates forbidden, " + FormatNumber(eval.distance_to_goal, 4) +
               " m from the goal" + reasons,
           out);
    return;
  }
  const nav_core::Candidate& c = eval.choice();
  const bool vo = ModeUsesVisOdom(run_->command.mode);
  Primitive p;
  std::optional<double> face;
  if (!selector_->ChecksTurns() && c.kind == nav_core::MotionKind::kArc) {
    face = FaceGoalInsideTurningCircle(eval, PlanarPose(pose_->site_from_rover), CurrentGoal(),
                                       run_->tolerance);
  }
  if (face) {
    p.kind = PrimitiveKind::kTurnInPlace;
    p.angle = vo ? std::clamp(*face, -options_.visodom_max_turn, options_.visodom_max_turn) : *face;
    counters_.goal_facing_turns += 1;
  } else if (c.kind == nav_core::MotionKind::kPointTurn) {
    p.kind = PrimitiveKind::kTurnInPlace;
    p.angle = vo ? std::clamp(c.turn_angle, -options_.visodom_max_turn, options_.visodom_max_turn)
                 : c.turn_angle;
    // A multi-segment plan (turn, then arcs): its first arc follows the turn without a new
    // decision, unless VO splits the turn.
    if (!vo && eval.path.size() >= 2 && eval.path[0].kind == nav_core::MotionKind::kPointTurn &&
        eval.path[1].kind == nav_core::MotionKind::kArc) {
      const nav_core::Candidate& a = eval.path[1];
      Primitive next;
      const Pose2 turned = geometry::Turned(PlanarPose(pose_->site_from_rover), c.turn_angle);
      double len = std::min(ArcStepLength(turned, a.curvature, a.direction), a.length);
      if (eval.max_drive > 0.0) len = std::min(len, eval.max_drive);
      next.kind = std::abs(a.curvature) < 1e-9 ? PrimitiveKind::kStraight : PrimitiveKind::kArc;
      next.curvature = std::abs(a.curvature) < 1e-9 ? 0.0 : a.curvature;
      next.distance = a.direction < 0 ? -len : len;
      run_->path_next = next;
    }
  } else {
    double len = ArcStepLength(PlanarPose(pose_->site_from_rover), c.curvature, c.direction);
    if (eval.max_drive > 0.0) len = std::min(len, eval.max_drive);
    if (vo) len = std::min(len, options_.visodom_max_step);
    p.kind = std::abs(c.curvature) < 1e-9 ? PrimitiveKind::kStraight : PrimitiveKind::kArc;
    p.curvature = std::abs(c.curvature) < 1e-9 ? 0.0 : c.curvature;
    p.distance = c.direction < 0 ? -len : len;
    run_->last_direction = c.direction;
  }
  if (!SendDrive(p, now, out)) return;
  if (run_->think && p.kind != PrimitiveKind::kTurnInPlace) StartThinking(p, now, out);
}

void MobilityManager::StartThinking(const Primitive& p, Time now, MobilityOutput* out) {
  const Pose2 predicted = Propagate(PlanarPose(pose_->site_from_rover), p);
  auto eval = Evaluate(predicted, now);
  if (eval.ok() && eval->all_paths_safe) return;  // the next step will not need an image
  RequestImage(eval.ok() ? CameraFor(*eval) : CameraId::kFrontHazcam, Purpose::kThink, now, out);
  counters_.images_while_driving += 1;
}

bool MobilityManager::PendingImage::Answers(std::uint32_t id) const {
  return id == request_id ||
         std::find(earlier_ids.begin(), earlier_ids.end(), id) != earlier_ids.end();
}

void MobilityManager::RequestImage(CameraId camera, Purpose purpose, Time now,
                                   MobilityOutput* out) {
  PendingImage img;
  img.request_id = next_id_++;
  img.camera = camera;
  img.first_sent = now;
  img.sent = now;
  img.purpose = purpose;
  run_->image = img;
  run_->images += 1;
  counters_.images += 1;
  RangeRequest r;
  r.request_id = img.request_id;
  r.camera = camera;
  r.width = options_.image_width;
  r.stamp = now;
  out->range_requests.push_back(r);
}

bool MobilityManager::SendDrive(const Primitive& p, Time now, MobilityOutput* out) {
  const Pose2 here = PlanarPose(pose_->site_from_rover);
  if (!run_->command.keep_out.empty()) {
    const auto pts = SweptCentre(here, p, 0.05);
    const KeepOutHit hit = FirstKeepOutHit(pts, run_->command.keep_out, options_.keepout_margin);
    if (hit.hit()) {
      Finish(now, State::kFailed, Fault::kKeepOut,
             "the next step (" + DescribePrimitive(p) + ") would come within " +
                 FormatNumber(options_.keepout_margin) + " m of keep_out[" +
                 std::to_string(hit.zone) + "] ('" + run_->command.keep_out[hit.zone].name +
                 "') at " + Xy(pts[hit.point]) + "; halted before it",
             out);
      return false;
    }
  }
  DriveCommand d;
  d.command_id = next_id_++;
  d.primitive = p.kind;
  d.curvature = p.kind == PrimitiveKind::kArc ? p.curvature : 0.0;
  d.distance = p.kind == PrimitiveKind::kTurnInPlace ? 0.0 : p.distance;
  d.angle = p.kind == PrimitiveKind::kTurnInPlace ? p.angle : 0.0;
  d.speed = options_.drive_speed;
  d.stamp = now;
  const double planned =
      PathLength(p) / options_.nominal_speed +
      (p.kind == PrimitiveKind::kTurnInPlace ? std::abs(p.angle) / options_.nominal_turn_rate
                                             : 0.0) +
      kSteerAllowance_s;
  PendingDrive pd;
  pd.command_id = d.command_id;
  pd.primitive = p;
  pd.sent = now;
  pd.last_report = now;
  pd.deadline =
      now + Seconds(options_.drive_timeout_factor * planned + options_.drive_timeout_margin_s);
  run_->drive = pd;
  run_->vo_after = now;
  counters_.drives += 1;
  out->drives.push_back(d);
  return true;
}

void MobilityManager::StepDone(Time now, MobilityOutput* out) {
  if (ModeHasGoal(run_->command.mode)) RecordProgress();
  if (ModeUsesVisOdom(run_->command.mode)) {
    run_->vo_since = now;
    EmitStatus(now, out);
    return;
  }
  if (run_->image) {  // the image taken while driving has not arrived yet
    EmitStatus(now, out);
    return;
  }
  NextStep(now, out);
}

void MobilityManager::SendStop(Time now, MobilityOutput* out) {
  DriveCommand d;
  d.command_id = next_id_++;
  d.primitive = PrimitiveKind::kStop;
  d.stamp = now;
  out->drives.push_back(d);
}

void MobilityManager::Account(Time now) {
  if (run_ && last_account_ && now > *last_account_) {
    const double dt = ToSeconds(now - *last_account_);
    (run_->drive ? counters_.moving_s : counters_.still_s) += dt;
  }
  if (!last_account_ || now > *last_account_) last_account_ = now;
}

msg::ArcVotes ArcVotesOf(const ArcVotesSnapshot& s) {
  const auto vote = [](int v) { return static_cast<std::uint8_t>(std::clamp(v, 0, 255)); };
  msg::ArcVotes a;
  a.stamp = s.stamp;
  a.command_id = s.command_id;
  a.step = s.step;
  a.rover_pose = s.site_from_rover;
  const nav_core::ArcEvaluation& e = s.evaluation;
  for (std::size_t i = 0; i < e.candidates.size(); ++i) {
    const nav_core::Candidate& c = e.candidates[i];
    msg::ArcVote v;
    v.kind = c.kind == nav_core::MotionKind::kArc ? msg::CandidateKind::kArc
                                                  : msg::CandidateKind::kPointTurn;
    v.curvature = c.curvature;
    v.direction = c.direction < 0 ? -1 : 1;
    v.turn_angle = c.turn_angle;
    v.hazard = i < e.hazard.size() ? vote(e.hazard[i].goodness) : 0;
    v.waypoint = i < e.waypoint.size() ? vote(e.waypoint[i].goodness) : 0;
    v.merged = i < e.merged.size() ? vote(e.merged[i].goodness) : 0;
    a.votes.push_back(v);
  }
  a.chosen = e.chosen;
  return a;
}

}  // namespace rover::apl::mobility
