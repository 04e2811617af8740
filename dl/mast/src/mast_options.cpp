#include "rover/dl/mast/mast_options.hpp"

#include "rover/base/param_binder.hpp"
#include "rover/base/range_check.hpp"

namespace rover::dl::mast {

Status MastOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckRange("pan_min", pan_min, -180.0 * kDegree, 180.0 * kDegree, "rad"));
  ROVER_RETURN_IF_ERROR(CheckRange("pan_max", pan_max, Bounds::OpenLow(pan_min, 180.0 * kDegree),
                                   "rad"));
  ROVER_RETURN_IF_ERROR(CheckRange("tilt_min", tilt_min, -90.0 * kDegree, 90.0 * kDegree, "rad"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("tilt_max", tilt_max, Bounds::OpenLow(tilt_min, 90.0 * kDegree), "rad"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("tolerance", tolerance, Bounds::OpenLow(0.0, 10.0 * kDegree), "rad"));
  ROVER_RETURN_IF_ERROR(CheckRange("speed", speed, Bounds::OpenLow(0.0, 5.0), "rad/s"));
  ROVER_RETURN_IF_ERROR(CheckPositive("max_timeout_s", max_timeout_s, "s"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("timeout_s", timeout_s, Bounds::OpenLow(0.0, max_timeout_s), "s"));
  ROVER_RETURN_IF_ERROR(CheckPositive("joint_stale_s", joint_stale_s, "s"));
  ROVER_RETURN_IF_ERROR(CheckPositive("pose_stale_s", pose_stale_s, "s"));
  ROVER_RETURN_IF_ERROR(CheckPositive("min_look_distance", min_look_distance, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("check_rate_hz", check_rate_hz, Bounds::OpenLow(0.0, 100.0),
                                   "Hz"));
  return CheckRange("status_rate_hz", status_rate_hz, Bounds::OpenLow(0.0, check_rate_hz), "Hz");
}

void MastOptions::BindParams(ParamBinder<MastOptions>& b) {
  b.BindDegrees("pan_min_deg", &MastOptions::pan_min, "lowest pan goal accepted (+ looks left)")
      .Range(-180.0, 180.0);
  b.BindDegrees("pan_max_deg", &MastOptions::pan_max, "highest pan goal accepted")
      .Range(-180.0, 180.0);
  b.BindDegrees("tilt_min_deg", &MastOptions::tilt_min, "lowest tilt goal accepted (+ looks up)")
      .Range(-90.0, 90.0);
  b.BindDegrees("tilt_max_deg", &MastOptions::tilt_max, "highest tilt goal accepted")
      .Range(-90.0, 90.0);
  b.BindDegrees("tolerance_deg", &MastOptions::tolerance,
                "|measured - goal| per joint that counts as at the goal")
      .Range(0.0, 10.0);
  b.Bind("speed", &MastOptions::speed, "rad/s", "rate limit of each mast motor during a move")
      .Range(0.0, 5.0);
  b.Bind("timeout_s", &MastOptions::timeout_s, "s",
         "run-clock limit of a move when the command's timeout_s is 0")
      .Range(0.0, 3600.0);
  b.Bind("max_timeout_s", &MastOptions::max_timeout_s, "s",
         "largest timeout_s a command may ask for")
      .Range(0.0, 3600.0);
  b.Bind("joint_stale_s", &MastOptions::joint_stale_s, "s",
         "ddl/joint_state older than this is stale (commands refused, moves fault)")
      .Range(0.0, 60.0);
  b.Bind("pose_stale_s", &MastOptions::pose_stale_s, "s",
         "dl/pose older than this cannot serve a look-at command")
      .Range(0.0, 60.0);
  b.Bind("min_look_distance", &MastOptions::min_look_distance, "m",
         "look-at points nearer the mast head than this are refused")
      .Range(0.0, 100.0);
  b.Bind("check_rate_hz", &MastOptions::check_rate_hz, "Hz",
         "state-machine step: timeouts, staleness, arrival")
      .Range(0.0, 100.0);
  b.Bind("status_rate_hz", &MastOptions::status_rate_hz, "Hz",
         "dl/mast_status rate while moving (it is also sent on every change)")
      .Range(0.0, 100.0);
}

}  // namespace rover::dl::mast
