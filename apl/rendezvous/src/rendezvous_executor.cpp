#include "rover/apl/rendezvous/rendezvous_executor.hpp"

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

constexpr double kMidRangeLimit = 30.0;  // [m] farther: LONG_RANGE
constexpr double kLookHeight = 0.6;      // [m] aim this far above the ground at the deck centre
using internal::Cm;
using internal::Deg;
using internal::kMaxDriveS;
using internal::kMaxMobilityRetries;
using internal::Straight;
using internal::Turn;
constexpr double kApproachShiftDeg = 20.0;  // [deg] approach point moved per refused leg
constexpr double kFarRangeFloor = 0.08;    // relative range sigma of an estimate from far fixes
constexpr double kResetRangeSigma = 0.3;   // ... after far fixes on its bearing kept disagreeing
constexpr int kMaxRangeConflicts = 2;      // such fixes in a row before the reset
constexpr double kTrustedSigma = 1.0;       // [m] an estimate this good may lead a leg
constexpr int kMaxBlindLegs = 2;            // legs in a row led by the estimate alone

Eigen::Vector2d Unit(double angle) { return {std::cos(angle), std::sin(angle)}; }

}  // namespace

RendezvousExecutor::RendezvousExecutor(const RendezvousOptions& options,
                                       const hwconfig::LanderDescription& lander,
                                       std::shared_ptr<RendezvousVision> vision)
    : options_(options), lander_(lander), vision_(std::move(vision)) {
  ROVER_DEMAND(options_.Validate().ok());
  ROVER_DEMAND(lander_.Validate().ok());
  ROVER_DEMAND(vision_ != nullptr);
}

// ---- plumbing -------------------------------------------------------------------------------

void RendezvousExecutor::Reply(ExecutorOutput* out) {
  status_.stamp = pose_ ? pose_->stamp : status_.stamp;
  out->statuses.push_back(status_);
}

void RendezvousExecutor::SetPhase(RendezvousPhase phase, ExecutorOutput* out) {
  if (status_.phase == phase) return;
  status_.phase = phase;
  Reply(out);
}

void RendezvousExecutor::Fail(RendezvousFault fault, const std::string& message,
                              ExecutorOutput* out) {
  if (wait_ == Wait::kDrive) {  // stop the drive we started
    out->mobility.push_back(internal::StopDriveCommand(ids_.Mobility()));
  }
  wait_ = Wait::kNone;
  status_.phase = RendezvousPhase::kFailed;
  status_.fault = fault;
  status_.message = message;
  Reply(out);
}

bool RendezvousExecutor::PoseFresh(Time now) const {
  return pose_ && ToSeconds(now - pose_->stamp) <= options_.pose_stale_s;
}

Eigen::Vector2d RendezvousExecutor::RoverXy() const {
  return pose_->site_from_rover.translation().head<2>();
}

double RendezvousExecutor::RoverHeading() const {
  return geometry::ToPose2(pose_->site_from_rover).heading;
}

double RendezvousExecutor::OrbitRadius() const {
  return lander_.Apothem() + lander_.ramp_length + options_.circle_margin;
}

void RendezvousExecutor::LookAt(const Eigen::Vector3d& site_point, Time now,
                                ExecutorOutput* out) {
  out->mast.push_back(
      internal::LookAtCommand(site_point, options_.mast_timeout_s, now, ids_.Mast()));
  outstanding_ = out->mast.back().command_id;
  wait_ = Wait::kMast;
  wait_since_ = now;
}

void RendezvousExecutor::RequestPair(Time now, ExecutorOutput* out) {
  out->camera.push_back(internal::NavcamPairRequest(now, ids_.Camera()));
  outstanding_ = out->camera.back().request_id;
  wait_ = Wait::kFrame;
  wait_since_ = now;
}

void RendezvousExecutor::Drive(msg::MobilityCommand c, DriveKind kind, Time now,
                               ExecutorOutput* out) {
  out->mobility.push_back(internal::StampedDrive(std::move(c), now, ids_.Mobility()));
  outstanding_ = out->mobility.back().command_id;
  drive_kind_ = kind;
  wait_ = Wait::kDrive;
  wait_since_ = now;
}

void RendezvousExecutor::DriveTo(const Eigen::Vector2d& goal, double tolerance, DriveKind kind,
                                 Time now, ExecutorOutput* out) {
  msg::MobilityCommand c;
  c.mode = options_.leg_mode == "goto_waypoint" ? msg::MobilityMode::kGoToWaypoint
                                                : msg::MobilityMode::kAutoNav;
  c.goal = Eigen::Vector3d(goal.x(), goal.y(), 0.0);
  c.tolerance = tolerance;
  Drive(c, kind, now, out);
}

