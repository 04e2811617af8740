#include "rover/apl/rendezvous/rendezvous_options.hpp"

#include "rover/base/param_binder.hpp"
#include "rover/base/range_check.hpp"

namespace rover::apl::rendezvous {

Status RendezvousOptions::Validate() const {
  const std::string p = "rendezvous.";
  ROVER_RETURN_IF_ERROR(CheckRange(p + "max_target_range", max_target_range, 10.0, 1000.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "min_standoff", min_standoff, 0.3, 5.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "max_standoff", max_standoff, min_standoff, 10.0, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange(p + "default_standoff", default_standoff, min_standoff, max_standoff, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange(p + "default_time_budget_s", default_time_budget_s, 10.0, 1e6, "s"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "pose_stale_s", pose_stale_s, 0.1, 60.0, "s"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "camera_timeout_s", camera_timeout_s, 1.0, 600.0, "s"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "mast_timeout_s", mast_timeout_s, 1.0, 600.0, "s"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "settle_s", settle_s, 0.0, 10.0, "s"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "reacquire_step", reacquire_step, 1.0, 30.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "sight_range", sight_range, 5.0, 200.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "approach_radius", approach_radius, 5.0, 20.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "prior_gate", prior_gate, 0.5, 100.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckIntRange(p + "search_images", search_images, 1, 50));
  ROVER_RETURN_IF_ERROR(
      CheckRange(p + "search_pan_step_deg", search_pan_step_deg, 5.0, 45.0, "deg"));
  ROVER_RETURN_IF_ERROR(
      CheckRange(p + "autonav_tolerance", autonav_tolerance, 0.1, 3.0, "m"));
  if (leg_mode != "autonav" && leg_mode != "goto_waypoint") {
    return InvalidArgument(p + "leg_mode: '" + leg_mode + "' is not autonav or goto_waypoint");
  }
  ROVER_RETURN_IF_ERROR(CheckRange(p + "circle_margin", circle_margin, 1.0, 10.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "circle_step_deg", circle_step_deg, 10.0, 120.0, "deg"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "servo_run", servo_run, 0.5, 5.0, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange(p + "pre_point_tolerance", pre_point_tolerance, 0.05, 2.0, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange(p + "lateral_tolerance", lateral_tolerance, 0.001, 0.5, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "along_tolerance", along_tolerance, 0.001, 0.5, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange(p + "heading_tolerance_deg", heading_tolerance_deg, 0.05, 20.0, "deg"));
  ROVER_RETURN_IF_ERROR(
      CheckRange(p + "accept_lateral", accept_lateral, lateral_tolerance, 1.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "accept_along", accept_along, along_tolerance, 1.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "accept_heading_deg", accept_heading_deg,
                                   heading_tolerance_deg, 30.0, "deg"));
  ROVER_RETURN_IF_ERROR(CheckIntRange(p + "max_servo_steps", max_servo_steps, 1, 20));
  ROVER_RETURN_IF_ERROR(CheckIntRange(p + "min_stripes", min_stripes, 2, 6));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "hold_at_base_s", hold_at_base_s, 0.0, 60.0, "s"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "climb_max_tilt_deg", climb_max_tilt_deg, 5.0, 45.0, "deg"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "target_min_standoff", target_min_standoff, 0.5, 3.0, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange(p + "target_max_standoff", target_max_standoff, target_min_standoff, 5.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "target_standoff", target_standoff, target_min_standoff,
                                   target_max_standoff, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "target_max_range", target_max_range, 2.0, 100.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "target_leg", target_leg, 0.2, 5.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "target_max_step_fraction", target_max_step_fraction, 0.05, 0.9));
  ROVER_RETURN_IF_ERROR(
      CheckRange(p + "target_final_approach", target_final_approach, 0.1, 5.0, "m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange(p + "target_along_tolerance", target_along_tolerance, 0.005, 0.5, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange(p + "target_heading_tolerance_deg",
                                   target_heading_tolerance_deg, 0.1, 20.0, "deg"));
  ROVER_RETURN_IF_ERROR(CheckIntRange(p + "target_max_steps", target_max_steps, 1, 200));
  if (target_leg_mode != "autonav" && target_leg_mode != "goto_waypoint" &&
      target_leg_mode != "directed") {
    return InvalidArgument(p + "target_leg_mode: '" + target_leg_mode +
                           "' is not autonav, goto_waypoint or directed");
  }
  ROVER_RETURN_IF_ERROR(CheckRange(p + "arm_timeout_s", arm_timeout_s, 1.0, 3600.0, "s"));
  return CheckIntRange(p + "target_images_kept", target_images_kept, 1, 64);
}

void RendezvousOptions::BindParams(ParamBinder<RendezvousOptions>& b) {
  using O = RendezvousOptions;
  b.Bind("max_target_range", &O::max_target_range, "m", "a-priori lander farther away is refused");
  b.Bind("default_standoff", &O::default_standoff, "m",
         "rover origin this far before the ramp base when the command says 0");
  b.Bind("min_standoff", &O::min_standoff, "m", "smallest standoff a command may ask");
  b.Bind("max_standoff", &O::max_standoff, "m", "largest standoff a command may ask");
  b.Bind("default_time_budget_s", &O::default_time_budget_s, "s",
         "time budget when the command says 0");
  b.Bind("pose_stale_s", &O::pose_stale_s, "s", "dl/pose older than this is stale");
  b.Bind("camera_timeout_s", &O::camera_timeout_s, "s", "NAVCAM pair not answered: CAMERA");
  b.Bind("mast_timeout_s", &O::mast_timeout_s, "s", "mast not at its goal: MAST");
  b.Bind("settle_s", &O::settle_s, "s", "wait after motion before imaging");
  b.Bind("reacquire_step", &O::reacquire_step, "m", "mid range: drive at most this far between sightings");
  b.Bind("sight_range", &O::sight_range, "m",
         "beyond it a missed lander means a leg towards the estimate, not a look-around");
  b.Bind("approach_radius", &O::approach_radius, "m", "close range starts this far from the deck centre");
  b.Bind("prior_gate", &O::prior_gate, "m", "a fix farther than this from the estimate is rejected");
  b.Bind("search_images", &O::search_images, "", "pairs tried at one station before NOT_FOUND");
  b.Bind("search_pan_step_deg", &O::search_pan_step_deg, "deg", "look-around step");
  b.Bind("autonav_tolerance", &O::autonav_tolerance, "m", "goal radius of the autonav legs");
  b.Bind("leg_mode", &O::leg_mode,
         "legs between sightings: autonav (hazard avoidance) or goto_waypoint (blind)");
  b.Bind("circle_margin", &O::circle_margin, "m", "orbit radius beyond the ramp feet");
  b.Bind("circle_step_deg", &O::circle_step_deg, "deg", "orbit leg");
  b.Bind("servo_run", &O::servo_run, "m", "straight run along the ramp axis before the base");
  b.Bind("pre_point_tolerance", &O::pre_point_tolerance, "m", "to the servo's start point");
  b.Bind("lateral_tolerance", &O::lateral_tolerance, "m", "placement goal, across the ramp axis");
  b.Bind("along_tolerance", &O::along_tolerance, "m", "placement goal, along the ramp axis");
  b.Bind("heading_tolerance_deg", &O::heading_tolerance_deg, "deg", "placement goal, heading");
  b.Bind("accept_lateral", &O::accept_lateral, "m", "accepted after max_servo_steps");
  b.Bind("accept_along", &O::accept_along, "m", "accepted after max_servo_steps");
  b.Bind("accept_heading_deg", &O::accept_heading_deg, "deg", "accepted after max_servo_steps");
  b.Bind("max_servo_steps", &O::max_servo_steps, "", "measure-and-correct steps at the base");
  b.Bind("min_stripes", &O::min_stripes, "", "stripes the final servo needs");
  b.Bind("hold_at_base_s", &O::hold_at_base_s, "s", "stand at the ramp base before climbing");
  b.Bind("climb_max_tilt_deg", &O::climb_max_tilt_deg, "deg", "tilt limit while climbing");
  b.Bind("target_standoff", &O::target_standoff, "m",
         "science target: rover origin this far from it at the end when the command says 0");
  b.Bind("target_min_standoff", &O::target_min_standoff, "m", "smallest science standoff asked");
  b.Bind("target_max_standoff", &O::target_max_standoff, "m", "largest science standoff asked");
  b.Bind("target_max_range", &O::target_max_range, "m", "a designated target farther is refused");
  b.Bind("target_leg", &O::target_leg, "m", "science target: drive at most this far between pairs");
  b.Bind("target_max_step_fraction", &O::target_max_step_fraction, "",
         "science target: no step longer than this fraction of the distance to it");
  b.Bind("target_final_approach", &O::target_final_approach, "m",
         "nearer than standoff + this: directed turn and straight");
  b.Bind("target_along_tolerance", &O::target_along_tolerance, "m", "done within this of the standoff");
  b.Bind("target_heading_tolerance_deg", &O::target_heading_tolerance_deg, "deg",
         "done facing the target within this");
  b.Bind("target_max_steps", &O::target_max_steps, "", "tracking pairs before PLACEMENT");
  b.Bind("target_leg_mode", &O::target_leg_mode,
         "science-target legs: autonav, goto_waypoint (blind) or directed (turn + straight)");
  b.Bind("target_images_kept", &O::target_images_kept, "",
         "recent NAVCAM pairs (any requester's) a command may designate in");
  b.Bind("target_look", &O::target_look,
         "point the mast at the science target before each tracking pair (false: leave it)");
  b.Bind("arm_timeout_s", &O::arm_timeout_s, "s",
         "a dl/arm_command (stow before driving, placement on the target) must end within this");
}

}  // namespace rover::apl::rendezvous
