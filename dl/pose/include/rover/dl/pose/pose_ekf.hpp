#pragma once
/// @file
/// Pose estimator: an error-state extended Kalman filter after FIDO's (Baumgartner et al. 2001)
/// and MER's (Ali et al. 2005; Maimone et al. 2007) attitude and position estimation, with
/// stochastic cloning (Roumeliotis & Burdick 2002) for relative-pose measurements.
///
/// Frames: site frame S (x north, y west, z up, fixed to the terrain); rover frame B (x forward,
/// y left, z up). R = R_SB rotates rover-frame vectors into the site frame; p = rover origin in
/// S. Angles rad, lengths m, time on the run clock.
///
/// Nominal state: p, R (kept as a rotation matrix, reported as a quaternion), gyro bias b [rad/s],
/// plus N clones (t_k, p_k, R_k) of past poses. Error state (dimension 9 + 6 N), with the
/// attitude error a small rotation in the SITE frame ("left" / global perturbation):
///   p = p^ + dp,   R = Exp(dth) R^,   b = b^ + db,   clone k likewise (dp_k, dth_k).
/// With this choice dth_z is the heading error (for small tilt), and the VO covariance
/// (dl/vo, "left" perturbation in the t_from frame) maps directly.
///
/// Propagation
///   gyro  w_m at t (zero-order hold over (t_prev, t]):  R^ <- R^ Exp((w_m - b^) dt),
///         dth <- dth - R^ db dt + noise(gyro_noise_density^2 dt I),
///         db <- db + noise(gyro_bias_walk^2 dt I).
///   wheel odometry increment (dx, dy, dyaw, Cov) in the rover frame at t_from (from
///         dl_locomotion's WheelOdometry): the rover frame at t_from is R_f = R^ Rz(dyaw)^T, and
///         p^ <- p^ + R_f d,  d = (dx, dy, 0),
///         dp <- dp - [R_f d]x dth + R_f n,  n ~ N(0, blockdiag(Cov_xy, vertical_var * s)).
///   Only the gyros drive the attitude (MER: IMU attitude, wheel/visual odometry position); the
///   odometry heading only re-expresses the step in the frame at t_from.
///   Clone cross-covariances are propagated lazily (P_lc <- Phi_acc P_lc when next needed).
///
/// Measurements (all Mahalanobis-gated: d^2 = r^T S^-1 r against the chi-square quantile of
/// gate_probability with dim(r) degrees of freedom; rejected ones are counted and reported):
///   accelerometer (only when stationary: no wheel motion for stationary_delay_s, |w_m - b^|
///       below stationary_gyro_threshold and | |f| - g | below accel_magnitude_tolerance; at most
///       one per accel_update_interval_s):  f = R^T (0, 0, g) + n;  H_dth = R^T [g e_z]x.
///       Observes roll and pitch (and through correlation the x/y gyro biases), not heading.
///   sun sensor: sun unit vector s_B in the rover frame, given the ephemeris sun direction s_S in
///       the site frame (an input, so the library stays pure): s_B = R^T s_S + n. The residual is
///       taken in the 2-D tangent plane of the prediction (basis E, 2 x 3):
///       r = E (s_B - R^T s_S),  H_dth = E R^T [s_S]x,  noise sun_noise^2 I_2.
///   relative pose (visual odometry): delta = T(t_from)^-1 T(t_to), the rover frame at t_to in
///       the rover frame at t_from, with a 6x6 covariance over (dx, dy, dz, dthx, dthy, dthz) in
///       the t_from frame (left perturbation: R_true = Exp(dth) R_meas, as dl/vo reports). With
///       poses (p_i, R_i) at t_from and (p_j, R_j) at t_to taken from the clones (linearly
///       interpolated between the two clones, or clone and live state, that bracket each time):
///         r_p  = dp_meas - R_i^T (p_j - p_i)
///         r_th = Log(dR_meas (R_i^T R_j)^T)
///         H: r_p wrt dp_j = R_i^T, dp_i = -R_i^T, dth_i = R_i^T [p_j - p_i]x;
///            r_th wrt dth_j = R_i^T, dth_i = -R_i^T.
///       A measurement whose t_to is ahead of the filter (by at most max_pending_s; at most 64
///       wait) is kept until the gyro propagation reaches t_to; one whose t_from is older than
///       the oldest clone is reported as rejected without gating (mahalanobis_sq NaN).
/// Clones are taken at initialisation and then every clone_interval_s of gyro propagation, and
/// kept for clone_window_s.
///
/// Output covariance over (x, y, z, roll, pitch, yaw): J P_pose J^T with J = blockdiag(I, E^-1),
/// E = [Rz Ry e_x, Rz e_y, e_z] the map from ZYX angle increments to the site-frame rotation
/// (singular only at pitch = +-90 deg).
///
/// Errors: bad inputs (non-finite, out-of-order stamps, covariances that are not symmetric
/// positive definite) return a Status and leave the state unchanged. The filter never aborts on
/// data.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/params.hpp"
#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/dl/locomotion/wheel_odometry.hpp"
#include "rover/msg/pose.hpp"

