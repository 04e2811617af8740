#pragma once
/// @file
/// How the pose filter starts: the start pose from parameters (the site frame's origin is the
/// rover's start, so x = y = 0 by default), roll and pitch levelled from the accelerometer at
/// rest, and the initial gyro bias from the gyro over the same stretch.
///
/// Leveller takes the IMU samples (time-stamped, rover frame, bias included) that arrive before
/// the filter runs. A sample is plausible when | |f| - g | <= ekf.accel_magnitude_tolerance and
/// still when it is also |w| <= ekf.stationary_gyro_threshold. Once start.level_samples
/// consecutive still samples were seen, the filter starts from their mean specific force and
/// (start.estimate_gyro_bias) their mean rate as the gyro bias, with the bias sigma the standard
/// error of that mean, ekf.gyro_noise_density / sqrt(span), capped by start.gyro_bias_sigma. If
/// no such stretch comes within start.level_timeout_s of the first sample, it starts from the
/// mean of the plausible samples (level if none), bias 0.
///
/// Levelling: at rest f = R^T (0, 0, g) = g (-sin pitch, sin roll cos pitch, cos roll cos pitch)
/// for R = Rz(yaw) Ry(pitch) Rx(roll) (rover/geometry/transforms.hpp), so
///   roll = atan2(f_y, f_z),   pitch = atan2(-f_x, hypot(f_y, f_z)).

#include <Eigen/Core>
#include <optional>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/dl/pose/pose_ekf.hpp"

namespace rover::dl::pose {

/// Keys start.* of dl-pose.
struct PoseStartOptions {
  double x = 0.0;  ///< [m] start position, site frame
  double y = 0.0;
  double z = 0.0;
  double yaw = 0.0;                          ///< [rad] start heading
  double position_sigma = 0.01;              ///< [m] initial 1-sigma of x, y, z
  double tilt_sigma = 0.017453292519943295;  ///< [rad] of the levelled roll and pitch (1 deg)
  double yaw_sigma = 0.08726646259971647;    ///< [rad] of the heading (5 deg)
  double gyro_bias_sigma = 0.002;            ///< [rad/s] initial 1-sigma of the gyro bias
  // 10 s at 100 Hz: the mean gyro rate of a stationary stretch is the initial bias, and its
  // error (noise density / sqrt(duration): 6e-6 rad/s for the LN-200-like IMU) integrates into
  // heading drift (0.4 deg over a 1100 s drive; 0.5 s of levelling gave 1.8 deg).
  int level_samples = 1000;       ///< consecutive still samples averaged
  double level_timeout_s = 30.0;  ///< [s] then start anyway
  bool estimate_gyro_bias = true;

  static void BindParams(ParamBinder<PoseStartOptions>& b);
};

/// ZYX roll and pitch [rad] of the rover from a specific-force vector measured at rest.
Eigen::Vector2d LevelFromSpecificForce(const Eigen::Vector3d& f);

/// The filter's start, once the Leveller has it.
struct StartDecision {
  EkfInitialState init;
  bool at_rest = false;   ///< levelled on a still stretch (else: timed out)
  int samples = 0;        ///< samples averaged (still ones, or the plausible ones)
  double waited_s = 0.0;  ///< since the first sample
  Eigen::Vector2d roll_pitch = Eigen::Vector2d::Zero();  ///< [rad] levelled
};

class Leveller {
 public:
  /// `ekf` gives gravity, the plausibility and stillness thresholds and the gyro noise density.
  Leveller(const PoseStartOptions& start, const EkfOptions& ekf);

  /// One IMU sample before the filter started (finite values). The start once it is decided
  /// (the leveller then starts over); nullopt while it waits.
  std::optional<StartDecision> Add(Time t, const Eigen::Vector3d& angular_velocity,
                                   const Eigen::Vector3d& specific_force);
  /// Forgets every sample (a new run).
  void Reset();

  const PoseStartOptions& options() const { return start_; }

 private:
  StartDecision Decide(Time t, const Eigen::Vector3d& f_mean, const Eigen::Vector3d& bias,
                       double bias_span_s) const;

  PoseStartOptions start_;
  EkfOptions ekf_;
  std::optional<Time> first_;                        // first sample
  Eigen::Vector3d f_sum_ = Eigen::Vector3d::Zero();  // current still stretch
  Eigen::Vector3d w_sum_ = Eigen::Vector3d::Zero();
  int count_ = 0;
  Time still_since_;                                 // first sample of the stretch
  Eigen::Vector3d f_all_ = Eigen::Vector3d::Zero();  // every plausible sample
  int count_all_ = 0;
};

}  // namespace rover::dl::pose
