#pragma once
/// @file
/// dl-pose: the service that binds the pose estimator (library dl_pose: PoseEstimator, the EKF,
/// the start-up levelling, and dl_locomotion's WheelOdometry) to topics.
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
/// Start-up (dl/pose/pose_startup.hpp): the position and heading come from parameters (start.*;
/// the site frame's origin is the rover's start, so x = y = 0 by default); roll and pitch are
/// levelled from the first start.level_samples accelerometer samples of a stationary stretch,
/// the mean gyro over it is the initial bias (start.estimate_gyro_bias); without a stationary
/// stretch within start.level_timeout_s the filter starts from the mean of the plausible samples
/// and says so in a warning. Until then nothing is published on dl/pose and the heartbeat
/// reports DEGRADED.
///
/// Restart (kill -9, crash: the supervisor starts it again; dl/pose/pose_resume.hpp): in a
/// supervised set dl-pose keeps a checkpoint of its last published estimate every
/// resume.checkpoint_period_s of run time (rover/base/checkpoint.hpp:
/// $ROVER_STATE_DIR/checkpoints/<name>.ckpt, valid for this set's ROVER_SET_ID only). A
/// restarted dl-pose never starts over at start.* as if nothing had happened: on its first
/// usable ddl/imu sample it either resumes from the checkpoint (both filters, the covariance
/// inflated for the gap; heartbeat DEGRADED "restarted: resuming from checkpoint" until then),
/// or, when the checkpoint is older than resume.max_age_s or unreadable, declares the pose
/// unknown: no dl/pose at all, heartbeat FAILED "pose unknown after restart: ...", so nothing
/// drives on it. A checkpoint stamped more than 1 s after the first sample means the run clock
/// went back (a new run): it is ignored and the filter levels as at a first start.
///
/// The IDL conversions are core/msg's (rover/msg/pose_idl.hpp, sensors_idl.hpp). Bad samples
/// never crash the service: FAILED/STALE, non-finite or unreadable samples are dropped (counted
/// in warnings), library errors are logged, and a run-clock reset (a sample more than 1 s older
/// than the filter, e.g. after a simulator reset) restarts the filter and the levelling.

#include <optional>

#include "rover/base/checkpoint.hpp"
#include "rover/dl/pose/pose_estimator.hpp"
#include "rover/runtime/service.hpp"

namespace rover::dl::pose {

class PoseService final : public Service {
 public:
  PoseService() : Service("dl-pose") {}

  void DeclareParameters(ParamSet& params) override;
  Status ValidateParameters(const ParamSet& params) const override;
  Status OnConfigure(ServiceContext& ctx, const ParamSet& params) override;

  /// The filter (for tests); null before configuration.
  const PoseEkf* ekf() const { return estimator_.has_value() ? &estimator_->ekf() : nullptr; }
  /// The IMU + wheel odometry filter (for tests); null before configuration or when disabled.
  const PoseEkf* odometry_only() const {
    return estimator_.has_value() ? estimator_->odometry_only() : nullptr;
  }

 private:
  void OnRelativePose(const rover_dl_RelativePose& m);
  void OnTimer();
  /// Reads this set's checkpoint at configuration: arms the estimator's resume, or declares the
  /// pose unknown on an unreadable one.
  void LoadCheckpoint();
  /// Saves both filters' state when resume.checkpoint_period_s of run time has passed.
  void SaveCheckpointIfDue();
  void PublishEvents();
  void Publish(const PoseEkf& filter, dds::Writer<rover_dl_PoseEstimate>& writer,
               const char* topic);

  ServiceContext* ctx_ = nullptr;
  double imu_stale_s_ = 0.5;
  std::optional<PoseEstimator> estimator_;
  PoseResumeOptions resume_;
  CheckpointStore checkpoints_;          // disabled outside a supervised set
  std::optional<Time> last_checkpoint_;  // filter time of the last save
  dds::Writer<rover_dl_PoseEstimate> pose_writer_;
  dds::Writer<rover_dl_EstimatorEvent> event_writer_;
  dds::Writer<rover_dl_PoseEstimate> odometry_only_writer_;
};

}  // namespace rover::dl::pose
