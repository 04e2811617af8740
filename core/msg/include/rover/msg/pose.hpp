#pragma once
/// @file
/// The pose messages as plain values (idl/rover_dl.idl): dl/pose (and dl/pose_odometry),
/// dl/relative_pose and dl/estimator_event, plus the two views of dl/pose that consumers keep:
/// PoseSample (for a pose history) and AttitudeSample (roll, pitch, heading).
/// rover/msg/pose_idl.hpp converts them.
///
/// Frames: site frame S (x north, y west, z up, fixed to the terrain); rover frame B (x forward,
/// y left, z up). Angles rad, lengths m, time on the run clock. Covariances are 6x6 over
/// (x, y, z [m], roll, pitch, yaw [rad]) for dl/pose and (dx, dy, dz [m], droll, dpitch, dyaw
/// [rad]) in the rover frame at t_from for dl/relative_pose.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <string>

#include "rover/base/time.hpp"

namespace rover::msg {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

/// rover_dl.idl MotionSource (same ordinals).
enum class MotionSource : std::int32_t {
  kWheelOdometry = 0,
  kVisualOdometry = 1,
  kSunSensor = 2,
  kAccelerometer = 3,
  kExternal = 4,
};
/// "wheel_odometry", "visual_odometry", "sun_sensor", "accelerometer", "external"; "unknown".
const char* MotionSourceName(MotionSource s);
bool IsKnownMotionSource(MotionSource s);

/// rover_dl.idl RelativePoseStatus (same ordinals). Only kConverged samples are measurements.
enum class RelativePoseStatus : std::int32_t {
  kConverged = 0,
  kTooFewFeatures = 1,
  kLimitsFailed = 2,
  kNotConverged = 3,
  kBadInput = 4,
};
/// "converged", "too_few_features", "limits_failed", "not_converged", "bad_input"; "unknown".
const char* RelativePoseStatusName(RelativePoseStatus s);

/// dl/pose: the rover frame in the site frame.
struct PoseEstimate {
  Time stamp;                                          ///< the filter's time of validity
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  ///< [m] site frame
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();  ///< rover in site, w >= 0
  Eigen::Vector3d rpy = Eigen::Vector3d::Zero();        ///< ZYX roll, pitch, yaw of `orientation`
  Matrix6d covariance = Matrix6d::Zero();               ///< x, y, z [m], roll, pitch, yaw [rad]
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();   ///< [m/s] rover frame, from odometry
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();  ///< [rad/s] estimated
  bool stationary = false;                  ///< the estimator considers the rover at rest
  std::uint32_t rejected_measurements = 0;  ///< since start, by Mahalanobis gating
  double odometer = 0.0;                    ///< [m] planar path length from wheel odometry
};

/// What a pose history keeps of a dl/pose sample.
struct PoseSample {
  Time stamp;  ///< time of validity on the run clock
  Eigen::Isometry3d site_from_rover = Eigen::Isometry3d::Identity();
  double odometer = 0.0;                               ///< [m] path length driven
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  ///< [m/s] rover frame
  bool stationary = false;                             ///< the estimator's rest flag
};

/// Rover attitude: ZYX roll, pitch, yaw of the rover frame in the site frame (see
/// rover/geometry/transforms.hpp).
struct AttitudeSample {
  Time stamp;
  double roll = 0.0;    ///< [rad]
  double pitch = 0.0;   ///< [rad]
  double yaw = 0.0;     ///< [rad] heading, counter-clockwise from site x (north)
  bool healthy = true;  ///< false: the source says not to use it
};

/// dl/relative_pose: the rover's motion between two run-clock times.
struct RelativePose {
  Time stamp;  ///< header stamp (t_to for visual odometry)
  MotionSource source = MotionSource::kVisualOdometry;
  Time t_from;
  Time t_to;
  Eigen::Isometry3d delta = Eigen::Isometry3d::Identity();  ///< rover(t_to) in rover(t_from)
  Matrix6d covariance = Matrix6d::Identity();
  RelativePoseStatus status = RelativePoseStatus::kConverged;
  std::uint32_t features = 0;  ///< features used (visual odometry)
};

/// dl/vo_command: a client asks dl-vo for visual-odometry pairs, or withdraws.
struct VoCommand {
  Time stamp;
  std::string client;    ///< who asks (its service name), 1..63 characters
  bool imaging = false;  ///< true: take pairs for this client; false: done
};

/// dl/estimator_event: one gated measurement.
struct EstimatorEvent {
  Time stamp;  ///< time of validity of the measurement (t_to for relative poses)
  MotionSource source = MotionSource::kExternal;
  bool accepted = false;
  double mahalanobis_sq = 0.0;  ///< NaN when rejected before gating (e.g. outside the window)
  double gate = 0.0;            ///< chi-square gate it was compared with
  std::string message;          ///< <= 127 characters on the wire
};

}  // namespace rover::msg
