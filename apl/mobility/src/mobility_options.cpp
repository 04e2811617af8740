#include "rover/apl/mobility/mobility_options.hpp"

#include <string>

#include "rover/base/range_check.hpp"
#include "rover/base/units.hpp"

namespace rover::apl::mobility {
Status MobilityOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckPositive("max_goal_distance", max_goal_distance, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("min_tolerance", min_tolerance, Bounds::OpenLow(0.0, 10.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("time_budget_s", time_budget_s, "s"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("max_steps", max_steps, 1, 100000));
  ROVER_RETURN_IF_ERROR(
      CheckRange("max_tilt", max_tilt, Bounds::OpenLow(0.0, 80.0 * kDegree), "rad"));
  ROVER_RETURN_IF_ERROR(CheckRange("step_length", step_length, Bounds::OpenLow(0.0, 5.0), "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("waypoint_step_length", waypoint_step_length, Bounds::OpenLow(0.0, 50.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("waypoint_turn_threshold", waypoint_turn_threshold,
                                   Bounds::OpenLow(0.0, kPi), "rad"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("visodom_max_step", visodom_max_step, Bounds::OpenLow(0.0, 5.0), "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("visodom_max_turn", visodom_max_turn, Bounds::OpenLow(0.0, kPi), "rad"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("guard_segment_length", guard_segment_length, Bounds::OpenLow(0.0, 5.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("guard_min_goodness", guard_min_goodness, 0, 255));
  ROVER_RETURN_IF_ERROR(CheckIntRange("progress_steps", progress_steps, 1, 10000));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("min_progress", min_progress, "m"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("limit_cycle_turns", limit_cycle_turns, 0, 100));
  ROVER_RETURN_IF_ERROR(CheckRange("limit_cycle_min_bearing", limit_cycle_min_bearing,
                                   Bounds::Closed(0.0, kPi), "rad"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("limit_cycle_turn", limit_cycle_turn, Bounds::OpenLow(0.0, kPi), "rad"));
  ROVER_RETURN_IF_ERROR(CheckIntRange("max_visodom_failures", max_visodom_failures, 0, 10000));
  ROVER_RETURN_IF_ERROR(CheckPositive("visodom_timeout_s", visodom_timeout_s, "s"));
  ROVER_RETURN_IF_ERROR(CheckPositive("image_timeout_s", image_timeout_s, "s"));
  ROVER_RETURN_IF_ERROR(CheckRange("image_resend_s", image_resend_s, 0.0, 1e6));
  ROVER_RETURN_IF_ERROR(CheckIntRange("max_image_resends", max_image_resends, 0, 100));
  ROVER_RETURN_IF_ERROR(CheckIntRange("image_width", image_width, 0, 4096));
  ROVER_RETURN_IF_ERROR(CheckPositive("pose_stale_s", pose_stale_s, "s"));
  ROVER_RETURN_IF_ERROR(CheckPositive("pose_jump", pose_jump, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("pose_jump_angle", pose_jump_angle, Bounds::OpenLow(0.0, kPi), "rad"));
  ROVER_RETURN_IF_ERROR(CheckRange("drive_speed", drive_speed, 0.0, 1.0, "m/s"));
  ROVER_RETURN_IF_ERROR(CheckPositive("nominal_speed", nominal_speed, "m/s"));
  ROVER_RETURN_IF_ERROR(CheckPositive("nominal_turn_rate", nominal_turn_rate, "rad/s"));
  ROVER_RETURN_IF_ERROR(CheckRange("drive_timeout_factor", drive_timeout_factor, 1.0, 100.0));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("drive_timeout_margin_s", drive_timeout_margin_s, "s"));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("drive_status_timeout_s", drive_status_timeout_s, "s"));
  ROVER_RETURN_IF_ERROR(CheckRange("keepout_margin", keepout_margin, 0.0, 10.0, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("site_longitude_east", site_longitude_east, -2.0 * kPi, 2.0 * kPi, "rad"));
  ROVER_RETURN_IF_ERROR(CheckFinite("run_clock_epoch_unix_s", run_clock_epoch_unix_s));
  ROVER_RETURN_IF_ERROR(CheckPositive("status_period_s", status_period_s, "s"));
  return Status::Ok();
}

void MobilityOptions::BindParams(ParamBinder<MobilityOptions>& b) {
  using O = MobilityOptions;
  b.Bind("software_enable", &O::software_enable,
         "ACM: false refuses every motion command (MER's software enable)");
  b.Bind("max_goal_distance_m", &O::max_goal_distance, "m",
         "goals farther from the rover are rejected as out of the map (stack 200)")
      .Min(0.0);
  b.Bind("min_tolerance_m", &O::min_tolerance, "m",
         "goal radius used when the command's is smaller (stack 0.1)");
  b.Bind("time_budget_s", &O::time_budget_s, "s",
         "default command time-out (WAYPT_TIMEOUT); 0 = none")
      .Min(0.0);
  b.Bind("max_steps", &O::max_steps, "", "autonav steps per command (stack 500)").Min(1);
  b.BindDegrees("max_tilt_deg", &O::max_tilt, "TILT above this rover tilt (MER nominal 30)");
  b.Bind("step_length_m", &O::step_length, "m", "autonav arc length per step (stack 0.5)");
  b.Bind("waypoint_step_length_m", &O::waypoint_step_length, "m",
         "blind go-to-waypoint arc length per step (stack 1.0)");
  b.BindDegrees("waypoint_turn_threshold_deg", &O::waypoint_turn_threshold,
                "blind go-to-waypoint turns in place first beyond this bearing (stack 30)");
  b.Bind("visodom_max_step_m", &O::visodom_max_step, "m",
         "VisOdom steps are split to at most this (MER ~0.6)");
  b.BindDegrees("visodom_max_turn_deg", &O::visodom_max_turn,
                "VisOdom turns are split to at most this (MER 15)");
  b.Bind("guard_segment_length_m", &O::guard_segment_length, "m",
         "guarded primitives are re-imaged every this far (stack 1.0)");
  b.Bind("guard_min_goodness", &O::guard_min_goodness, "",
         "a guarded path over a cell below this goodness is vetoed (MER min-allowed 10)")
      .Range(0, 255);
  b.Bind("drive_while_thinking", &O::drive_while_thinking,
         "image and assess the next step while driving (false = MER's stop-and-go)");
  b.Bind("progress_steps", &O::progress_steps, "", "NOPROGRESS window in steps (stack 10)").Min(1);
  b.Bind("min_progress_m", &O::min_progress, "m",
         "the distance to the goal must shrink this much per window (stack 0.5)")
      .Min(0.0);
  b.Bind("limit_cycle_turns", &O::limit_cycle_turns, "",
         "arc voting: turns in place after a failed NOPROGRESS window before it ends the "
         "command (stack 2; 0 = end at once)")
      .Range(0, 100);
  b.BindDegrees("limit_cycle_min_bearing_deg", &O::limit_cycle_min_bearing,
                "a limit-cycle turn faces the goal when it is at least this far off ahead "
                "(stack 30)")
      .Range(0.0, 180.0);
  b.BindDegrees("limit_cycle_turn_deg", &O::limit_cycle_turn,
                "otherwise it turns this much toward the better forward arcs (MER 90)")
      .Range(1.0, 180.0);
  b.Bind("max_visodom_failures", &O::max_visodom_failures, "",
         "VISODOM after this many failed VO steps in one command (stack 3)")
      .Min(0);
  b.Bind("visodom_timeout_s", &O::visodom_timeout_s, "s",
         "a VO result not arriving in this time counts as failed (stack 30)");
  b.Bind("image_timeout_s", &O::image_timeout_s, "s",
         "IMG when a requested range image has not arrived in this time (stack 10)");
  b.Bind("image_resend_s", &O::image_resend_s, "s",
         "a range request unanswered this long is sent again (a restarted dl-stereo lost it); "
         "0 = never")
      .Range(0.0, 1e6);
  b.Bind("max_image_resends", &O::max_image_resends, "", "times one range request is re-sent")
      .Range(0, 100);
  b.Bind("image_width", &O::image_width, "px", "range image width asked of stereo (MER 256)")
      .Range(0, 4096);
  b.Bind("pose_stale_s", &O::pose_stale_s, "s", "SAPP when the newest dl/pose is older (stack 1)");
  b.Bind("pose_jump_m", &O::pose_jump, "m",
         "SAPP when consecutive dl/pose samples differ by more (stack 0.5)");
  b.BindDegrees("pose_jump_angle_deg", &O::pose_jump_angle,
                "SAPP when consecutive dl/pose samples turn by more (stack 20)");
  b.Bind("drive_speed_mps", &O::drive_speed, "m/s",
         "speed asked of locomotion; 0 = its default (0.05, MER top speed)");
  b.Bind("nominal_speed_mps", &O::nominal_speed, "m/s", "speed the drive watchdog plans with");
  b.Bind("nominal_turn_rate_radps", &O::nominal_turn_rate, "rad/s",
         "turn rate the drive watchdog plans with");
  b.Bind("drive_timeout_factor", &O::drive_timeout_factor, "",
         "DRIVE_TIMEOUT after factor * planned time + margin");
  b.Bind("drive_timeout_margin_s", &O::drive_timeout_margin_s, "s", "see drive_timeout_factor");
  b.Bind("drive_status_timeout_s", &O::drive_status_timeout_s, "s",
         "MOT when the running drive reports no dl/drive_status this long (0 = off)")
      .Min(0.0);
  b.Bind("keepout_margin_m", &O::keepout_margin, "m",
         "the rover centre keeps this far from keep-out zones (about half its width)");
  b.BindDegrees("site_longitude_east_deg", &O::site_longitude_east,
                "Mars east longitude of the site, for local mean solar time (TOD)");
  b.Bind("run_clock_epoch_unix_s", &O::run_clock_epoch_unix_s, "s",
         "UTC (Unix seconds) of run-clock 0, for local mean solar time (default J2000 noon)");
  b.Bind("status_period_s", &O::status_period_s, "s",
         "a running command reports at least this often");
  b.Bind("id_base", &O::id_base, "", "first drive / range / mast request id").Range(1, 4.0e9);
}

}  // namespace rover::apl::mobility
