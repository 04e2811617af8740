#pragma once
/// @file
/// dl-pose: the service that binds the pose EKF (library dl_pose) and wheel odometry
/// (dl_locomotion's WheelOdometry) to topics.
///
///   in:  ddl/imu           gyro propagation (every sample); accelerometer update when the filter
///                          considers the rover stationary (the library decides)
///        ddl/joint_state   wheel-odometry increments between consecutive healthy samples
///        ddl/sun_sensor    heading update when `valid`, using the sun direction in the site frame
///                          from the Mars ephemeris (core/geometry mars_sun.hpp) at run time
///                          t - ephemeris.run_start_s, with the simulator's default site/season
///        dl/relative_pose  visual-odometry measurements; only RELPOSE_CONVERGED are applied
///   out: dl/pose           at publish_rate_hz (10 Hz run-clock timer), stamped with the filter
///                          time, frame "site": pose, 6x6 covariance, velocity, gyro bias,
///                          stationary flag, rejected count, odometer
///        dl/estimator_event one per gated measurement (accepted or rejected, d^2 and gate), and
///                          one (rejected, d^2 NaN) per relative pose refused as bad input
///        dl/pose_odometry  (odometry_only.enabled) the same rate and layout from a second filter
///                          fed only the IMU and wheel odometry (no sun, no visual odometry):
///                          MER's "IMU + wheel odometry" dead reckoning. The difference from
///                          dl/pose is the slip that the sun sensor and visual odometry removed;
///                          the scenario judge reports both errors side by side.
///
/// Start-up: the position and heading come from parameters (start.*; the site frame's origin is
/// the rover's start, so x = y = 0 by default). Roll and pitch are levelled from the mean of the
/// first start.level_samples accelerometer samples of a stationary stretch (gyro rate below
/// ekf.stationary_gyro_threshold, |f| within ekf.accel_magnitude_tolerance of ekf.gravity); the
/// mean gyro over that stretch is the initial bias (start.estimate_gyro_bias). If no stationary
/// stretch comes within start.level_timeout_s, the filter starts from the mean of the
/// plausible accelerometer samples seen (level if none) and says so in a warning. Until then
/// nothing is published on dl/pose and the heartbeat reports DEGRADED.
///
/// Restart (kill -9, crash: the supervisor starts it again): in a supervised set dl-pose keeps a
/// checkpoint of its last published estimate every resume.checkpoint_period_s of run time
/// (rover/base/checkpoint.hpp: $ROVER_STATE_DIR/checkpoints/<name>.ckpt, valid for this set's
/// ROVER_SET_ID only). A restarted dl-pose never starts over at start.* as if nothing had
/// happened: on its first usable ddl/imu sample it either
///   - resumes from the checkpoint (position, attitude, gyro bias, odometer; both filters), the
///     covariance inflated for what may have happened while it was down: position sigma grown
///     by resume.max_speed, heading sigma by resume.max_yaw_rate_deg_s, times the run-clock gap
///     (quadrature); heartbeat OK "resumed from checkpoint ..."; or
///   - declares itself uninitialised when the checkpoint is older than resume.max_age_s or
///     unreadable: no dl/pose at all, heartbeat FAILED "pose unknown after restart: ...", so
///     nothing drives on it (the set must be restarted or the pose set by an operator).
/// A checkpoint stamped more than 1 s after the first sample means the run clock went back (a new
/// run): it is ignored and the filter levels as at a first start.
///
/// Bad samples never crash the service: FAILED/STALE or non-finite samples are dropped (counted
/// in warnings), library errors are logged, and a run-clock reset (a sample more than 1 s older
/// than the filter, e.g. after a simulator reset) restarts the filter and the levelling.

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "rover/base/checkpoint.hpp"
#include "rover/dl/locomotion/wheel_odometry.hpp"
#include "rover/dl/pose/pose_ekf.hpp"
#include "rover/geometry/mars_sun.hpp"
#include "rover/runtime/service.hpp"

namespace rover::dl {

/// dl/pose from the library's estimate (covariance row-major).
rover_dl_PoseEstimate PoseEstimateToIdl(const PoseEstimate& e);
/// dl/estimator_event from the library's event.
rover_dl_EstimatorEvent EstimatorEventToIdl(const EstimatorEvent& e);
/// dl/relative_pose -> measurement. Errors: unknown source value, a delta quaternion whose norm
/// is not 1 within 1e-6 (or NaN). Other non-finite values and a covariance that is not symmetric
/// positive definite are left for PoseEkf::AddRelativePose to reject.
Result<RelativePoseMeasurement> RelativePoseFromIdl(const rover_dl_RelativePose& m);
/// ZYX roll and pitch [rad] of the rover from a specific-force vector measured at rest.
Eigen::Vector2d LevelFromSpecificForce(const Eigen::Vector3d& f);

class PoseService final : public Service {
 public:
  PoseService() : Service("dl-pose") {}

  void DeclareParameters(ParamSet& params) override;
  Status ValidateParameters(const ParamSet& params) const override;
  Status OnConfigure(ServiceContext& ctx, const ParamSet& params) override;

