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
/// The IDL conversions are core/msg's (rover/msg/pose_idl.hpp, sensors_idl.hpp).
///
/// Bad samples never crash the service: FAILED/STALE or non-finite samples are dropped (counted
/// in warnings), library errors are logged, and a run-clock reset (a sample more than 1 s older
/// than the filter, e.g. after a simulator reset) restarts the filter and the levelling.

#include <cstdint>
#include <map>
#include <optional>
#include <string>

#include "rover/dl/locomotion/wheel_odometry.hpp"
#include "rover/dl/pose/pose_ekf.hpp"
#include "rover/geometry/mars_sun.hpp"
#include "rover/runtime/service.hpp"

namespace rover::dl {

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
  dds::Writer<rover_dl_PoseEstimate> pose_writer_;
  dds::Writer<rover_dl_EstimatorEvent> event_writer_;
  dds::Writer<rover_dl_PoseEstimate> odometry_only_writer_;
  std::map<std::string, std::uint64_t> warn_counts_;
};

}  // namespace rover::dl
