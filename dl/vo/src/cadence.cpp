#include "rover/dl/vo/cadence.hpp"

#include <cmath>
#include <string>

#include "rover/base/check.hpp"

namespace rover::dl::vo {
namespace {

double AngleBetween(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  return a.angularDistance(b);
}

Status CheckRange(const char* name, double v, double lo, double hi, bool open_lo) {
  const bool ok = std::isfinite(v) && (open_lo ? v > lo : v >= lo) && v <= hi;
  if (ok) return Status::Ok();
  return InvalidArgument(std::string("cadence ") + name + " " + std::to_string(v) + " is outside " +
                         (open_lo ? "(" : "[") + std::to_string(lo) + ", " + std::to_string(hi) +
                         "]");
}

}  // namespace

void CadenceOptions::BindParams(ParamBinder<CadenceOptions>& b) {
  b.Bind("step_distance", &CadenceOptions::step_distance, "m",
         "odometer travelled between two pairs while driving (MER: <= ~0.6 m)")
      .Range(0.05, 0.9);
  b.BindDegrees("step_angle_deg", &CadenceOptions::step_angle,
                "turn between two pairs while driving (turns in place move no odometer)")
      .Range(1.0, 20.0);
  b.Bind("max_interval_s", &CadenceOptions::max_interval_s, "s",
         "run-clock time between two pairs while driving, at most")
      .Range(0.5, 3600.0);
  b.Bind("moving_speed", &CadenceOptions::moving_speed, "m/s",
         "dl/pose speed or odometer rate above which the rover is driving")
      .Range(0.0001, 1.0);
  b.BindScaled("moving_rate_deg_s", &CadenceOptions::moving_rate, 3.14159265358979323846 / 180.0,
               "deg/s", "turn rate above which the rover is driving")
      .Range(0.001, 30.0);
  b.Bind("settle_s", &CadenceOptions::settle_s, "s", "at rest before the end-of-drive pair")
      .Range(0.0, 60.0);
  b.Bind("min_distance", &CadenceOptions::min_distance, "m",
         "moved since the last pair for an end-of-drive pair")
      .Range(0.0, 0.9);
  b.BindDegrees("min_angle_deg", &CadenceOptions::min_angle,
                "turned since the last pair for an end-of-drive pair")
      .Range(0.0, 20.0);
}

Status CadenceOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckRange("step_distance", step_distance, 0.0, 0.9, true));
  ROVER_RETURN_IF_ERROR(CheckRange("step_angle", step_angle, 0.0, 0.35, true));
  ROVER_RETURN_IF_ERROR(CheckRange("max_interval_s", max_interval_s, 0.0, 1e6, true));
  ROVER_RETURN_IF_ERROR(CheckRange("moving_speed", moving_speed, 0.0, 10.0, true));
  ROVER_RETURN_IF_ERROR(CheckRange("moving_rate", moving_rate, 0.0, 10.0, true));
  ROVER_RETURN_IF_ERROR(CheckRange("settle_s", settle_s, 0.0, 1e6, false));
  ROVER_RETURN_IF_ERROR(CheckRange("min_distance", min_distance, 0.0, step_distance, false));
  ROVER_RETURN_IF_ERROR(CheckRange("min_angle", min_angle, 0.0, step_angle, false));
  return Status::Ok();
}

VoCadence::VoCadence(const CadenceOptions& options) : options_(options) {
  ROVER_DEMAND(options_.Validate().ok());
}

void VoCadence::OnPose(Time t, double odometer, double speed, const Eigen::Quaterniond& attitude,
                       bool stationary) {
  const Eigen::Quaterniond q = attitude.normalized();
  if (last_pose_.has_value()) {
    if (t <= last_pose_->t) return;
    const double dt = ToSeconds(t - last_pose_->t);
    const bool moved =
        !stationary && (std::abs(speed) > options_.moving_speed ||
                        std::abs(odometer - last_pose_->odometer) / dt > options_.moving_speed ||
                        AngleBetween(last_pose_->attitude, q) / dt > options_.moving_rate);
    if (moved) {
      driving_ = true;
      last_motion_ = t;
    } else if (driving_ && ToSeconds(t - last_motion_) >= options_.settle_s) {
      driving_ = false;
    }
  } else if (!stationary && std::abs(speed) > options_.moving_speed) {
    driving_ = true;
    last_motion_ = t;
  }
  last_pose_ = State{t, odometer, q};
}

VoCadence::Reason VoCadence::Due(Time now) const {
  if (!last_pose_.has_value()) return Reason::kNone;
  if (!last_capture_.has_value()) return Reason::kFirst;
  const double moved = std::abs(last_pose_->odometer - last_capture_->odometer);
  const double turned = AngleBetween(last_capture_->attitude, last_pose_->attitude);
  if (driving_) {
    if (moved >= options_.step_distance) return Reason::kDistance;
    if (turned >= options_.step_angle) return Reason::kRotation;
    if (ToSeconds(now - last_capture_->t) >= options_.max_interval_s) return Reason::kInterval;
    return Reason::kNone;
  }
  if (moved >= options_.min_distance || turned >= options_.min_angle) return Reason::kEndOfDrive;
  return Reason::kNone;
}

void VoCadence::MarkCaptured(Time t, double odometer, const Eigen::Quaterniond& attitude) {
  last_capture_ = State{t, odometer, attitude.normalized()};
}

void VoCadence::Reset() {
  last_pose_.reset();
  last_capture_.reset();
  last_motion_ = Time{0};
  driving_ = false;
}

const char* CadenceReasonName(VoCadence::Reason reason) {
  switch (reason) {
    case VoCadence::Reason::kNone:
      return "none";
    case VoCadence::Reason::kFirst:
      return "first";
    case VoCadence::Reason::kDistance:
      return "distance";
    case VoCadence::Reason::kRotation:
      return "rotation";
    case VoCadence::Reason::kInterval:
      return "interval";
    case VoCadence::Reason::kEndOfDrive:
      return "end_of_drive";
  }
  return "unknown";
}

}  // namespace rover::dl::vo