  /// The filter (for tests); null before configuration.
  const PoseEkf* ekf() const { return ekf_.has_value() ? &*ekf_ : nullptr; }
  /// The IMU + wheel odometry filter (for tests); null before configuration or when disabled.
  const PoseEkf* odometry_only() const {
    return odometry_only_.has_value() ? &*odometry_only_ : nullptr;
  }

 private:
  struct StartOptions {
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    double yaw = 0.0;
    double position_sigma = 0.01;
    double tilt_sigma = 0.017453292519943295;  // 1 deg
    double yaw_sigma = 0.08726646259971647;    // 5 deg
    double gyro_bias_sigma = 0.002;
    // 10 s at 100 Hz: the mean gyro rate of a stationary stretch is the initial bias, and its
    // error (noise density / sqrt(duration): 6e-6 rad/s for the LN-200-like IMU) integrates
    // into heading drift (0.4 deg over a 1100 s drive; 0.5 s of levelling gave 1.8 deg).
    int level_samples = 1000;
    double level_timeout_s = 30.0;
    bool estimate_gyro_bias = true;
  };
  struct ResumeOptions {
    bool enabled = true;
    double checkpoint_period_s = 1.0;
    double max_age_s = 60.0;
    double max_speed = 0.1;                       // [m/s]
    double max_yaw_rate = 0.034906585039886591;   // [rad/s] 2 deg/s
  };
  /// A checkpoint read back: one filter's state.
  struct Saved {
    Time stamp;
    Eigen::Vector3d position = Eigen::Vector3d::Zero();
    Eigen::Quaterniond attitude = Eigen::Quaterniond::Identity();
    Eigen::Vector3d position_sigma = Eigen::Vector3d::Zero();
    Eigen::Vector3d rpy_sigma = Eigen::Vector3d::Zero();
    Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
    double odometer = 0.0;
  };
  struct Levelling {
    std::optional<Time> first;                        // first usable IMU sample
    Eigen::Vector3d f_sum = Eigen::Vector3d::Zero();  // current stationary stretch
    Eigen::Vector3d w_sum = Eigen::Vector3d::Zero();
    int count = 0;
    Time still_since;                                 // first sample of the current stretch
    Eigen::Vector3d f_all = Eigen::Vector3d::Zero();  // every plausible sample (fallback)
    int count_all = 0;
  };

  void OnImu(const rover_ddl_Imu& m);
  void OnJointState(const rover_ddl_JointState& m);
  void OnSunSensor(const rover_ddl_SunSensor& m);
  void OnRelativePose(const rover_dl_RelativePose& m);
  void OnTimer();
  void Level(Time t, const Eigen::Vector3d& w, const Eigen::Vector3d& f);
  /// `bias_span_s` > 0: `bias` is the mean gyro rate over that many seconds at rest, and its
  /// initial sigma is the standard error of that mean (ekf.gyro_noise_density / sqrt(span)),
  /// capped by start.gyro_bias_sigma.
  void Start(Time t, const Eigen::Vector3d& f_mean, const Eigen::Vector3d& bias,
             double bias_span_s, const char* how);
  void Restart(const std::string& why);
  /// Reads this set's checkpoint at configuration (into saved_, or uninitialised_ on a bad one).
  void LoadCheckpoint();
  void SaveCheckpoint();
  /// On the first usable sample after a restart: resume from saved_ or declare the pose unknown.
  /// Returns true when it resumed.
  bool ResumeOrRefuse(Time t);
  void PublishEvents();
  void PublishRejectedInput(MotionSource source, Time t, const std::string& message);
  /// Logs the 1st, 10th, 100th, ... occurrence of `what` (a warning that cannot flood sys/event).
  void WarnCounted(const std::string& what, const std::string& detail);

  ServiceContext* ctx_ = nullptr;
  EkfOptions ekf_options_;
  StartOptions start_;
  geometry::SunEphemerisOptions ephemeris_options_;
  double run_start_s_ = 0.0;
  bool sun_enabled_ = true;
  double sun_min_elevation_ = 0.0;
  double sun_max_rate_ = 0.0;       // [rad/s] no sun updates while turning faster
  double last_rate_ = 0.0;          // [rad/s] |bias-corrected gyro| of the last IMU sample
  double imu_stale_s_ = 0.5;
  std::optional<PoseEkf> ekf_;
  /// IMU + wheel odometry only (dl/pose_odometry); empty when odometry_only.enabled is false.
  std::optional<PoseEkf> odometry_only_;
  std::optional<WheelOdometry> odometry_;
  std::optional<geometry::SunEphemeris> ephemeris_;
  Levelling levelling_;
  ResumeOptions resume_;
  CheckpointStore checkpoints_;
  std::optional<Saved> saved_;                 // the filter's checkpoint
  std::optional<Saved> saved_odometry_only_;   // the odometry-only filter's
  std::optional<Time> last_checkpoint_;
  std::optional<std::string> uninitialised_;   // why the pose is unknown after a restart
  dds::Writer<rover_dl_PoseEstimate> pose_writer_;
  dds::Writer<rover_dl_EstimatorEvent> event_writer_;
  dds::Writer<rover_dl_PoseEstimate> odometry_only_writer_;
  std::map<std::string, std::uint64_t> warn_counts_;
};

}  // namespace rover::dl
