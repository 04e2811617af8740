#pragma once
/// @file
/// PoseEstimator: everything dl-pose does between its topics, DDS-free and clock-free (every
/// input carries its time of validity). It owns
///   * the pose filter (PoseEkf) fed by the IMU (gyro propagation; accelerometer when at rest),
///     wheel odometry (dl_locomotion's WheelOdometry between consecutive usable joint states),
///     the sun sensor and relative poses (visual odometry);
///   * optionally a second filter fed only the IMU and wheel odometry (odometry_only: MER's
///     "IMU + wheel odometry" dead reckoning, published on dl/pose_odometry);
///   * the start-up (Leveller, pose_startup.hpp): nothing is estimated until the filter is
///     levelled, and a sample more than kClockResetS older than the filter (the run clock went
///     back: a simulator reset) restarts both filters, the odometry and the levelling;
///   * the gyro check (gyro_check.hpp): the bias-corrected gyro yaw rate against wheel
///     odometry's; when it fails the pose is declared unknown (a gyro that turns the heading
///     by itself makes every later pose wrong, and nothing may drive on it);
///   * the restart after a crash (pose_resume.hpp): armed with a checkpoint (ResumeFrom), the
///     first usable IMU sample resumes both filters from it, inflated for the gap, or declares
///     the pose unknown when it is too old; a pose declared unknown is never estimated again
///     (nothing may drive on it: the set must be restarted or the pose set by an operator).
///
/// Sun updates: the sun direction in the site frame comes from the Mars ephemeris
/// (core/geometry mars_sun.hpp) at run time t - run_start_s. A sample is used only when it is
/// valid and usable, the ephemeris sun is at least sun_min_elevation high, and the rover turns
/// no faster than sun_max_rate (|bias-corrected gyro| of the last IMU sample): a sample's
/// latency times the turn rate would be a heading error (MER took sun images at rest).
///
/// Bad samples never stop it: FAILED/STALE or non-finite samples are dropped, library errors
/// are warnings (rover::log; a repeated one is logged at its 1st, 10th, 100th, ... occurrence)
/// and relative poses the filter refuses become rejected events (d^2 NaN).

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/dl/locomotion/wheel_odometry.hpp"
#include "rover/dl/pose/gyro_check.hpp"
#include "rover/dl/pose/pose_ekf.hpp"
#include "rover/dl/pose/pose_resume.hpp"
#include "rover/dl/pose/pose_startup.hpp"
#include "rover/geometry/mars_sun.hpp"
#include "rover/msg/pose.hpp"
#include "rover/msg/sensors.hpp"

namespace rover::dl::pose {

/// A sample this much older than the filter means the run clock went back [s].
inline constexpr double kClockResetS = 1.0;

/// Keys start.*, ephemeris.*, sun.* and odometry_only.enabled of dl-pose.
struct PoseFusionOptions {
  PoseStartOptions start;
  /// Same keys and defaults as the simulator's sensors.ephemeris.* (sim/sensors).
  geometry::SunEphemerisOptions ephemeris;
  double run_start_s = 0.0;  ///< [s] run-clock time of the ephemeris' run start
  bool sun_enabled = true;
  double sun_min_elevation = 0.0;                              ///< [rad]
  double sun_max_rate = 0.2 * 3.14159265358979323846 / 180.0;  ///< [rad/s]
  bool odometry_only = true;  ///< also run the IMU + wheel odometry filter
  GyroCheckOptions gyro_check;  ///< gyro against wheel odometry (gyro_check.hpp)

  /// The ephemeris options' checks.
  Status Validate() const;
  static void BindParams(ParamBinder<PoseFusionOptions>& b);
};

class PoseEstimator {
 public:
  /// Errors: invalid EKF options, geometry or odometry options, ephemeris.
  static Result<PoseEstimator> Create(const EkfOptions& ekf,
                                      const locomotion::RoverGeometry& geometry,
                                      const locomotion::WheelOdometryOptions& odometry,
                                      const PoseFusionOptions& fusion);

