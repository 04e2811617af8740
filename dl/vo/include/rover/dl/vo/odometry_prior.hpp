#pragma once
/// @file
/// The wheel-odometry prior of a visual-odometry step, from the pose estimate at the two capture
/// times, in the rover (body) frame; ToCameraFrame (visual_odometry.hpp) turns it into the
/// camera frame the VO library works in.
///
/// With T_a = site_from_rover at t_from and T_b at t_to, the prior motion is
///     delta = T_a^-1 T_b        (rover at t_to in the rover at t_from; x forward, y left, z up)
/// and its covariance over [dx, dy, dz, droll, dpitch, dyaw] is diagonal with
///     sigma_t = translation_sigma_min + translation_sigma_fraction |t|       [m]
///     sigma_r = rotation_sigma_min + rotation_sigma_fraction angle(R)       [rad]
/// i.e. a floor plus a fraction of the step (slip makes wheel odometry err in proportion to the
/// distance driven). Without a pose at one of the times the prior is "unknown": zero motion
/// with the vague sigmas (vague_translation_sigma, vague_rotation_sigma), which makes the VO
/// library run its coarse first pass.

#include <Eigen/Geometry>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/dl/vo/visual_odometry.hpp"

namespace rover::dl::vo {

struct OdometryPriorOptions {
  double translation_sigma_min = 0.02;      ///< [m] > 0
  double translation_sigma_fraction = 0.1;  ///< [0, 10]
  double rotation_sigma_min = 0.02;         ///< [rad] > 0 (~1.1 deg)
  double rotation_sigma_fraction = 0.1;     ///< [0, 10]
  double vague_translation_sigma = 0.5;     ///< [m] > 0, prior without poses
  double vague_rotation_sigma = 0.2;        ///< [rad] > 0, prior without poses

  Status Validate() const;
  /// dl-vo's keys prior.* (translation_sigma_min, translation_sigma_fraction,
  /// rotation_sigma_min_deg, rotation_sigma_fraction, vague_translation_sigma,
  /// vague_rotation_sigma_deg) without the prefix.
  static void BindParams(ParamBinder<OdometryPriorOptions>& b);
};

/// The prior in the rover frame from the two poses (see the file comment).
MotionPrior OdometryPrior(const Eigen::Isometry3d& site_from_rover_from,
                          const Eigen::Isometry3d& site_from_rover_to,
                          const OdometryPriorOptions& options);

/// The prior when the motion is unknown: identity with the vague sigmas.
MotionPrior VaguePrior(const OdometryPriorOptions& options);

}  // namespace rover::dl::vo
