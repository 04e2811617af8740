#pragma once
/// @file
/// When to take the next visual-odometry image pair: MER's cadence (Maimone, Cheng & Matthies
/// 2007), driven by the pose estimate (dl/pose).
///
/// MER took a VO pair at every drive step of at most ~0.6 m (and ~18 deg of turn) so that
/// consecutive images still overlapped enough to track features, and once more at the end of the
/// drive. Here, from each dl/pose sample (stamp t, odometer s [m], speed |v| [m/s], attitude R,
/// the estimator's `stationary` flag):
///   driving   while the estimator does not say stationary and s rises faster than
///             `moving_speed`, or |v| > `moving_speed`, or the attitude turns faster than
///             `moving_rate` (turns in place move no odometer); it ends once none of these has
///             held for `settle_s` (the rover has come to rest). The stationary flag keeps
///             estimator jitter at rest (attitude corrections) from counting as motion.
///   due       kFirst        no pair yet (the first reference, taken as soon as poses arrive);
///             kDistance     driving and s - s_last >= step_distance;
///             kRotation     driving and the attitude turned >= step_angle since the last pair;
///             kInterval     driving and t - t_last >= max_interval_s (run clock);
///             kEndOfDrive   at rest and s - s_last >= min_distance or the attitude turned
///                           >= min_angle since the last pair (one pair after each drive).
/// where (t_last, s_last, R_last) are the capture time, odometer and attitude of the last pair
/// (MarkCaptured). While parked with nothing new to measure, no pair is due.

#include <Eigen/Geometry>
#include <optional>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/base/time.hpp"

namespace rover::dl::vo {

struct CadenceOptions {
  double step_distance = 0.5;    ///< [m] (0, 0.9]; MER used <= ~0.6 m
  double step_angle = 0.3;       ///< [rad] (0, 0.35] (~17 deg)
  double max_interval_s = 20.0;  ///< [s] > 0, while driving (0.5 m at MER's 5 cm/s: 10 s)
  double moving_speed = 0.005;   ///< [m/s] > 0
  double moving_rate = 0.005;    ///< [rad/s] > 0
  double settle_s = 1.0;         ///< [s] >= 0 at rest before the end-of-drive pair
  double min_distance = 0.01;    ///< [m] >= 0 moved since the last pair for an end-of-drive pair
  double min_angle = 0.005;      ///< [rad] >= 0 turned since the last pair, same

  /// Checks the ranges above; the message names the field.
  Status Validate() const;
  /// dl-vo's top-level keys step_distance, step_angle_deg, max_interval_s, moving_speed,
  /// moving_rate_deg_s, settle_s, min_distance, min_angle_deg.
  static void BindParams(ParamBinder<CadenceOptions>& b);
};

class VoCadence {
 public:
  enum class Reason { kNone, kFirst, kDistance, kRotation, kInterval, kEndOfDrive };

  /// Precondition: options.Validate().ok().
  explicit VoCadence(const CadenceOptions& options);

  /// One pose sample (samples in time order; an older one is ignored).
  void OnPose(Time t, double odometer, double speed, const Eigen::Quaterniond& attitude,
              bool stationary = false);
  /// Whether a pair is due at run-clock time `now`, and why.
  Reason Due(Time now) const;
  /// A pair was captured at `t` with the rover at `odometer` and `attitude`.
  void MarkCaptured(Time t, double odometer, const Eigen::Quaterniond& attitude);
  /// Forgets everything (e.g. after a run-clock reset).
  void Reset();

  bool driving() const { return driving_; }
  bool has_capture() const { return last_capture_.has_value(); }

 private:
  struct State {
    Time t;
    double odometer = 0.0;
    Eigen::Quaterniond attitude = Eigen::Quaterniond::Identity();
  };
  CadenceOptions options_;
  std::optional<State> last_pose_;
  std::optional<State> last_capture_;
  Time last_motion_{0};  // last pose sample at which the rover moved
  bool driving_ = false;
};

const char* CadenceReasonName(VoCadence::Reason reason);

}  // namespace rover::dl::vo
