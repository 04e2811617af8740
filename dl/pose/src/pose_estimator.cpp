#include "rover/dl/pose/pose_estimator.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <utility>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/log.hpp"
#include "rover/base/units.hpp"

namespace rover::dl::pose {

using locomotion::RoverGeometry;
using locomotion::WheelOdometry;
using locomotion::WheelOdometryOptions;

Status PoseFusionOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(gyro_check.Validate());
  return ephemeris.Validate();
}

void PoseFusionOptions::BindParams(ParamBinder<PoseFusionOptions>& b) {
  b.Nest("start.", &PoseFusionOptions::start);
  b.Nest("ephemeris.", &PoseFusionOptions::ephemeris);
  b.Nest("gyro_check.", &PoseFusionOptions::gyro_check);
  b.Bind("ephemeris.run_start_s", &PoseFusionOptions::run_start_s, "s",
         "run-clock time of the run start (0 = sim/clock zero, as the simulator)")
      .Range(-1e11, 1e11);
  b.Bind("sun.enabled", &PoseFusionOptions::sun_enabled, "apply ddl/sun_sensor heading updates");
  b.Bind("odometry_only.enabled", &PoseFusionOptions::odometry_only,
         "also run an IMU + wheel odometry filter (no sun, no visual odometry) and publish it on "
         "dl/pose_odometry, the dead-reckoning baseline");
  b.BindDegrees("sun.min_elevation_deg", &PoseFusionOptions::sun_min_elevation,
                "ignore sun samples when the ephemeris sun is lower than this")
      .Range(-90.0, 90.0);
  b.BindScaled("sun.max_rate_deg_s", &PoseFusionOptions::sun_max_rate, kDegree, "deg/s",
               "ignore sun samples while the rover turns faster than this (a sample's latency "
               "times the turn rate would be a heading error; MER took sun images at rest)")
      .Range(0.0, 100.0);
}

Result<PoseEstimator> PoseEstimator::Create(const EkfOptions& ekf_options,
                                            const RoverGeometry& geometry,
                                            const WheelOdometryOptions& odometry_options,
                                            const PoseFusionOptions& fusion) {
  ROVER_RETURN_IF_ERROR(fusion.Validate());
  ROVER_ASSIGN_OR_RETURN(WheelOdometry odometry, WheelOdometry::Create(geometry, odometry_options));
  ROVER_ASSIGN_OR_RETURN(PoseEkf ekf, PoseEkf::Create(ekf_options));
  ROVER_ASSIGN_OR_RETURN(GyroCheck gyro_check, GyroCheck::Create(fusion.gyro_check));
  std::optional<PoseEkf> odometry_only;
  if (fusion.odometry_only) {
    ROVER_ASSIGN_OR_RETURN(PoseEkf reference, PoseEkf::Create(ekf_options));
    odometry_only.emplace(std::move(reference));
  }
  return PoseEstimator(std::move(ekf), std::move(odometry_only), std::move(odometry),
                       std::move(gyro_check), ekf_options, fusion);
}

PoseEstimator::PoseEstimator(PoseEkf ekf, std::optional<PoseEkf> odometry_only,
                             WheelOdometry odometry, GyroCheck gyro_check,
                             const EkfOptions& ekf_options, const PoseFusionOptions& fusion)
    : ekf_options_(ekf_options),
      fusion_(fusion),
      ekf_(std::move(ekf)),
      odometry_only_(std::move(odometry_only)),
      odometry_(std::move(odometry)),
      gyro_check_(std::move(gyro_check)),
      leveller_(fusion.start, ekf_options),
      ephemeris_(fusion.ephemeris) {}

void PoseEstimator::WarnCounted(const std::string& what, const std::string& detail) {
  const std::uint64_t n = ++warn_counts_[what];
  std::uint64_t p = 1;
  while (p < n) p *= 10;
  if (p == n) log::Warn(what, {{"count", n}, {"detail", detail}});
}

void PoseEstimator::Restart(const std::string& why) {
  log::Info("pose estimator restarted", {{"reason", why}});
  auto ekf = PoseEkf::Create(ekf_options_);
  ROVER_DEMAND(ekf.ok());  // the options were valid at creation
  ekf_ = std::move(*ekf);
  if (odometry_only_) {
    auto reference = PoseEkf::Create(ekf_options_);
    ROVER_DEMAND(reference.ok());
    odometry_only_.emplace(std::move(*reference));
  }
  odometry_.Reset();
  gyro_check_.Reset();
  leveller_.Reset();
}