namespace rover::dl::pose {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Matrix9d = Eigen::Matrix<double, 9, 9>;

// The messages the filter reads and writes (rover/msg/pose.hpp): dl/pose, dl/relative_pose
// (only CONVERGED samples are measurements) and dl/estimator_event.
using msg::MotionSource;
using msg::MotionSourceName;
using msg::PoseEstimate;

/// One gated measurement (dl/estimator_event) and the degrees of freedom of its test.
struct EstimatorEvent : msg::EstimatorEvent {
  int dof = 0;  ///< dim(r) of the chi-square test (not on the wire)
};

struct EkfOptions {
  // Process noise.
  double gyro_noise_density = 1e-4;                ///< [rad/s/sqrt(Hz)] angle random walk
  double gyro_bias_walk = 1e-6;                    ///< [rad/s/sqrt(s)] bias random walk
  double odometry_vertical_variance_per_m = 1e-4;  ///< [m^2/m] rover-z noise of odometry steps
  // Accelerometer.
  double gravity = 9.81;                    ///< [m/s^2] (3.71 on Mars)
  double accel_noise = 0.05;                ///< [m/s^2] 1-sigma per axis (averaged sample)
  double accel_magnitude_tolerance = 0.3;   ///< [m/s^2] | |f| - g | allowed for an update
  double accel_update_interval_s = 0.5;     ///< [s] minimum spacing of accelerometer updates
  double stationary_delay_s = 0.5;          ///< [s] without wheel motion before "stationary"
  double stationary_gyro_threshold = 0.01;  ///< [rad/s] bias-corrected rate below which at rest
  double wheel_motion_threshold = 1e-4;     ///< [m] odometry path per increment that is motion
  /// [m] the odometer counts planar displacement in steps of this length: it grows when the
  /// displacement since its last step reaches it, so encoder jitter at rest (increments of either
  /// sign that cancel) never adds up, and a drive is counted to within one step.
  double odometer_step = 0.01;
  // Sun sensor.
  double sun_noise = 0.005;  ///< [rad] 1-sigma angular error of the sun vector
  // Gating.
  double gate_probability = 0.999;  ///< chi-square gate probability, in (0, 1)
  // Stochastic cloning for relative poses.
  double clone_interval_s = 1.0;  ///< [s] clone spacing; 0 disables cloning
  double clone_window_s = 60.0;   ///< [s] clones kept this long
  double max_pending_s = 30.0;    ///< [s] largest t_to - time() accepted (then it waits)

  Status Validate() const;
};

/// Initial state and its uncertainty.
struct EkfInitialState {
  Time stamp;
  Eigen::Vector3d position = Eigen::Vector3d::Zero();                ///< [m] site frame
  Eigen::Quaterniond attitude = Eigen::Quaterniond::Identity();      ///< rover in site
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();               ///< [rad/s]
  Eigen::Vector3d position_sigma = Eigen::Vector3d::Constant(0.01);  ///< [m]
  Eigen::Vector3d rpy_sigma = Eigen::Vector3d(0.02, 0.02, 0.1);      ///< [rad] roll pitch yaw
  double gyro_bias_sigma = 0.002;                                    ///< [rad/s] per axis
  double odometer = 0.0;  ///< [m] the odometer's start value (a resumed estimator keeps its own)
};

/// Heading for closed-loop turns in place.
struct HeadingEstimate {
  Time stamp;
  double yaw = 0.0;       ///< [rad] in (-pi, pi]
  double variance = 0.0;  ///< [rad^2]
};

class PoseEkf {
 public:
  static Result<PoseEkf> Create(const EkfOptions& options);

  /// (Re)starts the filter. Errors: non-finite values or negative sigmas.
  Status Initialize(const EkfInitialState& init);
  bool initialized() const { return initialized_; }

