#include "rover/apl/rendezvous/target_approach.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>

#include "drive_steps.hpp"
#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/units.hpp"
#include "rover/geometry/planar.hpp"

namespace rover::apl::rendezvous {
namespace {

using msg::RendezvousFault;
using msg::RendezvousPhase;

using internal::Cm;
using internal::kMaxDriveS;
using internal::kMaxMobilityRetries;
using internal::Straight;
using internal::Turn;

}  // namespace

TargetApproach::TargetApproach(const RendezvousOptions& options, std::shared_ptr<TargetVision> vision)
    : options_(options), vision_(std::move(vision)) {
  ROVER_DEMAND(options_.Validate().ok());
  ROVER_DEMAND(vision_ != nullptr);
}

void TargetApproach::Reply(ExecutorOutput* out) { out->statuses.push_back(status_); }

void TargetApproach::Fail(RendezvousFault fault, const std::string& message, ExecutorOutput* out) {
  if (wait_ == Wait::kDrive) out->mobility.push_back(internal::StopDriveCommand(ids_.Mobility()));
  if (wait_ == Wait::kStow || wait_ == Wait::kPlace || wait_ == Wait::kFocus) {
    msg::ArmCommand stop;
    stop.mode = msg::ArmMode::kStop;
    stop.command_id = ids_.Arm();
    out->arm.push_back(stop);
  }
  after_stow_.reset();
  focus_at_.reset();
  wait_ = Wait::kNone;
  status_.phase = RendezvousPhase::kFailed;
  status_.fault = fault;
  status_.message = message;
  Reply(out);
}

bool TargetApproach::PoseFresh(Time now) const {
  return pose_ && ToSeconds(now - pose_->stamp) <= options_.pose_stale_s;
}

void TargetApproach::Look(Time now, ExecutorOutput* out) {
  if (!options_.target_look && !designating_) {
    // The mast stays where it is (a test of what the tracker does when the target drifts out).
    wait_ = Wait::kSettle;
    wait_since_ = now;
    return;
  }
  out->mast.push_back(
      internal::LookAtCommand(target_site_, options_.mast_timeout_s, now, ids_.Mast()));
  outstanding_ = out->mast.back().command_id;
  wait_ = Wait::kMast;
  wait_since_ = now;
}

void TargetApproach::RequestPair(Time now, ExecutorOutput* out) {
  out->camera.push_back(internal::NavcamPairRequest(now, ids_.Camera()));
  outstanding_ = out->camera.back().request_id;
  wait_ = Wait::kFrame;
  wait_since_ = now;
}

void TargetApproach::Arm(msg::ArmCommand c, Wait wait, Time now, ExecutorOutput* out) {
  c.stamp = now;
  c.command_id = ids_.Arm();
  c.timeout_s = options_.arm_timeout_s;
  out->arm.push_back(c);
  outstanding_ = c.command_id;
  wait_ = wait;
  wait_since_ = now;
}

void TargetApproach::Focus(const Eigen::Vector3d& target, const std::string& from, Time now,
                           ExecutorOutput* out) {
  msg::ArmCommand focus;
  focus.mode = msg::ArmMode::kAutofocus;
  focus.target = target;
  status_.phase = RendezvousPhase::kFocusing;
  status_.message = "auto-focus on (" + Cm(target.x()) + ", " + Cm(target.y()) + ", " +
                    Cm(target.z()) + ") in the rover frame, " + from;
  Reply(out);
  Arm(focus, Wait::kFocus, now, out);
}

void TargetApproach::Drive(msg::MobilityCommand c, Time now, ExecutorOutput* out) {
  if (arm_ && !arm_->stowed) {
    // The arm is out (dl-arm says so): stow it before the rover moves.
    after_stow_ = c;
    msg::ArmCommand stow;
    stow.mode = msg::ArmMode::kStow;
    status_.message = "stowing the arm before driving";
    Reply(out);
    Arm(stow, Wait::kStow, now, out);
    return;
  }
  out->mobility.push_back(internal::StampedDrive(std::move(c), now, ids_.Mobility()));
  outstanding_ = out->mobility.back().command_id;
  wait_ = Wait::kDrive;
  wait_since_ = now;
}

bool TargetApproach::Stop(std::uint32_t command_id, ExecutorOutput* out) {
  if (!busy()) return false;
  Fail(RendezvousFault::kStopped, "stopped by command " + std::to_string(command_id), out);
  return true;
}

ExecutorOutput TargetApproach::OnCommand(const msg::RendezvousCommand& c, const NavcamPair* pair,
                                         const Eigen::Isometry3d& site_from_rover_at_pair,
                                         Time now) {
  ExecutorOutput out;
  auto reject = [&](RendezvousFault fault, const std::string& message) {
    if (fault == RendezvousFault::kBusy) {
      msg::RendezvousStatus s = status_;
      s.command_id = c.command_id;
      s.phase = RendezvousPhase::kFailed;
      s.fault = fault;
      s.message = message;
      out.statuses.push_back(s);
      out.statuses.push_back(status_);
      return out;
    }
    status_ = {};
    status_.command_id = c.command_id;
    wait_ = Wait::kNone;
    Fail(fault, message, &out);
    return out;
  };
  if (busy()) {
    return reject(RendezvousFault::kBusy, "command " + std::to_string(status_.command_id) +
                                              " is running (phase " +
                                              msg::RendezvousPhaseName(status_.phase) + ")");
  }
  const double standoff = c.standoff == 0.0 ? options_.target_standoff : c.standoff;
  if (!(standoff >= options_.target_min_standoff && standoff <= options_.target_max_standoff)) {
    return reject(RendezvousFault::kBadCommand,
                  "standoff = " + FormatNumber(c.standoff) + " m is outside [" +
                      FormatNumber(options_.target_min_standoff) + ", " +
                      FormatNumber(options_.target_max_standoff) + "] for a science target");
  }
  if (!(std::isfinite(c.time_budget_s) && c.time_budget_s >= 0.0)) {
    return reject(RendezvousFault::kBadCommand,
                  "time_budget_s = " + FormatNumber(c.time_budget_s) + " must be >= 0");
  }
  const bool by_point = c.image_id == 0;
  if (by_point) {
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(c.target_estimate[i])) {
        return reject(RendezvousFault::kBadCommand,
                      std::string("target_estimate.") + "xyz"[i] + " = " +
                          FormatNumber(c.target_estimate[i]) + " is not finite");
      }
    }
  } else if (pair == nullptr) {
    return reject(RendezvousFault::kBadCommand,
                  "image_id = " + std::to_string(c.image_id) +
                      " is not among the NAVCAM pairs apl-rendezvous holds (the last " +
                      std::to_string(options_.target_images_kept) + ")");
  }
  if (!PoseFresh(now)) {
    return reject(RendezvousFault::kStalePose,
                  pose_ ? "dl/pose is " + FormatNumber(ToSeconds(now - pose_->stamp)) +
                              " s old (limit " + FormatNumber(options_.pose_stale_s) + " s)"
                        : "no dl/pose received yet");
  }
  const Eigen::Vector2d rover_xy = pose_->site_from_rover.translation().head<2>();
  if (by_point) {
    const double range = (c.target_estimate.head<2>() - rover_xy).norm();
    if (range > options_.target_max_range) {
      return reject(RendezvousFault::kBadCommand,
                    "target_estimate is " + FormatNumber(range) + " m away, beyond target_max_range " +
                        FormatNumber(options_.target_max_range) + " m");
    }
    // Designation by a site point: look at it, take a pair, designate where it projects.
    command_ = c;
    standoff_ = standoff;
    status_ = {};
    status_.command_id = c.command_id;
    steps_ = mobility_retries_ = 0;
    designating_ = true;
    target_site_ = c.target_estimate;
    status_.target_position = target_site_;
    deadline_ = now + Seconds(c.time_budget_s > 0.0 ? c.time_budget_s : options_.default_time_budget_s);
    status_.phase = RendezvousPhase::kApproachTarget;
    status_.message = "designating the target at the site point " + FormatNumber(range) + " m away";
    Reply(&out);
    Look(now, &out);
    return out;
  }
  Result<TargetFix> fix =
      vision_->Designate(*pair, site_from_rover_at_pair, Eigen::Vector2d(c.pixel_x, c.pixel_y));
  if (DetectionImage img = vision_->LastDrawing(); img.bgr) out.images.push_back(img);
  if (!fix.ok()) {
    return reject(RendezvousFault::kBadCommand,
                  "image_id = " + std::to_string(c.image_id) + ": " + fix.status().message());
  }
  const Eigen::Vector3d site = site_from_rover_at_pair * fix->target_rover;
  const double range = (site.head<2>() - rover_xy).norm();
  if (range > options_.target_max_range) {
    return reject(RendezvousFault::kBadCommand,
                  "the target at pixel (" + FormatNumber(c.pixel_x) + ", " +
                      FormatNumber(c.pixel_y) + ") is " + FormatNumber(range) +
                      " m away, beyond target_max_range " + FormatNumber(options_.target_max_range) + " m");
  }
  designating_ = false;
  command_ = c;
  standoff_ = standoff;
  status_ = {};
  status_.command_id = c.command_id;
  status_.images = 0;
  steps_ = mobility_retries_ = 0;
  deadline_ = now + Seconds(c.time_budget_s > 0.0 ? c.time_budget_s : options_.default_time_budget_s);
  status_.phase = RendezvousPhase::kApproachTarget;
  Accept(*fix, site_from_rover_at_pair);
  status_.message = "target designated " + FormatNumber(range) + " m away (" +
                    std::to_string(fix->features) + " features)";
  Decide(now, &out);
  return out;
}

