#include "rover/dl/arm/arm_options.hpp"

#include "rover/base/param_binder.hpp"
#include "rover/base/range_check.hpp"

namespace rover::dl::arm {

Status ArmOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckRange("speed", speed, Bounds::OpenLow(0.0, 2.0), "rad/s"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("descent_speed", descent_speed, Bounds::OpenLow(0.0, 0.1), "m/s"));
  ROVER_RETURN_IF_ERROR(CheckRange("hover_height", hover_height, Bounds::OpenLow(0.0, 0.5), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("overdrive", overdrive, Bounds::OpenLow(0.0, 0.2), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("tolerance", tolerance, Bounds::OpenLow(0.0, 0.2), "rad"));
  ROVER_RETURN_IF_ERROR(CheckPositive("max_timeout_s", max_timeout_s, "s"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("timeout_s", timeout_s, Bounds::OpenLow(0.0, max_timeout_s), "s"));
  ROVER_RETURN_IF_ERROR(CheckPositive("joint_stale_s", joint_stale_s, "s"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("max_wheel_rate", max_wheel_rate, Bounds::OpenLow(0.0, 10.0), "rad/s"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("check_rate_hz", check_rate_hz, Bounds::OpenLow(0.0, 100.0), "Hz"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("status_rate_hz", status_rate_hz, Bounds::OpenLow(0.0, check_rate_hz), "Hz"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("focus_steps", focus_steps, 3, 30));
  ROVER_RETURN_IF_ERROR(CheckRange("focus_span", focus_span, Bounds::OpenLow(0.0, 0.3), "m"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("focus_max_extra_steps", focus_max_extra_steps, 0, 20));
  ROVER_RETURN_IF_ERROR(CheckRange("focus_image_timeout_s", focus_image_timeout_s,
                                   Bounds::OpenLow(0.0, 120.0), "s"));
  return CheckRange("focus_min_contrast", focus_min_contrast, 1.0, 100.0, "");
}

void ArmOptions::BindParams(ParamBinder<ArmOptions>& b) {
  b.Bind("speed", &ArmOptions::speed, "rad/s",
         "rate limit of the fastest arm joint in an ordinary move (the others are slowed so "
         "that all finish together)")
      .Range(0.0, 2.0);
  b.Bind("descent_speed", &ArmOptions::descent_speed, "m/s",
         "speed of the instrument face during a placement's guarded descent")
      .Range(0.0, 0.1);
  b.Bind("hover_height", &ArmOptions::hover_height, "m",
         "a placement first puts the face this high above the target, face down (also the "
         "lift before stowing)")
      .Range(0.0, 0.5);
  b.Bind("overdrive", &ArmOptions::overdrive, "m",
         "the guarded descent aims this far below the target; contact must stop it before")
      .Range(0.0, 0.2);
  b.Bind("tolerance", &ArmOptions::tolerance, "rad",
         "|measured - goal| per joint that counts as at the goal")
      .Range(0.0, 0.2);
  b.Bind("timeout_s", &ArmOptions::timeout_s, "s",
         "run-clock limit of a command (all its moves) when the command's timeout_s is 0")
      .Range(0.0, 3600.0);
  b.Bind("max_timeout_s", &ArmOptions::max_timeout_s, "s",
         "largest timeout_s a command may ask for")
      .Range(0.0, 3600.0);
  b.Bind("joint_stale_s", &ArmOptions::joint_stale_s, "s",
         "ddl/joint_state older than this is stale (commands refused, moves fault)")
      .Range(0.0, 60.0);
  b.Bind("check_rate_hz", &ArmOptions::check_rate_hz, "Hz",
         "state-machine step: timeouts, staleness, arrival")
      .Range(0.0, 100.0);
  b.Bind("status_rate_hz", &ArmOptions::status_rate_hz, "Hz",
         "dl/arm_status rate while moving (it is also sent on every change)")
      .Range(0.0, 100.0);
  b.Bind("focus_steps", &ArmOptions::focus_steps, "",
         "auto-focus: microscopic-imager frames in the stepped sweep (FIDO: 10)")
      .Range(3, 30);
  b.Bind("focus_span", &ArmOptions::focus_span, "m",
         "auto-focus: length of the sweep, centred where the target's estimated height puts "
         "best focus")
      .Range(0.0, 0.3);
  b.Bind("focus_max_extra_steps", &ArmOptions::focus_max_extra_steps, "",
         "auto-focus: steps added beyond the end of the sweep while the sharpest frame is "
         "the last one there")
      .Range(0, 20);
  b.Bind("focus_image_timeout_s", &ArmOptions::focus_image_timeout_s, "s",
         "auto-focus: a microscopic-imager frame not back within this (run clock) is a FAULT")
      .Range(0.0, 120.0);
  b.Bind("max_wheel_rate", &ArmOptions::max_wheel_rate, "rad/s",
         "a drive wheel turning faster than this means the rover is driving: the arm does not "
         "move out (JOINTS, PLACE, AUTOFOCUS refused, a running one faults); STOW and STOP run")
      .Range(0.0, 10.0);
  b.Bind("focus_min_contrast", &ArmOptions::focus_min_contrast, "",
         "auto-focus: best over worst focus measure below this is no focus signal (FAULT)")
      .Range(1.0, 100.0);
}

}  // namespace rover::dl::arm