Eigen::Vector2d RendezvousExecutor::LookTarget() const {
  // The deck centre, or a point as far away turned by the look-around offset while searching.
  if (search_bearing_offset_ == 0.0) return center_;
  const Eigen::Vector2d rover = RoverXy(), d = center_ - rover;
  return rover + d.norm() * Unit(std::atan2(d.y(), d.x()) + search_bearing_offset_);
}

void RendezvousExecutor::LookAtLander(Time now, ExecutorOutput* out) {
  const Eigen::Vector2d target = LookTarget();
  LookAt(Eigen::Vector3d(target.x(), target.y(), center_z_ + kLookHeight), now, out);
}

// ---- inputs ---------------------------------------------------------------------------------

ExecutorOutput RendezvousExecutor::OnCommand(const msg::RendezvousCommand& c, Time now) {
  ExecutorOutput out;
  auto reject = [&](RendezvousFault fault, const std::string& message) {
    msg::RendezvousStatus s = status_;
    if (fault == RendezvousFault::kBusy) {
      // The running command goes on; the rejection is reported for the new id only.
      s.command_id = c.command_id;
      s.phase = RendezvousPhase::kFailed;
      s.fault = fault;
      s.message = message;
      out.statuses.push_back(s);
      out.statuses.push_back(status_);  // the running command's status stays the latest
      return out;
    }
    status_ = {};
    status_.command_id = c.command_id;
    Fail(fault, message, &out);
    return out;
  };
  if (c.target == msg::RendezvousTarget::kStop) {
    if (busy()) {
      Fail(RendezvousFault::kStopped, "stopped by command " + std::to_string(c.command_id), &out);
    } else {
      out.statuses.push_back(status_);  // nothing runs: the latest status answers
    }
    return out;
  }
  if (busy()) {
    return reject(RendezvousFault::kBusy, "command " + std::to_string(status_.command_id) +
                                              " is running (phase " +
                                              msg::RendezvousPhaseName(status_.phase) + ")");
  }
  if (c.target != msg::RendezvousTarget::kLander) {
    return reject(RendezvousFault::kBadCommand,
                  std::string("target ") + msg::RendezvousTargetName(c.target) +
                      " (" + std::to_string(static_cast<int>(c.target)) +
                      ") is not served: only LANDER");
  }
  for (int i = 0; i < 3; ++i) {
    if (!std::isfinite(c.target_estimate[i])) {
      return reject(RendezvousFault::kBadCommand,
                    std::string("target_estimate.") + "xyz"[i] + " = " +
                        FormatNumber(c.target_estimate[i]) + " is not finite");
    }
  }
  const double standoff = c.standoff == 0.0 ? options_.default_standoff : c.standoff;
  if (!(standoff >= options_.min_standoff && standoff <= options_.max_standoff)) {
    return reject(RendezvousFault::kBadCommand,
                  "standoff = " + FormatNumber(c.standoff) + " m is outside [" +
                      FormatNumber(options_.min_standoff) + ", " +
                      FormatNumber(options_.max_standoff) + "]");
  }
  if (c.ramp < -1 || c.ramp > 1) {
    return reject(RendezvousFault::kBadCommand,
                  "ramp = " + std::to_string(c.ramp) + " is not 0, 1 or -1 (the nearer)");
  }
  if (!(std::isfinite(c.time_budget_s) && c.time_budget_s >= 0.0)) {
    return reject(RendezvousFault::kBadCommand,
                  "time_budget_s = " + FormatNumber(c.time_budget_s) + " must be >= 0");
  }
  if (!PoseFresh(now)) {
    return reject(RendezvousFault::kStalePose,
                  pose_ ? "dl/pose is " + FormatNumber(ToSeconds(now - pose_->stamp)) +
                              " s old (limit " + FormatNumber(options_.pose_stale_s) + " s)"
                        : "no dl/pose received yet");
  }
  const double range = (c.target_estimate.head<2>() - RoverXy()).norm();
  if (range > options_.max_target_range) {
    return reject(RendezvousFault::kBadCommand,
                  "target_estimate is " + FormatNumber(range) + " m away, beyond max_target_range " +
                      FormatNumber(options_.max_target_range) + " m");
  }

  command_ = c;
  standoff_ = standoff;
  status_ = {};
  status_.command_id = c.command_id;
  status_.ramp = c.ramp;
  center_ = c.target_estimate.head<2>();
  center_z_ = pose_->site_from_rover.translation().z();
  // The a-priori estimate as a weak measurement: 1-sigma of a fifth of the range (>= 2 m).
  const double sigma0 = std::max(2.0, 0.2 * range);
  info_ = Eigen::Matrix2d::Identity() / (sigma0 * sigma0);
  info_vec_ = info_ * center_;
  status_.target_position = Eigen::Vector3d(center_.x(), center_.y(), center_z_);
  status_.target_sigma = sigma0;
  search_bearing_offset_ = 0.0;
  search_count_ = mobility_retries_ = orbit_legs_ = servo_steps_ = fixes_ = blind_legs_ = range_conflicts_ = 0;
  backups_ = 0;
  goal_ramp_.reset();
  servo_started_ = false;
  deadline_ = now + Seconds(c.time_budget_s > 0.0 ? c.time_budget_s : options_.default_time_budget_s);
  status_.phase = range > kMidRangeLimit ? RendezvousPhase::kLongRange : RendezvousPhase::kMidRange;
  status_.message = "started " + FormatNumber(range) + " m from the a-priori lander";
  Reply(&out);
  LookAtLander(now, &out);
  return out;
}

