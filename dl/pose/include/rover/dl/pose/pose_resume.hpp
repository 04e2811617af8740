#pragma once
/// @file
/// Restarting the pose estimator after a crash or kill -9 without pretending nothing happened.
///
/// A supervised dl-pose keeps a checkpoint (rover/base/checkpoint.hpp, text `key value` fields)
/// of each filter's published estimate. The fields of one filter, under a prefix ("" for the
/// main filter, "odometry_only." for the IMU + wheel-odometry baseline):
///   stamp_ns          time of validity on the run clock [ns]
///   position          x y z [m], site frame
///   attitude_wxyz     unit quaternion, rover in site
///   sigma_xyz_rpy     1-sigma of x, y, z [m] and roll, pitch, yaw [rad] (covariance diagonal)
///   gyro_bias         [rad/s], rover frame
///   odometer          [m] planar path length
/// Doubles are written with 17 significant digits, so they read back exactly.
///
/// On the first usable IMU sample at run time t after a restart, with gap = t - stamp:
///   * gap < -kClockResetS: the run clock went back (a new run, not a restart): start afresh;
///   * gap > max_age_s: the pose is unknown (nothing may drive on it);
///   * else resume, the uncertainty inflated for what may have happened unseen:
///       sigma_p' = hypot(sigma_p, max_speed * gap)  per axis,
///       sigma_yaw' = hypot(sigma_yaw, max_yaw_rate * gap),
///     roll, pitch and their sigmas as saved (the accelerometer re-levels them at rest).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <map>
#include <optional>
#include <string>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/dl/pose/pose_ekf.hpp"

namespace rover::dl::pose {

/// Keys resume.* of dl-pose.
struct PoseResumeOptions {
  bool enabled = true;                  ///< keep a checkpoint in a supervised set, resume from it
  double checkpoint_period_s = 1.0;     ///< [s] run time between checkpoints
  double max_age_s = 60.0;              ///< [s] older checkpoints are not resumed
  double max_speed = 0.1;               ///< [m/s] assumed while down (position inflation)
  double max_yaw_rate = 0.034906585039886591;  ///< [rad/s] assumed while down (2 deg/s)

  static void BindParams(ParamBinder<PoseResumeOptions>& b);
};

/// One filter's state as checkpointed.
struct SavedFilter {
  Time stamp;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Quaterniond attitude = Eigen::Quaterniond::Identity();
  Eigen::Vector3d position_sigma = Eigen::Vector3d::Zero();  ///< [m]
  Eigen::Vector3d rpy_sigma = Eigen::Vector3d::Zero();       ///< [rad]
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();       ///< [rad/s]
  double odometer = 0.0;                                     ///< [m]
};

/// Both filters' checkpoint.
struct PoseCheckpoint {
  SavedFilter main;
  std::optional<SavedFilter> odometry_only;  ///< absent: it resumes from `main`
};

/// The filter state of `estimate`.
SavedFilter SavedFilterOf(const PoseEstimate& estimate);
/// The checkpoint fields of `checkpoint` (see the file comment).
std::map<std::string, std::string> CheckpointFields(const PoseCheckpoint& checkpoint);
/// Reads fields written by CheckpointFields. Errors: a missing or unreadable main-filter field
/// or a non-unit quaternion (names the key and value); an incomplete odometry-only part is
/// dropped (it then resumes from the main filter).
Result<PoseCheckpoint> PoseCheckpointFromFields(const std::map<std::string, std::string>& fields);

/// The initial state resuming `saved` at `t` (inflated as in the file comment; the gyro bias
/// sigma is `gyro_bias_sigma`, the start's: the bias may have wandered).
EkfInitialState ResumedInitialState(const SavedFilter& saved, Time t,
                                    const PoseResumeOptions& options, double gyro_bias_sigma);

}  // namespace rover::dl::pose