void PoseEstimator::OnImu(const msg::Imu& imu) {
  if (!msg::IsUsable(imu.health)) {
    WarnCounted("ddl/imu sample dropped: health FAILED or STALE", "");
    return;
  }
  const Time t = imu.stamp;
  const Eigen::Vector3d& w = imu.angular_velocity;
  const Eigen::Vector3d& f = imu.linear_acceleration;
  if (!w.allFinite() || !f.allFinite()) {
    WarnCounted("ddl/imu sample dropped: non-finite value", "");
    return;
  }
  if (ekf_.initialized() && ToSeconds(ekf_.time() - t) > kClockResetS) {
    Restart("ddl/imu stamp " + FormatNumber(t.seconds()) + " s is before the filter time " +
            FormatNumber(ekf_.time().seconds()) + " s (run clock reset)");
  }
  if (unknown_) return;  // nothing to propagate
  if (!ekf_.initialized() && resume_ && !ResumeOrRefuse(t)) return;
  if (!ekf_.initialized()) {
    if (const auto d = leveller_.Add(t, w, f)) Start(*d);
    return;
  }
  const Time before = ekf_.time();
  const Status s = ekf_.PropagateGyro(t, w);
  if (!s.ok()) {
    WarnCounted("ddl/imu sample dropped", s.message());
    return;
  }
  last_rate_ = (w - ekf_.gyro_bias()).norm();
  gyro_check_.AddGyro(t, ToSeconds(t - before), w.z() - ekf_.gyro_bias().z());
  CheckGyro();
  const Status a = ekf_.UpdateAccelerometer(t, f);
  if (!a.ok()) WarnCounted("accelerometer update failed", a.message());
  if (odometry_only_ && odometry_only_->initialized() && odometry_only_->PropagateGyro(t, w).ok()) {
    (void)odometry_only_->UpdateAccelerometer(t, f);
    (void)odometry_only_->TakeEvents();  // its events are not published
  }
}

void PoseEstimator::Start(const StartDecision& d) {
  if (!d.at_rest) {
    log::Warn("no stationary stretch to level on; starting from the mean accelerometer sample",
              {{"samples", d.samples}, {"waited_s", d.waited_s}});
  }
  const Status s = ekf_.Initialize(d.init);
  if (!s.ok()) {
    WarnCounted("pose estimator could not start", s.message());
    return;
  }
  if (odometry_only_) {
    const Status r = odometry_only_->Initialize(d.init);
    ROVER_DEMAND(r.ok());  // the same initial state was just accepted by ekf_
  }
  log::Info("pose estimator started",
            {{"how", d.at_rest ? "levelled at rest" : "not levelled at rest"},
             {"t_s", d.init.stamp.seconds()},
             {"roll_deg", d.roll_pitch.x() / kDegree},
             {"pitch_deg", d.roll_pitch.y() / kDegree},
             {"yaw_deg", fusion_.start.yaw / kDegree},
             {"gyro_bias_z", d.init.gyro_bias.z()},
             {"gyro_bias_sigma", d.init.gyro_bias_sigma}});
}

void PoseEstimator::ResumeFrom(const PoseCheckpoint& checkpoint,
                               const PoseResumeOptions& options) {
  ROVER_DEMAND(!ekf_.initialized());
  resume_ = checkpoint;
  resume_options_ = options;
}

void PoseEstimator::DeclareUnknown(const std::string& why) {
  resume_.reset();
  unknown_ = why;
  log::Error("pose unknown: dl/pose not published", {{"reason", why}});
}

PoseCheckpoint PoseEstimator::Checkpoint() const {
  ROVER_DEMAND(ekf_.initialized());
  PoseCheckpoint c;
  c.main = SavedFilterOf(ekf_.Estimate());
  if (odometry_only_ && odometry_only_->initialized()) {
    c.odometry_only = SavedFilterOf(odometry_only_->Estimate());
  }
  return c;
}