  /// ddl/imu: levelling until the filter runs, then gyro propagation and (at rest) an
  /// accelerometer update of both filters.
  void OnImu(const msg::Imu& imu);
  /// ddl/joint_state: a wheel-odometry increment for both filters. Returns the wheel
  /// odometry's refusal of an implausible sample (a jump no wheel can make), which the service
  /// reports as a rejected input; OK otherwise (also for samples it merely drops).
  Status OnJointState(const msg::JointState& joints);
  /// ddl/sun_sensor: a heading update of the main filter (see the file comment).
  void OnSunSensor(const msg::SunSensor& sun);
  /// dl/relative_pose with status CONVERGED: a measurement of the main filter (refused ones
  /// become rejected events).
  void OnRelativePose(const msg::RelativePose& relative_pose);
  /// A relative pose that could not be read (`why`): a rejected event at `t_to`, d^2 NaN.
  void RejectRelativePose(MotionSource source, Time t_to, const std::string& why);
  /// Logs `what` (with `detail`) at its 1st, 10th, 100th, ... occurrence (e.g. a dropped sample
  /// that could not be converted).
  void WarnCounted(const std::string& what, const std::string& detail);

  /// The main filter's events since the last call (gated measurements and rejected inputs),
  /// oldest first. The odometry-only filter's are discarded.
  std::vector<EstimatorEvent> TakeEvents();

  /// Both filters, the odometry and the levelling start over (`why` is logged).
  void Restart(const std::string& why);

  /// After a restart: resume from `checkpoint` on the first usable IMU sample instead of
  /// levelling (see pose_resume.hpp). Precondition: not started.
  void ResumeFrom(const PoseCheckpoint& checkpoint, const PoseResumeOptions& options);
  /// The pose is unknown (`why`, e.g. an unreadable checkpoint): nothing is estimated any more.
  void DeclareUnknown(const std::string& why);
  /// Why the pose is unknown after a restart; nullopt when it is known or being levelled.
  const std::optional<std::string>& pose_unknown() const { return unknown_; }
  /// Armed with a checkpoint that the first IMU sample will resume from.
  bool resuming() const { return resume_.has_value(); }
  /// Both filters' state to checkpoint. Precondition: started().
  PoseCheckpoint Checkpoint() const;

  bool started() const { return ekf_.initialized(); }
  const PoseEkf& ekf() const { return ekf_; }
  /// The IMU + wheel odometry filter; null when odometry_only is off.
  const PoseEkf* odometry_only() const {
    return odometry_only_.has_value() ? &*odometry_only_ : nullptr;
  }
  const PoseFusionOptions& options() const { return fusion_; }
  const GyroCheck& gyro_check() const { return gyro_check_; }

 private:
  PoseEstimator(PoseEkf ekf, std::optional<PoseEkf> odometry_only,
                locomotion::WheelOdometry odometry, GyroCheck gyro_check,
                const EkfOptions& ekf_options, const PoseFusionOptions& fusion);
  void Start(const StartDecision& d);
  /// On the first usable sample at `t` after a restart; false when the pose became unknown.
  bool ResumeOrRefuse(Time t);
  /// A failed gyro check declares the pose unknown (once).
  void CheckGyro();

  EkfOptions ekf_options_;
  PoseFusionOptions fusion_;
  PoseEkf ekf_;
  std::optional<PoseEkf> odometry_only_;
  locomotion::WheelOdometry odometry_;
  GyroCheck gyro_check_;
  Leveller leveller_;
  geometry::SunEphemeris ephemeris_;
  double last_rate_ = 0.0;                // [rad/s] |bias-corrected gyro| of the last IMU sample
  std::vector<EstimatorEvent> rejected_;  // rejected inputs not yet taken
  std::map<std::string, std::uint64_t> warn_counts_;
  std::optional<PoseCheckpoint> resume_;  // armed by ResumeFrom, used by the first IMU sample
  PoseResumeOptions resume_options_;
  std::optional<std::string> unknown_;    // why the pose is unknown after a restart
};

}  // namespace rover::dl::pose
