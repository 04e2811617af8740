#pragma once
/// @file
/// apl-rendezvous parameters (keys `rendezvous.*`, RendezvousOptions::BindParams) and the
/// lander as the rover knows it (keys `lander.*`, core/hwconfig's LanderDescription).

#include <string>

#include "rover/base/status.hpp"

namespace rover {
template <class Options>
class ParamBinder;
}  // namespace rover

namespace rover::apl::rendezvous {

struct RendezvousOptions {
  // Command checks and budgets.
  double max_target_range = 150.0;   ///< [m] a-priori lander farther than this is refused
  double default_standoff = 1.0;     ///< [m] rover origin before the ramp base
  double min_standoff = 0.6;         ///< [m]
  double max_standoff = 3.0;         ///< [m]
  double default_time_budget_s = 3600.0;
  double pose_stale_s = 2.0;         ///< [s] a pose older than this is stale
  double camera_timeout_s = 30.0;    ///< [s] NAVCAM pair not answered
  double mast_timeout_s = 20.0;      ///< [s]
  double settle_s = 0.5;             ///< [s] wait after motion before imaging

  // Mid range (seed 004 phase 2).
  double reacquire_step = 5.0;       ///< [m] drive at most this far between sightings
  /// [m] farther than this from the estimate, a pair without the lander does not start the
  /// look-around: the rover drives a leg towards the estimate and looks again (the lander
  /// detector's reach; the long-range detector of seed 004's phase 1 is not built).
  double sight_range = 30.0;
  double approach_radius = 7.5;      ///< [m] from the deck centre: where close range starts
  double prior_gate = 8.0;           ///< [m] a fix this far from the estimate is not the lander
  int search_images = 7;             ///< pairs tried at a station before NOT_FOUND
  double search_pan_step_deg = 22.0; ///< [deg] look-around step at a station
  double autonav_tolerance = 0.6;    ///< [m] goal radius of mid-range legs
  /// How the legs between sightings drive: "autonav" (stereo hazard avoidance) or
  /// "goto_waypoint" (blind, pose-corrected arcs: for terrain known to be clear).
  std::string leg_mode = "autonav";

  // Close range (phase 3) and the placement.
  double circle_margin = 2.2;        ///< [m] orbit radius beyond the ramp feet
  double circle_step_deg = 50.0;     ///< [deg] per orbit leg
  double servo_run = 1.6;            ///< [m] straight run along the ramp axis before the base
  double pre_point_tolerance = 0.25; ///< [m] to the servo's start point
  double lateral_tolerance = 0.008;  ///< [m] placement accepted within these
  double along_tolerance = 0.012;    ///< [m]
  double heading_tolerance_deg = 1.0;
  double accept_lateral = 0.03;      ///< [m] after max_servo_steps, still accepted within these
  double accept_along = 0.04;        ///< [m]
  double accept_heading_deg = 2.5;
  int max_servo_steps = 5;
  int min_stripes = 4;               ///< fewer: no final servo (TOO_FEW_STRIPES)
  double hold_at_base_s = 2.0;       ///< [s] stopped at the ramp base before climbing
  double climb_max_tilt_deg = 26.0;  ///< [deg] tilt limit of the climb

  // Science-target approach (TARGET_SCIENCE, target_approach.hpp).
  double target_standoff = 1.05;       ///< [m] rover origin to the target, horizontal, at the end
  double target_min_standoff = 0.8;    ///< [m] smallest standoff a command may ask
  double target_max_standoff = 1.5;    ///< [m] largest
  double target_max_range = 30.0;      ///< [m] a designated target farther than this is refused
  double target_leg = 1.0;             ///< [m] drive at most this far between tracking pairs
  /// ... and at most this fraction of the distance to the target (the image grows by at most
  /// 1 / (1 - fraction) between pairs)
  double target_max_step_fraction = 0.35;
  /// [m] nearer than standoff + this, the last moves are directed (turn, straight) and short
  double target_final_approach = 2.0;
  double target_along_tolerance = 0.03;     ///< [m] done within this of the standoff ...
  double target_heading_tolerance_deg = 2.0;  ///< [deg] ... facing the target within this
  int target_max_steps = 25;           ///< tracking pairs after the designation before PLACEMENT
  /// legs: autonav (hazard avoidance), goto_waypoint (blind) or directed (turn + straight)
  std::string target_leg_mode = "autonav";
  int target_images_kept = 8;          ///< recent NAVCAM pairs a command may designate in
  /// point the mast at the target before each tracking pair (false: it stays where it is; the
  /// lost-target scenario's way to let the target leave the view)
  bool target_look = true;
  /// [s] a dl/arm_command (stow before the first leg, placement at the target) must end within
  double arm_timeout_s = 240.0;

  Status Validate() const;
  static void BindParams(ParamBinder<RendezvousOptions>& b);
};

}  // namespace rover::apl::rendezvous