bool PoseEstimator::ResumeOrRefuse(Time t) {
  const PoseCheckpoint saved = *resume_;
  resume_.reset();
  const double gap = ToSeconds(t - saved.main.stamp);
  if (gap < -kClockResetS) {
    // The run clock is behind the checkpoint: a new run (simulator reset), not a restart.
    log::Info("checkpoint is from a later run time: starting afresh",
              {{"checkpoint_t_s", saved.main.stamp.seconds()}, {"t_s", t.seconds()}});
    return true;
  }
  if (gap > resume_options_.max_age_s) {
    DeclareUnknown("pose unknown after restart: the last checkpoint (t = " +
                   FormatNumber(saved.main.stamp.seconds()) + " s) is " + FormatNumber(gap) +
                   " s old, more than resume.max_age_s " + FormatNumber(resume_options_.max_age_s) +
                   " s");
    return false;
  }
  const double bias_sigma = fusion_.start.gyro_bias_sigma;
  const Status s =
      ekf_.Initialize(ResumedInitialState(saved.main, t, resume_options_, bias_sigma));
  if (!s.ok()) {
    DeclareUnknown("pose unknown after restart: checkpoint rejected: " + s.message());
    return false;
  }
  if (odometry_only_) {
    // Without its own (usable) checkpoint the baseline resumes from the main filter's.
    Status r = odometry_only_->Initialize(ResumedInitialState(
        saved.odometry_only.value_or(saved.main), t, resume_options_, bias_sigma));
    if (!r.ok()) {
      WarnCounted("odometry-only checkpoint rejected; resuming it from dl/pose's", r.message());
      r = odometry_only_->Initialize(ResumedInitialState(saved.main, t, resume_options_,
                                                         bias_sigma));
    }
    ROVER_DEMAND(r.ok());  // the main filter accepted this state
  }
  leveller_.Reset();
  log::Info("pose estimator resumed from checkpoint",
            {{"checkpoint_t_s", saved.main.stamp.seconds()}, {"t_s", t.seconds()}, {"gap_s", gap}});
  return true;
}

Status PoseEstimator::OnJointState(const msg::JointState& joints) {
  if (!msg::IsUsable(joints.health)) {
    WarnCounted("ddl/joint_state sample dropped: health FAILED or STALE", "");
    return Status::Ok();
  }
  auto inc = odometry_.Add(joints);
  if (!inc.ok()) {
    WarnCounted("ddl/joint_state sample rejected by wheel odometry", inc.status().message());
    return inc.status();
  }
  if (!ekf_.initialized() || !inc->has_value() || unknown_) return Status::Ok();
  const Status s = ekf_.AddWheelOdometry(**inc);
  if (!s.ok()) WarnCounted("wheel odometry increment rejected", s.message());
  if (odometry_only_ && odometry_only_->initialized()) {
    (void)odometry_only_->AddWheelOdometry(**inc);
  }
  const locomotion::OdometryIncrement& i = **inc;
  gyro_check_.AddOdometry(i.t_from, i.t_to, i.dyaw);
  CheckGyro();
  return Status::Ok();
}

void PoseEstimator::CheckGyro() {
  if (unknown_ || !gyro_check_.failure()) return;
  DeclareUnknown("gyro fault: " + gyro_check_.failure()->reason);
}

void PoseEstimator::OnSunSensor(const msg::SunSensor& m) {
  if (!fusion_.sun_enabled || !m.valid || !msg::IsUsable(m.health) || !ekf_.initialized()) return;
  const geometry::SunState sun = ephemeris_.At(m.stamp.seconds() - fusion_.run_start_s);
  if (sun.elevation_rad < fusion_.sun_min_elevation) return;
  if (last_rate_ > fusion_.sun_max_rate) return;  // turning: wait for a steadier sample
  const Status s = ekf_.UpdateSunSensor(m.stamp, m.sun_vector, sun.direction_site);
  if (!s.ok()) WarnCounted("ddl/sun_sensor sample rejected", s.message());
}

void PoseEstimator::OnRelativePose(const msg::RelativePose& r) {
  const Status s = ekf_.AddRelativePose(r);
  if (!s.ok()) RejectRelativePose(r.source, r.t_to, s.message());
}

void PoseEstimator::RejectRelativePose(MotionSource source, Time t_to, const std::string& why) {
  WarnCounted("relative pose rejected as bad input", why);
  EstimatorEvent e;
  e.stamp = t_to;
  e.source = source;
  e.accepted = false;
  e.mahalanobis_sq = std::numeric_limits<double>::quiet_NaN();
  e.gate = 0.0;
  e.message = "relative pose rejected: " + why;
  rejected_.push_back(std::move(e));
}

std::vector<EstimatorEvent> PoseEstimator::TakeEvents() {
  std::vector<EstimatorEvent> out = ekf_.TakeEvents();
  for (EstimatorEvent& e : rejected_) out.push_back(std::move(e));
  rejected_.clear();
  return out;
}

}  // namespace rover::dl::pose
