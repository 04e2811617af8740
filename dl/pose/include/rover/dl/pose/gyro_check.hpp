#pragma once
/// @file
/// GyroCheck: does the gyro's yaw rate agree with the wheels' (issue 12: a gyro bias no filter
/// state can follow must be caught before the heading it integrates steers the rover into a
/// rock). DDS-free and clock-free: every call passes its sample's time.
///
/// The yaw rate about the rover z axis from two independent sources is compared over a
/// sliding window of window_s (made of bins of bin_s):
///   gyro      omega_g = sum (w_z - b_z) dt / sum dt   (bias-corrected by the filter's estimate)
///   odometry  omega_o = sum dyaw / sum (t_to - t_from)  (dl_locomotion's WheelOdometry)
/// A window is judged only when both sources cover at least min_coverage of it and the wheels
/// turn the rover slower than max_odometry_rate (faster turns can slip enough to make the
/// wheels wrong). The check fails, and stays failed (latched), when in a judged window
///   |omega_g - omega_o| > max_disagreement + rate_tolerance |omega_o|,
/// the second term allowing turning wheels their slip (a share of the rate they turn the rover
/// by). At rest the gyro must read the planet's rotation (< 1e-4 rad/s on Mars) and noise;
/// driving straight, wheel slip turns the rover by far less than max_disagreement. Autonav
/// drives arcs most of the time (0.03 rad/s at 0.1 m/s on a 3 m radius), so gentle arcs are
/// judged: with every turn excluded (max_odometry_rate 0.02 rad/s) a bias that started during an
/// arc was caught only when the rover next stood still (6.3 s in the safety campaign). Point
/// turns and tight arcs on rocks are not: wheels turning the rover at 0.067 rad/s over rocks
/// read nearly three times the gyro's rate (a VL-1 run, 2026-12-06).
///
/// A failure must be confirmed: the window that ends confirm_s earlier (disjoint from it with
/// the default confirm_s = window_s) must have been judged and failed with the same sign. A
/// bias persists; a wheel that skids off a rock yaws the rover once, and its extra yaw falls
/// into one window, or splits between two (an autonav VL-2 run on rocks, 2026-12-06, read
/// 0.029 rad/s of disagreement in one window and declared the pose unknown).
///
/// A bias b that starts at t0 fails the first judged window whose share of biased time f
/// satisfies f b > max_disagreement + rate_tolerance |omega_o|, and is confirmed confirm_s later:
/// with the defaults (window 1 s in 0.25 s bins, 0.02 rad/s, 0.5, confirm 1 s) a 0.05 rad/s bias
/// is caught 1.4 to 1.65 s after it starts on straight drives and at rest, 1.75 to 2 s on a
/// 0.03 rad/s arc (confirm_s 0: one window, 0.4 to 0.65 s).

#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <utility>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/base/time.hpp"

namespace rover::dl::pose {

/// Keys gyro_check.* of dl-pose.
struct GyroCheckOptions {
  bool enabled = true;
  double window_s = 1.0;             ///< [s] judged window (a whole number of bins)
  double bin_s = 0.25;               ///< [s] bin length; windows slide by one bin
  double max_disagreement = 0.02;    ///< [rad/s] |gyro - odometry| yaw rate that fails the check
  double max_odometry_rate = 0.04;   ///< [rad/s] windows turning faster are not judged
  double rate_tolerance = 0.5;       ///< share of the odometry yaw rate added to the tolerance
  double min_coverage = 0.8;         ///< share of the window each source must cover
  double confirm_s = 1.0;            ///< [s] the window this much earlier must fail too (0: off)

  /// window_s and confirm_s whole numbers of bin_s (window >= 1 bin, confirm >= 0), every other
  /// value positive, min_coverage in (0, 1].
  Status Validate() const;
  static void BindParams(ParamBinder<GyroCheckOptions>& b);
};

/// One failed window.
struct GyroCheckFailure {
  Time window_end;
  double gyro_rate = 0.0;      ///< [rad/s] bias-corrected gyro yaw rate over the window
  double odometry_rate = 0.0;  ///< [rad/s] wheel-odometry yaw rate over the window
  std::string reason;          ///< "ddl/imu gyro z disagrees with wheel odometry: ..."
};

class GyroCheck {
 public:
  /// Errors: options.Validate().
  static Result<GyroCheck> Create(const GyroCheckOptions& options);

  /// A gyro sample: bias-corrected yaw rate `rate_z` [rad/s] held over (t - dt, t].
  void AddGyro(Time t, double dt, double rate_z);
  /// A wheel-odometry increment turning the rover by `dyaw` [rad] over (t_from, t_to].
  void AddOdometry(Time t_from, Time t_to, double dyaw);
  /// Forgets every bin (not a latched failure): after a gap or a filter restart.
  void Reset();

  /// The first failed window; nullopt while the check holds (or is disabled).
  const std::optional<GyroCheckFailure>& failure() const { return failure_; }
  /// Windows judged so far, and the largest |disagreement| among them [rad/s].
  std::uint64_t judged() const { return judged_; }
  double worst_disagreement() const { return worst_; }

 private:
  struct Bin {
    std::int64_t index = 0;
    double gyro_angle = 0.0, gyro_time = 0.0;  // [rad], [s]
    double odo_angle = 0.0, odo_time = 0.0;
  };
  explicit GyroCheck(const GyroCheckOptions& options);
  /// The bin of `t`, made when new; null for a time older than every bin still needed.
  Bin* BinAt(Time t);
  /// Judges every window that ends at a bin both sources have passed.
  void Judge();

  GyroCheckOptions options_;
  int bins_per_window_ = 4;
  int confirm_bins_ = 4;
  std::deque<std::pair<std::int64_t, int>> failed_;  // (window end bin, sign) of recent failures
  std::deque<Bin> bins_;  // consecutive indices, oldest first
  std::int64_t gyro_bin_ = INT64_MIN, odo_bin_ = INT64_MIN;  // bin of each source's latest time
  std::int64_t judged_through_ = INT64_MIN;  // last bin that ended a judged window
  std::uint64_t judged_ = 0;
  double worst_ = 0.0;
  std::optional<GyroCheckFailure> failure_;
};

}  // namespace rover::dl::pose