void TargetApproach::Accept(const TargetFix& fix, const Eigen::Isometry3d& site_from_rover) {
  target_site_ = site_from_rover * fix.target_rover;
  status_.target_position = target_site_;
  status_.target_in_rover = fix.target_rover;
  status_.target_sigma = fix.sigma;
  status_.range = fix.target_rover.head<2>().norm();
  status_.range_sigma = fix.sigma;
  status_.bearing = std::atan2(fix.target_rover.y(), fix.target_rover.x());
  char text[64];
  std::snprintf(text, sizeof text, "features %d/%d, inliers %d, rms %.1f mm%s", fix.matched,
                fix.features, fix.inliers, 1e3 * fix.rms, fix.target_measured ? ", ranged" : "");
  status_.features = text;
}

void TargetApproach::Decide(Time now, ExecutorOutput* out) {
  const Eigen::Vector3d rel = pose_->site_from_rover.inverse() * target_site_;
  const double d = rel.head<2>().norm();
  const double along = d - standoff_;
  const double bearing = std::atan2(rel.y(), rel.x());
  status_.range = d;
  status_.bearing = bearing;
  if (std::abs(along) <= options_.target_along_tolerance &&
      std::abs(bearing) <= options_.target_heading_tolerance_deg * kDegree) {
    status_.phase = RendezvousPhase::kAtTarget;
    status_.target_in_rover = rel;
    status_.message = "at the target: " + Cm(d) + " ahead (standoff " + Cm(standoff_) +
                      "), bearing " + FormatNumber(bearing / kDegree) + " deg, after " +
                      std::to_string(steps_) + " tracking pairs";
    Reply(out);
    if (command_.place_instrument) {
      // The instrument on the target where the last pair measured it, in the rover frame.
      msg::ArmCommand place;
      place.mode = msg::ArmMode::kPlace;
      place.target = rel;
      status_.phase = RendezvousPhase::kPlacing;
      status_.message = "placing the instrument at (" + Cm(rel.x()) + ", " + Cm(rel.y()) + ", " +
                        Cm(rel.z()) + ") in the rover frame";
      Reply(out);
      Arm(place, Wait::kPlace, now, out);
      return;
    }
    if (command_.autofocus) {
      Focus(rel, "the target measured in the last pair", now, out);
      return;
    }
    wait_ = Wait::kHold;
    wait_since_ = now;
    return;
  }
  if (steps_ >= options_.target_max_steps) {
    Fail(RendezvousFault::kPlacement, "not at the standoff after " + std::to_string(steps_) +
                                          " tracking pairs: " + Cm(along) + " along, bearing " +
                                          FormatNumber(bearing / kDegree) + " deg",
         out);
    return;
  }
  Reply(out);
  // No step longer than a fraction of the distance: the target's image grows by at most
  // 1 / (1 - fraction) between pairs, which its patch and features are matched through.
  const double step = std::min(options_.target_leg, options_.target_max_step_fraction * d);
  msg::MobilityCommand c;
  if (along > options_.target_final_approach && options_.target_leg_mode != "directed") {
    // A leg of at most target_leg towards the standoff point.
    const Eigen::Vector2d rover = pose_->site_from_rover.translation().head<2>();
    const Eigen::Vector2d dir = (target_site_.head<2>() - rover).normalized();
    const Eigen::Vector2d goal = rover + std::min(step, along) * dir;
    c.mode = options_.target_leg_mode == "goto_waypoint" ? msg::MobilityMode::kGoToWaypoint
                                                         : msg::MobilityMode::kAutoNav;
    c.goal = Eigen::Vector3d(goal.x(), goal.y(), 0.0);
    c.tolerance = std::max(0.05, 0.1 * options_.target_leg);
    // A short leg gets a short budget: a leg that wanders is looked at again, not driven on.
    c.time_budget_s = 60.0 + 120.0 * (goal - rover).norm();
  } else {
    // Face it, then straight (backwards when too close), at most target_leg.
    c.mode = msg::MobilityMode::kDirected;
    if (std::abs(bearing) > 0.05 * kDegree) c.primitives.push_back(Turn(bearing));
    const double go = std::clamp(along, -options_.target_leg, step);
    if (std::abs(go) > 0.002) c.primitives.push_back(Straight(go));
    if (c.primitives.empty()) c.primitives.push_back(Turn(bearing));
  }
  Drive(c, now, out);
}

