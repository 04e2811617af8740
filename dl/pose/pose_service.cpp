// dl-pose: binds PoseEstimator to ddl/imu, ddl/joint_state, ddl/sun_sensor and
// dl/relative_pose; publishes dl/pose, dl/pose_odometry and dl/estimator_event. See
// pose_service.hpp and docs/services/dl-pose.md.
#include "pose_service.hpp"

#include "rover/base/format.hpp"
#include "rover/base/log.hpp"
#include "rover/msg/pose_idl.hpp"
#include "rover/msg/sensors_idl.hpp"

namespace rover::dl::pose {

using locomotion::DeclareRoverGeometryParams;
using locomotion::DeclareWheelOdometryParams;
using locomotion::RoverGeometry;
using locomotion::RoverGeometryFromParams;
using locomotion::WheelOdometryOptions;
using locomotion::WheelOdometryOptionsFromParams;

namespace {

// [m/s^2] default of ekf.gravity: Mars, as the simulator's rover model (sim/physics).
constexpr double kMarsGravity = 3.711;

struct Config {
  EkfOptions ekf;
  RoverGeometry geometry;
  WheelOdometryOptions odometry;
  PoseFusionOptions fusion;
  PoseResumeOptions resume;
};

Result<Config> ConfigFromParams(const ParamSet& p) {
  Config c;
  ROVER_ASSIGN_OR_RETURN(c.ekf, EkfOptionsFromParams(p, "ekf."));
  ROVER_ASSIGN_OR_RETURN(c.geometry, RoverGeometryFromParams(p, "geometry."));
  ROVER_ASSIGN_OR_RETURN(c.odometry, WheelOdometryOptionsFromParams(p, "odometry."));
  ROVER_ASSIGN_OR_RETURN(c.fusion, ReadParams<PoseFusionOptions>(p, ""));
  ROVER_ASSIGN_OR_RETURN(c.resume, ReadParams<PoseResumeOptions>(p, "resume."));
  return c;
}

// Hands a converted sample to the estimator, or counts it as dropped; returns the conversion's
// status (the input monitor's verdict on the sample).
template <class T, class F>
Status Forward(PoseEstimator& estimator, const char* topic, const Result<T>& sample, F&& use) {
  if (sample.ok()) {
    use(*sample);
  } else {
    estimator.WarnCounted(std::string(topic) + " sample dropped: unreadable",
                          sample.status().message());
  }
  return sample.status();
}

}  // namespace

void PoseService::DeclareParameters(ParamSet& p) {
  EkfOptions ekf_defaults;
  ekf_defaults.gravity = kMarsGravity;  // the rover is on Mars (and so is the simulated one)
  DeclareEkfParams(p, "ekf.", ekf_defaults);
  DeclareRoverGeometryParams(p, "geometry.");
  DeclareWheelOdometryParams(p, "odometry.");
  DeclareParams<PoseFusionOptions>(p, "");
  DeclareParams<PoseResumeOptions>(p, "resume.");
  p.Declare("publish_rate_hz", 10.0, "[Hz] dl/pose rate (run clock)").Range(8.0, 200.0);
  p.Declare("imu_stale_s", 0.5, "[s] without ddl/imu before the heartbeat reports DEGRADED")
      .Range(0.01, 60.0);
}

Status PoseService::ValidateParameters(const ParamSet& p) const {
  return ConfigFromParams(p).status();
}

Status PoseService::OnConfigure(ServiceContext& ctx, const ParamSet& p) {
  ctx_ = &ctx;
  ROVER_ASSIGN_OR_RETURN(const Config c, ConfigFromParams(p));
  ROVER_ASSIGN_OR_RETURN(PoseEstimator estimator,
                         PoseEstimator::Create(c.ekf, c.geometry, c.odometry, c.fusion));
  estimator_.emplace(std::move(estimator));
  imu_stale_s_ = p.GetDouble("imu_stale_s");
  resume_ = c.resume;
  if (resume_.enabled) checkpoints_ = CheckpointStore::FromEnvironment(ctx.name());
  LoadCheckpoint();

  ROVER_ASSIGN_OR_RETURN(pose_writer_, ctx.MakeWriter<rover_dl_PoseEstimate>("dl/pose"));
  ROVER_ASSIGN_OR_RETURN(event_writer_,
                         ctx.MakeWriter<rover_dl_EstimatorEvent>("dl/estimator_event"));
  if (c.fusion.odometry_only) {
    ROVER_ASSIGN_OR_RETURN(odometry_only_writer_,
                           ctx.MakeWriter<rover_dl_PoseEstimate>("dl/pose_odometry"));
  }

  ROVER_RETURN_IF_ERROR(
      ctx.Subscribe<rover_ddl_Imu>("ddl/imu", [this](const dds::Sample<rover_ddl_Imu>& s) {
        const Status read = Forward(*estimator_, "ddl/imu", msg::ImuFromIdl(s.data()),
                                    [this](const msg::Imu& imu) { estimator_->OnImu(imu); });
        PublishEvents();
        return read;
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_JointState>(
      "ddl/joint_state", [this](const dds::Sample<rover_ddl_JointState>& s) {
        // A sample the wheel odometry refuses (a jump no wheel can make) is a rejected input.
        Status used = Status::Ok();
        const Status read =
            Forward(*estimator_, "ddl/joint_state", msg::JointStateFromIdl(s.data()),
                    [&](const msg::JointState& j) { used = estimator_->OnJointState(j); });
        return read.ok() ? used : read;
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_SunSensor>(
      "ddl/sun_sensor", [this](const dds::Sample<rover_ddl_SunSensor>& s) {
        const auto sun = msg::SunSensorFromIdl(s.data());
        if (sun.ok()) estimator_->OnSunSensor(*sun);  // an unreadable one is not a measurement
        PublishEvents();
        return sun.status();
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_RelativePose>(
      "dl/relative_pose",
      [this](const dds::Sample<rover_dl_RelativePose>& s) { return OnRelativePose(s.data()); }));
  ctx.executor().AddTimer(Seconds(1.0 / p.GetDouble("publish_rate_hz")), [this] { OnTimer(); });
  OnTimer();  // the first heartbeat's health
  return Status::Ok();
}

void PoseService::LoadCheckpoint() {
  const auto loaded = checkpoints_.Load();
  if (!loaded.ok()) {
    estimator_->DeclareUnknown("pose unknown after restart: " + loaded.status().message());
    return;
  }
  if (!loaded->has_value()) return;  // a first start in this set
  const auto checkpoint = PoseCheckpointFromFields(**loaded);
  if (!checkpoint.ok()) {
    estimator_->DeclareUnknown("pose unknown after restart: checkpoint " + checkpoints_.path() +
                               ": " + checkpoint.status().message());
    return;
  }
  log::Info("restarted: checkpoint found",
            {{"path", checkpoints_.path()}, {"t_s", checkpoint->main.stamp.seconds()}});
  estimator_->ResumeFrom(*checkpoint, resume_);
}

void PoseService::SaveCheckpointIfDue() {
  if (!checkpoints_.enabled()) return;
  const Time t = estimator_->ekf().time();
  if (last_checkpoint_ && t >= *last_checkpoint_ &&
      ToSeconds(t - *last_checkpoint_) < resume_.checkpoint_period_s) {
    return;
  }
  const Status s = checkpoints_.Save(CheckpointFields(estimator_->Checkpoint()));
  if (!s.ok()) estimator_->WarnCounted("checkpoint not written", s.message());
  last_checkpoint_ = t;
}

Status PoseService::OnRelativePose(const rover_dl_RelativePose& m) {
  if (m.status != rover_dl_RELPOSE_CONVERGED) return Status::Ok();  // not a measurement
  const auto r = msg::RelativePoseFromIdl(m);
  if (r.ok()) {
    estimator_->OnRelativePose(*r);
  } else {
    const auto source = msg::MotionSourceFromIdl(m.source);
    estimator_->RejectRelativePose(source.ok() ? *source : MotionSource::kExternal, Time{m.t_to_ns},
                                   r.status().message());
  }
  PublishEvents();
  return r.status();
}

void PoseService::PublishEvents() {
  for (const EstimatorEvent& e : estimator_->TakeEvents()) {
    rover_dl_EstimatorEvent m{};
    ctx_->Stamp(m.header, "site");
    msg::EstimatorEventToIdl(e, &m);
    const Status s = event_writer_.Write(m);
    if (!s.ok()) estimator_->WarnCounted("dl/estimator_event write failed", s.message());
  }
}

void PoseService::Publish(const PoseEkf& filter, dds::Writer<rover_dl_PoseEstimate>& writer,
                          const char* topic) {
  rover_dl_PoseEstimate m{};
  ctx_->Stamp(m.header, "site");
  msg::PoseEstimateToIdl(filter.Estimate(), &m);  // stamp = the filter's time of validity
  const Status s = writer.Write(m);
  if (!s.ok()) estimator_->WarnCounted(std::string(topic) + " write failed", s.message());
}

void PoseService::OnTimer() {
  if (const auto& why = estimator_->pose_unknown()) {
    ctx_->SetHealth(rover_HEALTH_FAILED, *why);
    return;
  }
  if (!estimator_->started()) {
    ctx_->SetHealth(rover_HEALTH_DEGRADED,
                    estimator_->resuming() ? "restarted: resuming from checkpoint"
                                           : "levelling: waiting for stationary ddl/imu samples");
    return;
  }
  Publish(estimator_->ekf(), pose_writer_, "dl/pose");
  const PoseEkf* odometry_only = estimator_->odometry_only();
  if (odometry_only != nullptr && odometry_only->initialized()) {
    Publish(*odometry_only, odometry_only_writer_, "dl/pose_odometry");
  }
  SaveCheckpointIfDue();
  const double age = ToSeconds(ctx_->Now() - estimator_->ekf().time());
  if (age > imu_stale_s_) {
    ctx_->SetHealth(rover_HEALTH_DEGRADED, "no ddl/imu for " + FormatNumber(age) + " s");
  } else {
    ctx_->SetHealth(rover_HEALTH_OK, "");
  }
}

}  // namespace rover::dl::pose