  /// Gyro sample (bias included, rover frame) valid over (time(), t]. Errors: not initialised,
  /// non-finite rate, t < time(). May take a clone and process waiting relative poses.
  Status PropagateGyro(Time t, const Eigen::Vector3d& angular_velocity);
  /// Errors: not initialised, non-finite values, t_to not after the previous increment.
  Status AddWheelOdometry(const locomotion::OdometryIncrement& increment);
  /// Specific force [m/s^2] in the rover frame. Used only when stationary (else ignored, Ok).
  Status UpdateAccelerometer(Time t, const Eigen::Vector3d& specific_force);
  /// Sun direction measured in the rover frame and the ephemeris direction in the site frame
  /// (need not be normalised). Errors: non-finite or (near-)zero vectors.
  Status UpdateSunSensor(Time t, const Eigen::Vector3d& sun_rover, const Eigen::Vector3d& sun_site);
  /// Processed now if t_to <= time(), else kept until the gyro propagation reaches t_to; the
  /// outcome is an EstimatorEvent. Errors: non-finite values, t_to <= t_from, a delta rotation
  /// that is not a rotation, a covariance that is not symmetric positive definite, t_to more
  /// than max_pending_s ahead of the filter.
  Status AddRelativePose(const msg::RelativePose& measurement);

  PoseEstimate Estimate() const;
  HeadingEstimate Heading() const;
  /// Events since the last call, oldest first.
  std::vector<EstimatorEvent> TakeEvents();

  Time time() const { return time_; }
  const Eigen::Vector3d& position() const { return p_; }
  const Eigen::Matrix3d& rotation() const { return R_; }
  Eigen::Quaterniond attitude() const;
  const Eigen::Vector3d& gyro_bias() const { return bg_; }
  /// 9 x 9 covariance of (dp, dth, db).
  Matrix9d covariance() const { return P_.topLeftCorner<9, 9>(); }
  bool stationary() const;
  std::size_t num_clones() const { return clones_.size(); }
  std::size_t pending_relative_poses() const { return pending_.size(); }
  std::uint32_t rejected_measurements() const { return rejected_; }
  const EkfOptions& options() const { return options_; }

 private:
  struct Clone {
    Time t;
    Eigen::Vector3d p;
    Eigen::Matrix3d R;
  };
  // A pose at some time as a weighted combination of pose blocks (live = index 0, clone k at
  // 9 + 6k) and its nominal value.
  struct PoseNode {
    Eigen::Vector3d p;
    Eigen::Matrix3d R;
    int block_a = 0;
    int block_b = 0;
    double weight_b = 0.0;  // error = (1 - w) block_a + w block_b
  };

  explicit PoseEkf(const EkfOptions& o);
  void PropagateLive(const Matrix9d& phi, const Matrix9d& q);
  void SyncCross();
  void AddClone();
  void PruneClones();
  std::optional<PoseNode> Interpolate(Time t) const;
  void ProcessPending();
  void ProcessRelativePose(const msg::RelativePose& m);
  bool Update(MotionSource source, Time t, const Eigen::VectorXd& r, const Eigen::MatrixXd& h,
              const Eigen::MatrixXd& noise, const std::string& what);
  void Inject(const Eigen::VectorXd& dx);
  void Reject(MotionSource source, Time t, std::string message);

  EkfOptions options_;
  bool initialized_ = false;
  Time time_;
  Eigen::Vector3d p_ = Eigen::Vector3d::Zero();
  Eigen::Matrix3d R_ = Eigen::Matrix3d::Identity();
  Eigen::Vector3d bg_ = Eigen::Vector3d::Zero();
  Eigen::MatrixXd P_;
  Matrix9d phi_acc_ = Matrix9d::Identity();
  std::vector<Clone> clones_;
  std::optional<Time> last_clone_;
  std::deque<msg::RelativePose> pending_;
  std::vector<EstimatorEvent> events_;
  Eigen::Vector3d last_rate_ = Eigen::Vector3d::Zero();  // bias-corrected
  Time last_motion_;
  std::optional<Time> last_accel_update_;
  std::optional<Time> last_odometry_;
  Eigen::Vector3d velocity_ = Eigen::Vector3d::Zero();
  std::uint32_t rejected_ = 0;
  double odometer_ = 0.0;
  Eigen::Vector3d odometer_pending_ = Eigen::Vector3d::Zero();  // [m] site frame, since the last step
};

/// Declares the EKF parameters under `prefix` ("ekf." by default) with `defaults` as their
/// default values (a service on Mars passes gravity 3.711).
void DeclareEkfParams(ParamSet& params, const std::string& prefix = "ekf.",
                      const EkfOptions& defaults = EkfOptions{});
Result<EkfOptions> EkfOptionsFromParams(const ParamSet& params, const std::string& prefix = "ekf.");

}  // namespace rover::dl::pose