ExecutorOutput TargetApproach::OnPose(const msg::PoseSample& pose, Time) {
  pose_ = pose;
  return {};
}

ExecutorOutput TargetApproach::OnMastStatus(const msg::MastStatus& s, Time now) {
  ExecutorOutput out;
  if (wait_ != Wait::kMast || s.command_id != outstanding_) return out;
  if (s.state == msg::MastState::kAtGoal) {
    wait_ = Wait::kSettle;
    wait_since_ = now;
  } else if (s.state == msg::MastState::kFault || s.state == msg::MastState::kRejected) {
    Fail(RendezvousFault::kMast, std::string("dl-mast ") + msg::MastStateName(s.state) + ": " + s.message,
         &out);
  }
  return out;
}

ExecutorOutput TargetApproach::OnArmStatus(const msg::ArmStatus& s, Time now) {
  ExecutorOutput out;
  arm_ = s;
  if ((wait_ != Wait::kStow && wait_ != Wait::kPlace && wait_ != Wait::kFocus) ||
      s.command_id != outstanding_) {
    return out;
  }
  if (s.state == msg::ArmState::kFault || s.state == msg::ArmState::kRejected) {
    const std::string why = std::string("dl-arm ") + msg::ArmStateName(s.state) + ": " + s.message;
    wait_ = Wait::kNone;  // dl-arm has stopped already
    Fail(RendezvousFault::kArm, why, &out);
    return out;
  }
  if (wait_ == Wait::kStow && s.state == msg::ArmState::kStowed) {
    wait_ = Wait::kNone;
    const msg::MobilityCommand leg = *after_stow_;
    after_stow_.reset();
    Drive(leg, now, &out);
  } else if (wait_ == Wait::kPlace && s.state == msg::ArmState::kPlaced) {
    status_.phase = RendezvousPhase::kPlaced;
    status_.message = "instrument on the target (dl-arm " + s.message + ")";
    Reply(&out);
    // With autofocus the instrument stays on the target `settle_s` (the contact read), then the
    // sweep is centred on the face where it touched: the contact measured the surface.
    if (command_.autofocus) focus_at_ = s.tool_point;
    wait_ = Wait::kHold;
    wait_since_ = now;
  } else if (wait_ == Wait::kFocus && s.state == msg::ArmState::kFocused) {
    status_.phase = RendezvousPhase::kFocused;
    status_.message = "in focus " + FormatNumber(s.focus_height * 1000.0, 3) +
                      " mm above the target after " + std::to_string(s.focus_images) +
                      " frames" + (s.focus_predicted ? ", predicted from the contact" : "") +
                      " (ddl/mi_frame " + std::to_string(s.focus_image_id) + ")";
    Reply(&out);
    wait_ = Wait::kHold;
    wait_since_ = now;
  }
  return out;
}

