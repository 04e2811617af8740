#pragma once
/// @file
/// Close-range lander vision, step 2: the pose of a lander ramp relative to the rover from its
/// identified stripe corners (stripe_detector.hpp) in one or both NAVCAM images.
///
/// Model. Stripe s of ramp r has its corners in the ramp-surface frame G
/// (hwconfig::LanderDescription: origin at the centre of the ramp surface, u up the slope, v to
/// the left facing up the ramp, w = u x v out of the surface) at
///   (u_s -+ width_s / 2, +-length / 2, 0)
/// in the detector's corner order (u-, v+), (u-, v-), (u+, v-), (u+, v+). A pose
/// T = rover_from_ramp maps them into the rover frame (x forward, y left, z up, metres), where
/// the camera models of the frame (CAHVOR, rover frame at capture time) project them.
///
/// Estimate. Initial pose from the left camera alone: every valid corner is unprojected to a
/// ray, expressed as normalised coordinates of a virtual pinhole looking along the mean ray, and
/// the plane-to-image homography from G's (u, v) is decomposed (H ~ [r1 r2 t]). Then
/// Levenberg-Marquardt minimises the reprojection error of every valid corner in both cameras,
///   sum_k rho(|Project_cam(k)(T p_k) - x_k|^2),   rho = Huber with `huber_px`,
/// over the right-multiplied increment T <- T Exp(delta), delta = (rho [m], phi [rad]) in G,
/// using the models' analytic 2x3 Jacobians. The covariance of delta is
///   sigma^2 (J^T W J)^-1,  sigma^2 = sum w r^2 / (2 N - 6),
/// i.e. the residual-scaled Gauss-Newton normal matrix (translation first, G axes u, v, w).
///
/// Errors: fewer than `min_stripes` identified stripes of the ramp in the left image
/// (FailedPrecondition, naming how many), a degenerate or behind-the-camera initial pose and a
/// final rms above `max_rms_px` (FailedPrecondition with the figures), bad options or a right
/// detection without a right model (InvalidArgument).

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "rover/apl/rendezvous/stripe_detector.hpp"
#include "rover/base/status.hpp"
#include "rover/geometry/camera_model.hpp"
#include "rover/hwconfig/lander_description.hpp"

namespace rover {
template <class Options>
class ParamBinder;
}  // namespace rover

namespace rover::apl::rendezvous {

struct RampPoseOptions {
  int min_stripes = 4;        ///< identified stripes of the ramp needed in the left image
  int ramp = -1;              ///< ramp to use (0/1); -1: the left detection's best ramp
  int max_iterations = 30;    ///< Levenberg-Marquardt iterations
  double huber_px = 1.0;      ///< [px] Huber threshold on a corner's reprojection error
  double max_rms_px = 2.0;    ///< [px] largest accepted final rms reprojection error
  double stripe_lift = 0.0;   ///< [m] stripes above the ramp surface along w (paint: 0)

  /// Checks every field; messages start with "<prefix><field>: " and name the value.
  Status Validate(const char* prefix = "ramp_pose.") const;
  static void BindParams(ParamBinder<RampPoseOptions>& b);
};

struct RampPose {
  int ramp = 0;  ///< which ramp (0/1)
  /// Frame G of the ramp -> rover frame.
  Eigen::Isometry3d rover_from_ramp = Eigen::Isometry3d::Identity();
  /// Covariance of delta = (translation [m], rotation [rad]) in G, rover_from_ramp_true =
  /// rover_from_ramp Exp(delta) (see the file comment).
  Eigen::Matrix<double, 6, 6> covariance = Eigen::Matrix<double, 6, 6>::Identity();
  double rms_px = 0.0;       ///< rms reprojection error over the corners used [px]
  int stripes_used = 0;      ///< distinct stripes with at least one valid corner (both cameras)
  int corners_used = 0;      ///< corner observations (both cameras)
  int iterations = 0;
};

/// Estimates the pose of the ramp from the left detection (and optionally the right one; both
/// may be null together). The models are those of the images, in the rover frame.
/// Preconditions: `lander` valid (Validate()).
Result<RampPose> EstimateRampPose(const hwconfig::LanderDescription& lander,
                                  const StripeDetection& left,
                                  const geometry::CameraModel& left_model,
                                  const StripeDetection* right,
                                  const geometry::CameraModel* right_model,
                                  const RampPoseOptions& options = {});

/// Where the rover has to go: the ramp's foot in the rover frame.
struct RampBase {
  /// [m] centre of the ramp's bottom edge, G point (-slope_length / 2, 0, 0), in the rover frame.
  Eigen::Vector3d base_in_rover = Eigen::Vector3d::Zero();
  /// Horizontal unit vector up the ramp (u projected onto the plane normal to `up`), rover frame.
  Eigen::Vector3d up_axis_in_rover = Eigen::Vector3d::UnitX();
  double inclination = 0.0;   ///< [rad] of u above the horizontal plane (estimated)
  double slope_length = 0.0;  ///< [m] ramp_length / cos(inclination)
};

/// The ramp's foot from an estimated pose. The rover knows the ramp's horizontal run
/// (lander.ramp_length) but not its inclination (it depends on the ground under the lander),
/// so the inclination is taken from the estimate: sin(incl) = u_rover . up_in_rover, with
/// `up_in_rover` the direction opposite to gravity in the rover frame (e.g. from the IMU;
/// (0, 0, 1) on level ground), and the surface length from the middle of the ramp down to its
/// foot is ramp_length / (2 cos(incl)). Errors: `up_in_rover` not finite or zero
/// (InvalidArgument), a ramp inclined 80 deg or more against `up` (FailedPrecondition).
Result<RampBase> RampBaseInRover(const hwconfig::LanderDescription& lander, const RampPose& pose,
                                 const Eigen::Vector3d& up_in_rover = Eigen::Vector3d::UnitZ());

/// The corner of stripe `index` (0..5) of ramp `ramp` in frame G, numbered as the detector's
/// corners (0: (u-, v+), 1: (u-, v-), 2: (u+, v-), 3: (u+, v+)), lifted `lift` along w.
Eigen::Vector3d StripeCornerInRamp(const hwconfig::LanderDescription& lander, int ramp, int index,
                                   int corner, double lift = 0.0);

}  // namespace rover::apl::rendezvous
