#pragma once
/// @file
/// Wheel odometry: the rover's planar motion between two joint-state samples from the wheel,
/// steering and suspension angles (least squares over the six wheels' contact velocities, as on
/// MER and FIDO; Maimone et al. 2007, Baumgartner et al. 2001).
///
/// For wheel i with centre p_i(t) (RoverGeometry::WheelCentre, from the rocker/bogie angles),
/// heading d_i (steer angle averaged over the two samples; 0 for the middle wheels), rolling
/// direction t_i = (cos d_i, sin d_i), lateral direction n_i = (-sin d_i, cos d_i), rim path
/// r dth_i and link pitch a_i (averaged), the no-slip equations for the body increment
/// (u = (dx, dy), w = dpsi), written in the rover frame at the first sample, are
///   t_i . (u + w J pbar_i) = r dth_i cos a_i - t_i . dp_i     (rolling)
///   n_i . (u + w J pbar_i) =                 - n_i . dp_i     (no side slip)
/// with J = [0 -1; 1 0], pbar_i the mean planar wheel position and dp_i its planar change due
/// to the suspension (the wheel centre moving relative to the body). The wheel is taken to roll
/// along the terrain tangent under it, approximated by its link's x axis, so only cos a_i of its
/// rim path is planar in the body frame. The 12 x 3 system is solved by least squares (QR).
/// The solution is a twist over the interval; the increment returned integrates it at constant
/// rate (SE(2) exponential):
///   dx = (u_x sin w - u_y (1 - cos w)) / w,   dy = (u_x (1 - cos w) + u_y sin w) / w,   dyaw = w.
/// On a slope the rover's planar (body xy) motion is rotated into the site frame by the attitude
/// estimate (dl/pose does this).
///
/// Covariance model (proportional to the distance travelled): with s = mean_i |r dth_i cos a_i|
/// (the wheels' mean path, > 0 also for turns in place) and e the unit direction of (dx, dy)
/// (x if no translation),
///   Cov(dx, dy) = s (k_along e e^T + k_cross e_perp e_perp^T),   Var(dyaw) = s k_yaw,
/// k_* in m^2/m and rad^2/m.

#include <Eigen/Core>
#include <optional>

#include "rover/base/params.hpp"
#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/dl/locomotion/drive_types.hpp"
#include "rover/dl/locomotion/rover_geometry.hpp"

namespace rover::dl::locomotion {

/// [rad/s] no drive wheel turns this fast (the rover's wheels: about 0.5 rad/s at top speed).
inline constexpr double kMaxPlausibleWheelRate = 10.0;
/// [rad] encoder quantisation and sample-time jitter allowed on top of rate * dt.
inline constexpr double kWheelJumpSlack = 0.05;

/// The one plausibility rule for consecutive joint samples (wheel odometry and the drive
/// executor): OutOfRange naming the wheel when a wheel angle changed by more than
/// max_wheel_rate * (to.stamp - from.stamp) + kWheelJumpSlack. Samples not after `from` pass.
Status CheckWheelJump(const msg::JointState& from, const msg::JointState& to,
                      double max_wheel_rate = kMaxPlausibleWheelRate);

struct WheelOdometryOptions {
  double along_variance_per_m = 1e-3;  ///< [m^2/m] along the motion (sigma 3.2 cm after 1 m)
  double cross_variance_per_m = 1e-3;  ///< [m^2/m] across the motion
  double yaw_variance_per_m = 3e-4;    ///< [rad^2/m] (sigma 1 deg after 1 m)
  double max_wheel_step = 2.0;         ///< [rad] largest plausible wheel rotation per interval
  double max_interval_s = 2.0;         ///< [s] largest plausible time between the two samples
  /// [rad/s] fastest plausible wheel: a wheel turning more than max_wheel_rate dt +
  /// kWheelJumpSlack between two samples is an encoder fault (a flipped bit), not motion
  double max_wheel_rate = kMaxPlausibleWheelRate;
  bool use_suspension = true;          ///< false: ignore rocker/bogie (flat-ground model)
  /// Expected longitudinal slip s = (rim speed - ground speed) / rim speed on the terrain
  /// driven, calibrated there (0 = a rigid wheel rolling without slip): each wheel's rim
  /// distance r dtheta counts as (1 - s) r dtheta on the ground. Even on flat firm soil a
  /// driven wheel slips enough for its traction to overcome rolling resistance (the simulator's
  /// firm soil: about 2 %), which uncompensated odometry counts as distance. In [0, 0.5).
  double slip_ratio = 0.0;

  Status Validate() const;
};

/// Planar motion of the rover between two samples, in the rover frame at t_from.
struct OdometryIncrement {
  Time t_from;
  Time t_to;
  double dx = 0.0;                                       ///< [m]
  double dy = 0.0;                                       ///< [m]
  double dyaw = 0.0;                                     ///< [rad] counter-clockwise
  double path_length = 0.0;                              ///< [m] mean wheel path s (>= 0)
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();  ///< over (dx, dy, dyaw)
  double residual_rms = 0.0;  ///< [m] RMS residual of the 12 no-slip equations (slip indicator)
};

class WheelOdometry {
 public:
  /// Errors: invalid geometry or options.
  static Result<WheelOdometry> Create(const RoverGeometry& geometry,
                                      const WheelOdometryOptions& options);

  /// The increment from `from` to `to`. Errors (InvalidArgument / OutOfRange, state-free):
  /// non-finite samples, to.stamp <= from.stamp, an interval longer than max_interval_s, or a
  /// wheel rotation larger than max_wheel_step.
  Result<OdometryIncrement> Compute(const msg::JointState& from, const msg::JointState& to) const;

  /// Convenience for a stream of samples: the increment from the previous accepted sample (none
  /// for the first). A non-finite or out-of-order sample is reported and dropped; a later sample
  /// with an implausible wheel jump is reported and restarts the stream, as does (silently,
  /// returning nullopt) a sample after a gap longer than max_interval_s.
  Result<std::optional<OdometryIncrement>> Add(const msg::JointState& sample);
  void Reset() { previous_.reset(); }

  const RoverGeometry& geometry() const { return geometry_; }
  const WheelOdometryOptions& options() const { return options_; }

 private:
  WheelOdometry(const RoverGeometry& g, const WheelOdometryOptions& o)
      : geometry_(g), options_(o) {}
  RoverGeometry geometry_;
  WheelOdometryOptions options_;
  std::optional<msg::JointState> previous_;
};

/// Declares the odometry parameters under `prefix` ("odometry." by default).
void DeclareWheelOdometryParams(ParamSet& params, const std::string& prefix = "odometry.");
Result<WheelOdometryOptions> WheelOdometryOptionsFromParams(
    const ParamSet& params, const std::string& prefix = "odometry.");

}  // namespace rover::dl::locomotion
