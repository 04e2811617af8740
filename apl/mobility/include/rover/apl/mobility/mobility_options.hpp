#pragma once
/// @file
/// MobilityOptions: every parameter of the mobility manager, declared once (BindParams, keys
/// under the service's "mobility." prefix) and checked by Validate() (messages start with the
/// member's name so ReadParams reports them against the key). Defaults: MER's value where the
/// seeds give one (noted "MER"), otherwise this stack's choice (noted "stack"); the table is in
/// docs/services/apl-mobility.md.
///
/// Units: metres, seconds, radians in members (degrees in keys ending in `_deg`).

#include <cstdint>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/base/units.hpp"

namespace rover::apl::mobility {

struct MobilityOptions {
  // ---- command limits ----------------------------------------------------------------------
  bool software_enable = true;  ///< ACM: false refuses every motion command (MER's enable)
  double max_goal_distance =
      200.0;                   ///< [m] goals farther from the rover are out of the map (stack)
  double min_tolerance = 0.1;  ///< [m] goal radius used when the command's is smaller (stack)
  double time_budget_s = 0.0;  ///< [s] default command time-out; 0 = none (MER: per command)
  int max_steps = 500;         ///< autonav steps per command (stack)
  double max_tilt = 30.0 * kDegree;  ///< [rad], rover tilt from dl/pose (MER's nominal limit)
  // ---- stepping ----------------------------------------------------------------------------
  double step_length = 0.5;           ///< [m] autonav arc per step (stack; seeds give no value)
  double waypoint_step_length = 1.0;  ///< [m] blind go-to-waypoint arc per step (stack)
  double waypoint_turn_threshold =
      30.0 * kDegree;                        ///< [rad] blind: turn in place first beyond 30 deg
  double visodom_max_step = 0.6;             ///< [m] VisOdom steps no longer than this (MER ~60 cm)
  double visodom_max_turn = 15.0 * kDegree;  ///< [rad] VisOdom turns at most this (MER)
  double guard_segment_length = 1.0;         ///< [m] guarded primitives are imaged every this far
  int guard_min_goodness = 10;               ///< a guarded path over a cell below this is vetoed
                                             ///< (MER's min-allowed goodness)
  bool drive_while_thinking = true;          ///< image and assess the next step while driving
  // ---- limit cycle, VisOdom ----------------------------------------------------------------
  int progress_steps = 10;       ///< NOPROGRESS window (steps) (stack)
  double min_progress = 0.5;     ///< [m] the distance to the goal must shrink this much per window
  /// Arc-voting modes: limit-cycle turns in place (seed 000's second off-nominal behaviour)
  /// before a failed window ends the command NOPROGRESS; 0 = end it at once (MER's other
  /// choice). A turn faces the goal, or when the goal is already within
  /// limit_cycle_min_bearing of ahead turns limit_cycle_turn toward the better forward arcs.
  int limit_cycle_turns = 2;                        ///< (stack)
  double limit_cycle_min_bearing = 30.0 * kDegree;  ///< [rad] (stack)
  double limit_cycle_turn = 90.0 * kDegree;         ///< [rad] (MER's point-turn-amount)
  int max_visodom_failures = 3;  ///< VISODOM after this many failed VO steps in one command
  double visodom_timeout_s = 30.0;  ///< [s] a VO result not arriving in time counts as failed
  // ---- inputs ------------------------------------------------------------------------------
  double image_timeout_s = 10.0;  ///< [s] IMG when a range image has not arrived in this time
  /// [s] a range request unanswered this long is sent again (a restarted dl-stereo lost it),
  /// up to max_image_resends times, while image_timeout_s (from the first) has not run out;
  /// 0 = never. An answer to any of the sends is taken.
  double image_resend_s = 4.0;
  int max_image_resends = 2;
  int image_width = 256;          ///< [px] processing width asked of stereo (MER 256)
  double pose_stale_s = 1.0;      ///< [s] SAPP when the newest pose is older than this
  double pose_jump = 0.5;         ///< [m] SAPP when consecutive poses differ by more
  double pose_jump_angle = 20.0 * kDegree;  ///< [rad] ... or turn by more than this
  // ---- drive watchdog ----------------------------------------------------------------------
  double drive_speed = 0.0;           ///< [m/s] asked of locomotion; 0 = its default (0.05 m/s)
  double nominal_speed = 0.05;        ///< [m/s] for the watchdog (MER top speed)
  double nominal_turn_rate = 0.05;    ///< [rad/s] for the watchdog
  double drive_timeout_factor = 3.0;  ///< DRIVE_TIMEOUT after factor * planned time + margin
  double drive_timeout_margin_s = 30.0;
  double drive_status_timeout_s =
      2.0;  ///< [s] MOT when the running drive reports no dl/drive_status this long; 0 = off
            ///< (stack; locomotion reports at 8 Hz)
  // ---- keep-out, time of day -----------------------------------------------------------------
  double keepout_margin = 0.6;       ///< [m] the rover centre keeps this far from keep-out zones
                                     ///< (about half the rover's width)
  double site_longitude_east = 0.0;  ///< [rad] Mars east longitude of the site (TOD)
  double run_clock_epoch_unix_s = 946728000.0;  ///< [s] UTC (Unix) of run-clock 0 (J2000 noon)
  // ---- output ------------------------------------------------------------------------------
  double status_period_s = 1.0;         ///< [s] a running status at least this often
  std::uint32_t id_base = 0x4d000000u;  ///< first drive / range / mast request id ('M' << 24)

  Status Validate() const;
  static void BindParams(ParamBinder<MobilityOptions>& b);
};

}  // namespace rover::apl::mobility
