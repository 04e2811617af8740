#pragma once
/// @file
/// Options of the instrument-arm service (dl-arm), declared once through the parameter binder
/// (`DeclareParams<ArmOptions>(params, "arm.")`, keys below without the prefix).
///
/// Joint angles and their conventions are core/hwconfig's (arm_description.hpp): azimuth,
/// shoulder, elbow, wrist in radians; heights and distances of the instrument face in metres
/// in the rover frame (x forward, y left, z up).

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"

namespace rover::dl::arm {

struct ArmOptions {
  double speed = 0.25;           ///< [rad/s] rate limit of the fastest joint for ordinary moves
  double descent_speed = 0.01;   ///< [m/s] speed of the instrument face in the guarded descent
  double hover_height = 0.06;    ///< [m] a placement first goes this high above the target
  double overdrive = 0.03;       ///< [m] the guarded descent aims this far below the target
  double tolerance = 0.01;       ///< [rad] |measured - goal| per joint that counts as there
  double timeout_s = 120.0;      ///< [s] run-clock limit of a command when it gives 0
  double max_timeout_s = 600.0;  ///< [s] largest timeout_s a command may ask for
  double joint_stale_s = 0.5;    ///< [s] ddl/joint_state older than this is stale
  double check_rate_hz = 8.0;    ///< [Hz] state-machine step (timeouts, arrival)
  /// [rad/s] a drive wheel turning faster than this (ddl/joint_state) means the rover drives:
  /// JOINTS, PLACE and AUTOFOCUS are refused and a running one faults; STOW and STOP still run.
  double max_wheel_rate = 0.05;
  double status_rate_hz = 2.0;   ///< [Hz] dl/arm_status while moving (also on change)
  // Auto-focus (ARM_MODE_AUTOFOCUS; the imager's optics are core/hwconfig MicroscopeOptics).
  int focus_steps = 10;            ///< images in the sweep (FIDO: ten)
  double focus_span = 0.06;        ///< [m] sweep length, centred on the expected best focus
  int focus_max_extra_steps = 6;   ///< steps added beyond an end of the sweep that holds the peak
  double focus_image_timeout_s = 15.0;  ///< [s] run clock; a frame not back by then: FAULT
  double focus_min_contrast = 1.3; ///< best / worst focus measure below this: no focus signal

  /// speed in (0, 2] rad/s, descent_speed in (0, 0.1] m/s, hover_height in (0, 0.5] m,
  /// overdrive in (0, 0.2] m, tolerance in (0, 0.2] rad, 0 < timeout_s <= max_timeout_s,
  /// positive joint_stale_s, max_wheel_rate (0, 10] rad/s, check_rate_hz in (0, 100] Hz, status_rate_hz in
  /// (0, check_rate_hz], focus_steps [3, 30], focus_span (0, 0.3] m, focus_max_extra_steps
  /// [0, 20], focus_image_timeout_s (0, 120] s, focus_min_contrast [1, 100]. Messages start
  /// with the field.
  Status Validate() const;
  static void BindParams(ParamBinder<ArmOptions>& b);
};

}  // namespace rover::dl::arm
