#pragma once
/// @file
/// Options of the mast pointing service (dl-mast), declared once through the parameter binder
/// (`DeclareParams<MastOptions>(params, "mast.")`, keys below without the prefix).
///
/// Angles follow ddl/joint_state and core/hwconfig: pan about the rover's +z through the pan
/// joint, + looks left; tilt about the head's -y, + looks up. Parameter keys ending in _deg are
/// degrees (deg/s for speed); the members are radians (rad/s).

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/base/units.hpp"

namespace rover::dl::mast {

struct MastOptions {
  double pan_min = -175.0 * kDegree;  ///< [rad] lowest pan goal accepted
  double pan_max = 175.0 * kDegree;   ///< [rad] highest pan goal accepted
  double tilt_min = -80.0 * kDegree;  ///< [rad] lowest tilt goal (looking down)
  double tilt_max = 80.0 * kDegree;   ///< [rad] highest tilt goal (looking up)
  double tolerance = 0.5 * kDegree;   ///< [rad] |measured - goal| per joint that counts as there
  double speed = 0.6;                 ///< [rad/s] rate limit of each mast motor for a move
  double timeout_s = 20.0;            ///< [s] run-clock limit of a move when the command gives 0
  double max_timeout_s = 120.0;       ///< [s] largest timeout_s a command may ask for
  double joint_stale_s = 0.5;         ///< [s] ddl/joint_state older than this is stale
  double pose_stale_s = 1.0;          ///< [s] dl/pose older than this cannot serve a look-at
  double min_look_distance = 0.3;     ///< [m] look-at points nearer the head are refused
  double check_rate_hz = 8.0;         ///< [Hz] state-machine step (timeouts, arrival)
  double status_rate_hz = 2.0;        ///< [Hz] dl/mast_status while moving (also on change)

  /// pan_min < pan_max within [-180, 180] deg, tilt_min < tilt_max within [-90, 90] deg,
  /// tolerance in (0, 10] deg, speed in (0, 5] rad/s, 0 < timeout_s <= max_timeout_s, positive
  /// staleness limits and rates, status_rate_hz <= check_rate_hz. Messages start with the field.
  Status Validate() const;
  static void BindParams(ParamBinder<MastOptions>& b);
};

}  // namespace rover::dl::mast