ExecutorOutput RendezvousExecutor::OnPose(const msg::PoseSample& pose, Time) {
  pose_ = pose;
  return {};
}

ExecutorOutput RendezvousExecutor::OnMastStatus(const msg::MastStatus& s, Time now) {
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

ExecutorOutput RendezvousExecutor::OnStereoPair(const NavcamPair& pair, Time now) {
  ExecutorOutput out;
  if (wait_ != Wait::kFrame || pair.request_id != outstanding_) return out;
  wait_ = Wait::kNone;
  ++status_.images;
  if (!PoseFresh(now)) {
    Fail(RendezvousFault::kStalePose, "dl/pose is stale at the sighting", &out);
    return out;
  }
  const bool close = status_.phase == RendezvousPhase::kCloseRange;
  if (!close) {
    // The search window follows the look-around: the ground under where the mast looks.
    const Eigen::Vector2d look = LookTarget();
    const Eigen::Vector3d prior_site(look.x(), look.y(), center_z_);
    const Eigen::Vector3d prior_rover = pose_->site_from_rover.inverse() * prior_site;
    Result<LanderFix> fix = vision_->SightLander(pair, prior_rover);
    if (DetectionImage img = vision_->LastDrawing(); img.bgr) out.images.push_back(img);
    if (!fix.ok()) {
      Fail(RendezvousFault::kCamera, "NAVCAM pair unusable: " + fix.status().message(), &out);
      return out;
    }
    OnLanderFix(*fix, now, &out);
  } else {
    Result<RampFix> fix = vision_->SightRamp(pair);
    if (DetectionImage img = vision_->LastDrawing(); img.bgr) out.images.push_back(img);
    if (!fix.ok()) {
      Fail(RendezvousFault::kCamera, "NAVCAM pair unusable: " + fix.status().message(), &out);
      return out;
    }
    OnRampFix(*fix, now, &out);
  }
  return out;
}

ExecutorOutput RendezvousExecutor::OnMobilityStatus(const msg::MobilityStatus& s, Time now) {
  ExecutorOutput out;
  if (wait_ != Wait::kDrive || s.command_id != outstanding_) return out;
  if (s.state == msg::MobilityState::kSucceeded) {
    wait_ = Wait::kNone;
    mobility_retries_ = 0;
    AfterDrive(now, &out);
  } else if (s.state == msg::MobilityState::kFailed || s.state == msg::MobilityState::kRejected) {
    wait_ = Wait::kNone;
    const std::string why =
        "apl-mobility " + std::string(msg::MobilityFaultName(s.fault)) + ": " + s.message;
    const bool retry = (drive_kind_ == DriveKind::kLeg || drive_kind_ == DriveKind::kOrbit) &&
                       s.fault_class == msg::FaultClass::kGoalError &&
                       mobility_retries_ < kMaxMobilityRetries;
    if (!retry) {
      Fail(RendezvousFault::kMobility, why, &out);
      return out;
    }
    ++mobility_retries_;
    status_.message = "leg ended (" + why + "); looking again";
    Reply(&out);
    LookAtLander(now, &out);
  }
  return out;
}

ExecutorOutput RendezvousExecutor::Step(Time now) {
  ExecutorOutput out;
  if (wait_ == Wait::kNone) return out;
  if (now > deadline_) {
    Fail(RendezvousFault::kTimeout, "time budget of " +
                                        FormatNumber(command_.time_budget_s > 0.0
                                                         ? command_.time_budget_s
                                                         : options_.default_time_budget_s) +
                                        " s used up in phase " +
                                        msg::RendezvousPhaseName(status_.phase),
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
    case Wait::kHold:
      if (waited >= options_.hold_at_base_s) {
        wait_ = Wait::kNone;
        if (command_.climb) {
          StartClimb(now, &out);
        } else {
          status_.phase = RendezvousPhase::kDone;
          Reply(&out);
        }
      }
      break;
    case Wait::kDrive:
      // apl-mobility ends every command within its budget; a status that never comes is a fault.
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

// ---- decisions ------------------------------------------------------------------------------

bool RendezvousExecutor::FarFixConsistent(const Eigen::Vector3d& c_site,
                                          const Eigen::Matrix3d& covariance_rover,
                                          std::string* detail, bool* range_conflict) const {
  *range_conflict = false;
  // The fix is rough along the view and sharp across it; the estimate's spread across and
  // along the view comes from its information matrix (after one far fix it too is sharp across
  // and rough along). Gate the bearing at 3 sigma of both (at least 1 deg, never wider than the
  // window the detector searched) and the range at 3 sigma of both.
  const Eigen::Isometry3d& site_from_rover = pose_->site_from_rover;
  const Eigen::Vector2d rover = RoverXy();
  const Eigen::Vector2d to_fix = c_site.head<2>() - rover, to_est = center_ - rover;
  const double r_f = std::max(to_fix.norm(), 1e-3), r_e = std::max(to_est.norm(), 1.0);
  const double db = std::abs(geometry::WrapAngle(std::atan2(to_fix.y(), to_fix.x()) -
                                                 std::atan2(to_est.y(), to_est.x())));
  const Eigen::Vector2d u = to_fix / r_f, n(-u.y(), u.x());
  const Eigen::Matrix2d c_fix =
      (site_from_rover.linear() * covariance_rover * site_from_rover.linear().transpose())
          .topLeftCorner<2, 2>();
  const Eigen::Matrix2d c_est = info_.inverse();
  const double s_b = std::hypot(std::sqrt(std::max(0.0, n.dot(c_fix * n))) / r_f,
                                std::sqrt(std::max(0.0, n.dot(c_est * n))) / r_e);
  const double s_r = std::hypot(std::sqrt(std::max(0.0, u.dot(c_fix * u))),
                                std::sqrt(std::max(0.0, u.dot(c_est * u))));
  const double b_gate =
      std::min(std::max(3.0 * s_b, kDegree), FarSearchHalfWindow(r_e, options_.prior_gate));
  *detail = " (fix " + FormatNumber(r_f) + " m at " + FormatNumber(db / kDegree) +
            " deg from the estimate's bearing, gate " + FormatNumber(b_gate / kDegree) +
            " deg; estimate " + FormatNumber(r_e) + " m, range gate " + FormatNumber(3.0 * s_r) +
            " m)";
  if (db > b_gate) return false;
  if (std::abs(r_f - r_e) <= 3.0 * s_r) return true;
  *range_conflict = true;
  return false;
}

void RendezvousExecutor::WeakenRange(double relative_sigma) {
  const Eigen::Vector2d to = center_ - RoverXy();
  const double r = to.norm();
  if (r <= 1.0) return;
  const Eigen::Vector2d u = to / r;
  const double i_u = u.dot(info_ * u), i_max = 1.0 / std::pow(relative_sigma * r, 2);
  if (i_u > i_max) {
    info_ -= (i_u - i_max) * u * u.transpose();
    info_vec_ = info_ * center_;
  }
}

void RendezvousExecutor::OnLanderFix(const LanderFix& fix, Time now, ExecutorOutput* out) {
  const Eigen::Isometry3d& site_from_rover = pose_->site_from_rover;
  bool accepted = false;
  if (fix.found) {
    const Eigen::Vector3d c_site = site_from_rover * fix.center_rover;
    const double off = (c_site.head<2>() - center_).norm();
    // A fixed gate, not one widened by the estimate's sigma: with a wide a-priori sigma a rock
    // and a soil edge 15 m off the estimate passed as the lander (campaign seed 8).
    const double gate = options_.prior_gate;
    bool inside = off <= gate;
    std::string detail, reset_note;
    if (fix.far) {
      bool range_conflict = false;
      inside = FarFixConsistent(c_site, fix.covariance, &detail, &range_conflict);
      // Fixes on the estimate's bearing that keep disagreeing with its range: the estimate's
      // range is what is wrong (one biased far fix made it confident). After
      // kMaxRangeConflicts since the last accepted fix (misses and off-bearing fixes between
      // them do not count), weaken its information along the view to 30 % of the distance and
      // take the fix.
      if (range_conflict) ++range_conflicts_;  // cleared by an accepted fix, not by misses
      if (range_conflict && range_conflicts_ >= kMaxRangeConflicts) {
        WeakenRange(kResetRangeSigma);
        inside = FarFixConsistent(c_site, fix.covariance, &detail, &range_conflict);
        reset_note = "; the estimate's range was reset after " + std::to_string(range_conflicts_) +
                     " fixes on its bearing disagreed with it";
        detail += reset_note;
        range_conflicts_ = 0;
      }
    }
    if (inside) {
      const Eigen::Matrix3d cov =
          site_from_rover.linear() * fix.covariance * site_from_rover.linear().transpose();
      const Eigen::Matrix2d cov2 = cov.topLeftCorner<2, 2>() + 1e-6 * Eigen::Matrix2d::Identity();
      const Eigen::Matrix2d inv = cov2.inverse();
      info_ += inv;
      info_vec_ += inv * c_site.head<2>();
      center_ = info_.ldlt().solve(info_vec_);
      // Far fixes share their range bias: averaging them must not make the estimate's range
      // better than kFarRangeFloor of the distance.
      if (fix.far) WeakenRange(kFarRangeFloor);

      center_z_ = c_site.z() - lander_.deck_height;  // the ground at the deck centre
      const Eigen::Vector2d d = center_ - RoverXy();
      const Eigen::Vector3d in_rover = fix.center_rover;
      status_.range = std::hypot(in_rover.x(), in_rover.y());
      status_.bearing = std::atan2(in_rover.y(), in_rover.x());
      const Eigen::Vector2d u = in_rover.head<2>() / std::max(status_.range, 1e-6);
      const Eigen::Matrix2d c2 = fix.covariance.topLeftCorner<2, 2>();
      status_.range_sigma = std::sqrt(std::max(0.0, u.dot(c2 * u)));
      const Eigen::Vector2d n(-u.y(), u.x());
      status_.bearing_sigma =
          std::sqrt(std::max(0.0, n.dot(c2 * n))) / std::max(status_.range, 1e-6);
      status_.target_position = Eigen::Vector3d(center_.x(), center_.y(), center_z_);
      status_.target_sigma = std::sqrt(std::max(0.0, info_.inverse().trace() / 2.0));
      status_.features = fix.features;
      status_.message = "lander at " + FormatNumber(d.norm()) + " m" + reset_note;
      accepted = true;
      ++fixes_;
      range_conflicts_ = 0;
    } else {
      status_.features = fix.features;
      status_.message = "a lander-like fix " + FormatNumber(off) +
                        " m from the estimate was rejected" +
                        (fix.far ? detail : " (gate " + FormatNumber(gate) + " m)");
    }
  } else {
    status_.features = "";
    status_.message = "lander not seen: " + fix.why;
  }
  Reply(out);
  if (!accepted) {
    // Beyond the detector's reach the a-priori estimate leads: drive a leg towards it and look
    // again (a fix was not seen, so nothing false is driven to).
    const double prior_range = (center_ - RoverXy()).norm();
    // Long range (seed 004 phase 1): the traverse starts only once the long-range detector has
    // acquired the lander; a later miss lets the estimate lead the next leg (reacquisition every
    // reacquire_step), as does a mid-range miss beyond sight_range (its reach is ~35 m).
    if (prior_range > options_.sight_range && !fix.found && (fixes_ > 0 || !fix.far)) {
      search_count_ = 0;
      search_bearing_offset_ = 0.0;
      status_.message += "; beyond sight range (" + FormatNumber(prior_range) +
                         " m to the estimate): a leg towards it";
      Reply(out);
      const Eigen::Vector2d rover = RoverXy();
      const Eigen::Vector2d to = (center_ - rover).normalized();
      const double step = std::min(options_.reacquire_step, prior_range - options_.sight_range + 1.0);
      DriveTo(rover + step * to, options_.autonav_tolerance, DriveKind::kLeg, now, out);
      return;
    }
    // Lost after several fixes (a view the detector misses): the estimate is good enough to
    // lead a leg towards the approach point, at most kMaxBlindLegs times in a row.
    ++search_count_;
    if (fixes_ >= 2 && status_.target_sigma < kTrustedSigma && blind_legs_ < kMaxBlindLegs &&
        search_count_ >= 3) {
      ++blind_legs_;
      status_.message += "; the estimate (sigma " + FormatNumber(status_.target_sigma) +
                         " m) leads the next leg";
      Reply(out);
      Advance(now, out);
      return;
    }
    if (search_count_ >= options_.search_images) {
      Fail(RendezvousFault::kNotFound,
           "lander not found in " + std::to_string(search_count_) + " pairs: " + status_.message,
           out);
      return;
    }
    // Look around the estimate: 0, +s, -s, +2s, -2s, ...
    const int k = (search_count_ + 1) / 2;
    const double sign = search_count_ % 2 == 1 ? 1.0 : -1.0;
    // Far away the detector's window is narrow: step by 1.6 of its half width, not by the
    // mid-range pan step.
    double step = options_.search_pan_step_deg * kDegree;
    if (prior_range > options_.sight_range) {
      step = std::min(step, 1.6 * FarSearchHalfWindow(prior_range, options_.prior_gate));
    }
    search_bearing_offset_ = sign * k * step;
    LookAtLander(now, out);
    return;
  }
  search_count_ = 0;
  blind_legs_ = 0;
  Advance(now, out);
}

void RendezvousExecutor::Advance(Time now, ExecutorOutput* out) {
  search_count_ = 0;
  search_bearing_offset_ = 0.0;
  const Eigen::Vector2d rover = RoverXy();
  const Eigen::Vector2d to_rover = rover - center_;
  const double dist = to_rover.norm();
  if (dist <= options_.approach_radius + 1.0) {
    SetPhase(RendezvousPhase::kCloseRange, out);
    LookAtLander(now, out);  // the next pair is read for stripes
    return;
  }
  if (dist <= kMidRangeLimit) SetPhase(RendezvousPhase::kMidRange, out);
  // After a refused leg (a rock on the approach point, no path) the approach point moves round
  // the lander: +20, -20, +40 deg, ...
  const int k = (mobility_retries_ + 1) / 2;
  const double turn = (mobility_retries_ % 2 == 1 ? 1.0 : -1.0) * k * kApproachShiftDeg * kDegree;
  const Eigen::Vector2d approach =
      center_ + options_.approach_radius * Unit(std::atan2(to_rover.y(), to_rover.x()) + turn);
  const Eigen::Vector2d leg = approach - rover;
  const double step = std::min(leg.norm(), options_.reacquire_step);
  DriveTo(rover + step * leg.normalized(), options_.autonav_tolerance, DriveKind::kLeg, now, out);
}

RendezvousExecutor::RampGoal RendezvousExecutor::RampGoalFromFix(const RampFix& fix) const {
  const Eigen::Isometry3d site_from_ramp = pose_->site_from_rover * fix.rover_from_ramp;
  const Eigen::Vector3d u = site_from_ramp.linear().col(0);
  RampGoal g;
  g.ramp = fix.ramp;
  const double horizontal = u.head<2>().norm();
  g.axis = u.head<2>() / std::max(horizontal, 1e-9);
  g.slope_len = lander_.ramp_length / std::max(horizontal, 0.3);
  g.base = site_from_ramp * Eigen::Vector3d(-0.5 * g.slope_len, 0.0, 0.0);
  return g;
}

RendezvousExecutor::RampGoal RendezvousExecutor::OtherRamp(const RampGoal& g) const {
  // Ramp 1 leaves the opposite deck edge: its foot is the mirror of this one about the centre.
  const double reach = lander_.Apothem() + lander_.ramp_length;
  const Eigen::Vector2d c = g.base.head<2>() + reach * g.axis;
  RampGoal o = g;
  o.ramp = 1 - g.ramp;
  o.axis = -g.axis;
  o.base.head<2>() = c + reach * g.axis;
  return o;
}

Eigen::Vector2d RendezvousExecutor::ServoStart() const {
  return goal_ramp_->base.head<2>() - (standoff_ + options_.servo_run) * goal_ramp_->axis;
}

void RendezvousExecutor::OnRampFix(const RampFix& fix, Time now, ExecutorOutput* out) {
  status_.features = fix.features;
  const bool usable = fix.found && fix.stripes >= options_.min_stripes;
  if (!usable) {
    status_.message = fix.found ? "ramp " + std::to_string(fix.ramp) + ": " +
                                      std::to_string(fix.stripes) + " stripes, need " +
                                      std::to_string(options_.min_stripes)
                                : "no ramp stripes: " + fix.why;
    Reply(out);
    if (servo_started_) {
      Fail(RendezvousFault::kTooFewStripes, "at the ramp base: " + status_.message, out);
      return;
    }
    Orbit(now, out);
    return;
  }
  const RampGoal seen = RampGoalFromFix(fix);
  const int want = command_.ramp >= 0 ? command_.ramp : (goal_ramp_ ? goal_ramp_->ramp : fix.ramp);
  goal_ramp_ = seen.ramp == want ? seen : OtherRamp(seen);
  status_.ramp = goal_ramp_->ramp;
  // The deck centre from the ramp: far better than the mid-range fix.
  const double reach = lander_.Apothem() + lander_.ramp_length;
  center_ = seen.base.head<2>() + reach * seen.axis;
  info_ = Eigen::Matrix2d::Identity() / (0.05 * 0.05);
  info_vec_ = info_ * center_;
  status_.target_position = Eigen::Vector3d(center_.x(), center_.y(), seen.base.z());
  status_.target_sigma = fix.base_sigma;
  const Eigen::Vector3d c_rover =
      pose_->site_from_rover.inverse() * Eigen::Vector3d(center_.x(), center_.y(), seen.base.z());
  status_.range = std::hypot(c_rover.x(), c_rover.y());
  status_.bearing = std::atan2(c_rover.y(), c_rover.x());
  status_.range_sigma = fix.base_sigma;
  status_.bearing_sigma = fix.base_sigma / std::max(status_.range, 1.0);

  if (goal_ramp_->ramp != seen.ramp || !servo_started_) {
    // Not yet on the chosen ramp's axis: orbit or drive to the servo start.
    const Eigen::Vector2d start = ServoStart();
    const Eigen::Vector2d rover = RoverXy();
    if ((start - rover).norm() > options_.pre_point_tolerance) {
      const double a_rover = std::atan2(rover.y() - center_.y(), rover.x() - center_.x());
      const double a_start = std::atan2(start.y() - center_.y(), start.x() - center_.x());
      const double gap = std::abs(geometry::WrapAngle(a_start - a_rover));
      status_.message = "ramp " + std::to_string(seen.ramp) + " seen (" +
                        std::to_string(fix.stripes) + " stripes); to ramp " +
                        std::to_string(goal_ramp_->ramp) + "'s axis";
      Reply(out);
      if (gap > options_.circle_step_deg * kDegree) {
        Orbit(now, out);
        return;
      }
      const double d = (start - rover).norm();
      if (d > 3.0) {
        DriveTo(start, options_.pre_point_tolerance, DriveKind::kToServoStart, now, out);
      } else {
        msg::MobilityCommand c;
        c.mode = msg::MobilityMode::kGoToWaypoint;
        c.goal = Eigen::Vector3d(start.x(), start.y(), 0.0);
        c.tolerance = 0.5 * options_.pre_point_tolerance;
        Drive(c, DriveKind::kToServoStart, now, out);
      }
      return;
    }
    servo_started_ = true;
  }

  // Servo in the rover frame of this pair: P* = base - standoff a.
  const Eigen::Isometry3d& T = fix.rover_from_ramp;
  const Eigen::Vector3d u = T.linear().col(0);
  const Eigen::Vector2d a = u.head<2>().normalized();
  const double slope_len = lander_.ramp_length / std::max(u.head<2>().norm(), 0.3);
  const Eigen::Vector2d base = (T * Eigen::Vector3d(-0.5 * slope_len, 0.0, 0.0)).head<2>();
  const Eigen::Vector2d target = base - standoff_ * a;
  const Eigen::Vector2d n(-a.y(), a.x());
  const double along = target.dot(a);      // > 0: the placement point is still ahead
  const double lateral = -target.dot(n);   // rover origin left of the axis
  const double heading = std::atan2(a.y(), a.x());  // turn left by this to face up the ramp
  status_.message = "ramp " + std::to_string(fix.ramp) + " servo " +
                    std::to_string(servo_steps_) + ": lateral " + Cm(lateral) + ", along " +
                    Cm(-along) + ", heading " + Deg(-heading) + " (" +
                    std::to_string(fix.stripes) + " stripes, " + FormatNumber(fix.rms_px) +
                    " px rms)";
  const bool good = std::abs(lateral) <= options_.lateral_tolerance &&
                    std::abs(along) <= options_.along_tolerance &&
                    std::abs(heading) <= options_.heading_tolerance_deg * kDegree;
  const bool acceptable = std::abs(lateral) <= options_.accept_lateral &&
                          std::abs(along) <= options_.accept_along &&
                          std::abs(heading) <= options_.accept_heading_deg * kDegree;
  // Too close to take a lateral error out means backing up; after one back-up an acceptable
  // placement is kept instead (campaign seed 10 alternated forward and back until it ran out of
  // steps), and so is one on the last step that could still correct.
  const bool needs_backup =
      along < 0.15 && std::abs(lateral) > options_.lateral_tolerance;
  const bool settle = acceptable && ((needs_backup && backups_ >= 1) ||
                                     servo_steps_ >= options_.max_servo_steps - 1);
  if (good || settle || (servo_steps_ >= options_.max_servo_steps && acceptable)) {
    status_.phase = RendezvousPhase::kAtRampBase;
    status_.message = "at the base of ramp " + std::to_string(fix.ramp) + ": lateral " +
                      Cm(lateral) + ", along " + Cm(-along) + ", heading " + Deg(-heading) +
                      " (own estimate)";
    Reply(out);
    wait_ = Wait::kHold;
    wait_since_ = now;
    return;
  }
  if (servo_steps_ >= options_.max_servo_steps) {
    Fail(RendezvousFault::kPlacement, "no placement within " +
                                          std::to_string(options_.max_servo_steps) +
                                          " steps: " + status_.message,
         out);
    return;
  }
  Reply(out);
  ++servo_steps_;
  // Aim: the placement point, or one `approach` short of it when it is far (a second look
  // follows); back up when a lateral error is left with too little run to take it out.
  const double approach = 0.4;
  Eigen::Vector2d aim = target;
  if (along > approach + 0.15) aim = target - approach * a;
  if (needs_backup) {
    aim = target - approach * a;
    ++backups_;
  }
  msg::MobilityCommand c;
  c.mode = msg::MobilityMode::kDirected;
  const double dist = aim.norm();
  if (dist > 0.002) {
    const bool backwards = aim.x() < 0.0;
    const double face = backwards ? std::atan2(-aim.y(), -aim.x()) : std::atan2(aim.y(), aim.x());
    if (std::abs(face) > 0.05 * kDegree) c.primitives.push_back(Turn(face));
    c.primitives.push_back(Straight(backwards ? -dist : dist));
    const double rest = geometry::WrapAngle(heading - face);
    if (std::abs(rest) > 0.05 * kDegree) c.primitives.push_back(Turn(rest));
  } else {
    c.primitives.push_back(Turn(heading));
  }
  Drive(c, DriveKind::kServo, now, out);
}

void RendezvousExecutor::Orbit(Time now, ExecutorOutput* out) {
  const int max_legs = static_cast<int>(std::ceil(360.0 / options_.circle_step_deg)) + 1;
  if (++orbit_legs_ > max_legs) {
    Fail(RendezvousFault::kNotFound,
         "no usable ramp seen after " + std::to_string(orbit_legs_ - 1) +
             " legs around the lander: " + status_.message,
         out);
    return;
  }
  const Eigen::Vector2d rover = RoverXy();
  const double a_rover = std::atan2(rover.y() - center_.y(), rover.x() - center_.x());
  double dir = 1.0, step = options_.circle_step_deg * kDegree;
  if (goal_ramp_) {
    const Eigen::Vector2d start = ServoStart();
    const double gap = geometry::WrapAngle(
        std::atan2(start.y() - center_.y(), start.x() - center_.x()) - a_rover);
    dir = gap >= 0.0 ? 1.0 : -1.0;
    step = std::min(step, std::abs(gap));
  }
  // A refused orbit leg retries on a wider circle.
  const double radius = OrbitRadius() + 0.6 * mobility_retries_;
  const Eigen::Vector2d p = center_ + radius * Unit(a_rover + dir * step);
  status_.message += "; orbiting";
  Reply(out);
  DriveTo(p, options_.autonav_tolerance, DriveKind::kOrbit, now, out);
}

void RendezvousExecutor::AfterDrive(Time now, ExecutorOutput* out) {
  switch (drive_kind_) {
    case DriveKind::kClimb: {
      const double rise = pose_->site_from_rover.translation().z() - climb_start_z_;
      const Eigen::Vector3d up = pose_->site_from_rover.linear().col(2);
      const double tilt = std::acos(std::clamp(up.z(), -1.0, 1.0));
      if (rise >= 0.5 * lander_.deck_height && tilt < 8.0 * kDegree) {
        status_.phase = RendezvousPhase::kDone;
        status_.message = "on the deck: rose " + FormatNumber(rise) + " m, tilt " +
                          FormatNumber(tilt / kDegree) + " deg";
        Reply(out);
      } else {
        Fail(RendezvousFault::kMobility, "climb ended off the deck: rose " + FormatNumber(rise) +
                                             " m, tilt " + FormatNumber(tilt / kDegree) + " deg",
             out);
      }
      return;
    }
    case DriveKind::kServo:
    case DriveKind::kToServoStart: {
      if (drive_kind_ == DriveKind::kToServoStart) {
        servo_started_ = true;  // from here on, too few stripes ends the rendezvous
        // Face up the ramp before the first servo look.
        const double turn =
            geometry::WrapAngle(std::atan2(goal_ramp_->axis.y(), goal_ramp_->axis.x()) -
                                RoverHeading());
        drive_kind_ = DriveKind::kServo;
        if (std::abs(turn) > 0.5 * kDegree) {
          msg::MobilityCommand c;
          c.mode = msg::MobilityMode::kDirected;
          c.primitives.push_back(Turn(turn));
          Drive(c, DriveKind::kServo, now, out);
          return;
        }
      }
      // Look at the middle of the stripe block of the chosen ramp.
      const Eigen::Vector3d mid =
          goal_ramp_->base + Eigen::Vector3d(0.5 * lander_.ramp_length * goal_ramp_->axis.x(),
                                             0.5 * lander_.ramp_length * goal_ramp_->axis.y(),
                                             0.5 * lander_.deck_height);
      LookAt(mid, now, out);
      return;
    }
    case DriveKind::kLeg:
    case DriveKind::kOrbit:
      if (status_.phase == RendezvousPhase::kCloseRange && goal_ramp_) {
        // Look at the chosen ramp's middle: the orbit brings it into view.
        const Eigen::Vector3d mid =
            goal_ramp_->base + Eigen::Vector3d(0.5 * lander_.ramp_length * goal_ramp_->axis.x(),
                                               0.5 * lander_.ramp_length * goal_ramp_->axis.y(),
                                               0.5 * lander_.deck_height);
        LookAt(mid, now, out);
        return;
      }
      LookAtLander(now, out);
      return;
  }
}

void RendezvousExecutor::StartClimb(Time now, ExecutorOutput* out) {
  status_.phase = RendezvousPhase::kClimb;
  status_.message = "climbing ramp " + std::to_string(goal_ramp_->ramp);
  Reply(out);
  climb_start_z_ = pose_->site_from_rover.translation().z();
  msg::MobilityCommand c;
  c.mode = msg::MobilityMode::kDirected;
  c.max_tilt = options_.climb_max_tilt_deg * kDegree;
  c.primitives.push_back(Straight(standoff_ + goal_ramp_->slope_len + lander_.Apothem()));
  Drive(c, DriveKind::kClimb, now, out);
}

}  // namespace rover::apl::rendezvous