ExecutorOutput TargetApproach::OnStereoPair(const NavcamPair& pair, Time now) {
  ExecutorOutput out;
  if (wait_ != Wait::kFrame || pair.request_id != outstanding_) return out;
  wait_ = Wait::kNone;
  ++status_.images;
  if (!PoseFresh(now)) {
    Fail(RendezvousFault::kStalePose, "dl/pose is stale at the tracking pair", &out);
    return out;
  }
  const Eigen::Isometry3d site_from_rover = pose_->site_from_rover;
  if (designating_) {
    // The pair taken looking at the commanded site point: the target is where it projects.
    designating_ = false;
    const auto px = pair.left_model != nullptr
                        ? pair.left_model->Project(site_from_rover.inverse() * target_site_)
                        : std::nullopt;
    if (!px || px->x() < 0.0 || px->y() < 0.0 || px->x() > pair.left_model->width() - 1.0 ||
        px->y() > pair.left_model->height() - 1.0) {
      Fail(RendezvousFault::kBadCommand, "target_estimate is not in the NAVCAM image taken looking at it",
           &out);
      return out;
    }
    Result<TargetFix> fix = vision_->Designate(pair, site_from_rover, *px);
    if (DetectionImage img = vision_->LastDrawing(); img.bgr) out.images.push_back(img);
    if (!fix.ok()) {
      Fail(RendezvousFault::kBadCommand, "target_estimate: " + fix.status().message(), &out);
      return out;
    }
    Accept(*fix, site_from_rover);
    status_.message = "target designated at the site point (" + std::to_string(fix->features) +
                      " features)";
    Decide(now, &out);
    return out;
  }
  ++steps_;
  Result<TargetFix> fix = vision_->Track(pair, site_from_rover);
  if (DetectionImage img = vision_->LastDrawing(); img.bgr) out.images.push_back(img);
  if (!fix.ok()) {
    Fail(RendezvousFault::kCamera, "NAVCAM pair unusable: " + fix.status().message(), &out);
    return out;
  }
  if (!fix->tracked) {
    Fail(RendezvousFault::kTargetLost,
         std::string("target lost (") + TargetLossName(fix->loss) + "): " + fix->why, &out);
    return out;
  }
  Accept(*fix, site_from_rover);
  const Eigen::Vector3d slip = fix->predicted_motion.translation() - fix->motion.translation();
  status_.message = "pair " + std::to_string(steps_) + ": target " + Cm(status_.range) +
                    " ahead; odometry off by " + Cm(slip.head<2>().norm()) + " since the last pair";
  Decide(now, &out);
  return out;
}

