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
      CheckRange("check_rate_hz", check_rate_hz, Bounds::OpenLow(0.0, 100.0), "Hz"));
  return CheckRange("status_rate_hz", status_rate_hz, Bounds::OpenLow(0.0, check_rate_hz), "Hz");
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
}

}  // namespace rover::dl::arm