ExecutorOutput TargetApproach::OnMobilityStatus(const msg::MobilityStatus& s, Time now) {
  ExecutorOutput out;
  if (wait_ != Wait::kDrive || s.command_id != outstanding_) return out;
  if (s.state == msg::MobilityState::kSucceeded) {
    wait_ = Wait::kNone;
    mobility_retries_ = 0;
    Look(now, &out);
  } else if (s.state == msg::MobilityState::kFailed || s.state == msg::MobilityState::kRejected) {
    wait_ = Wait::kNone;
    const std::string why =
        "apl-mobility " + std::string(msg::MobilityFaultName(s.fault)) + ": " + s.message;
    if (s.fault_class != msg::FaultClass::kGoalError || mobility_retries_ >= kMaxMobilityRetries) {
      Fail(RendezvousFault::kMobility, why, &out);
      return out;
    }
    // A leg that ended short (NOPATH, NOPROGRESS, budget): look again from where the rover is.
    ++mobility_retries_;
    status_.message = "leg ended (" + why + "); looking again";
    Reply(&out);
    Look(now, &out);
  }
  return out;
}

ExecutorOutput TargetApproach::Step(Time now) {
  ExecutorOutput out;
  if (wait_ == Wait::kNone) return out;
  if (now > deadline_ && wait_ != Wait::kHold) {
    Fail(RendezvousFault::kTimeout,
         "time budget of " +
             FormatNumber(command_.time_budget_s > 0.0 ? command_.time_budget_s
                                                       : options_.default_time_budget_s) +
             " s used up after " + std::to_string(steps_) + " tracking pairs",
         &out);
    return out;
  }
  const double waited = ToSeconds(now - wait_since_);
  switch (wait_) {
    case Wait::kMast:
      if (waited > options_.mast_timeout_s + 5.0) {
        Fail(RendezvousFault::kMast, "no AT_GOAL from dl-mast within " +
                                         FormatNumber(options_.mast_timeout_s + 5.0) + " s",
             &out);
      }
      break;
    case Wait::kSettle:
      if (waited >= options_.settle_s) RequestPair(now, &out);
      break;
    case Wait::kFrame:
      if (waited > options_.camera_timeout_s) {
        Fail(RendezvousFault::kCamera, "no NAVCAM pair within " +
                                           FormatNumber(options_.camera_timeout_s) + " s",
             &out);
      }
      break;
    case Wait::kStow:
    case Wait::kPlace:
    case Wait::kFocus:
      if (waited > options_.arm_timeout_s + 5.0) {
        const char* end = wait_ == Wait::kStow    ? "STOWED"
                          : wait_ == Wait::kPlace ? "PLACED"
                                                  : "FOCUSED";
        Fail(RendezvousFault::kArm, std::string("no ") + end +
                                        " from dl-arm within " +
                                        FormatNumber(options_.arm_timeout_s + 5.0) + " s",
             &out);
      }
      break;
    case Wait::kHold:
      if (focus_at_ && waited >= options_.settle_s) {
        const Eigen::Vector3d at = *focus_at_;
        focus_at_.reset();
        Focus(at, "where the instrument touched it", now, &out);
      } else if (!focus_at_ && waited >= options_.hold_at_base_s) {
        wait_ = Wait::kNone;
        status_.phase = RendezvousPhase::kDone;
        Reply(&out);
      }
      break;
    case Wait::kDrive:
      if (waited > kMaxDriveS + 60.0) {
        Fail(RendezvousFault::kMobility, "no terminal apl/mobility_status for command " +
                                             std::to_string(outstanding_) + " within " +
                                             FormatNumber(kMaxDriveS + 60.0) + " s",
             &out);
      }
      break;
    case Wait::kNone:
      break;
  }
  return out;
}

}  // namespace rover::apl::rendezvous
