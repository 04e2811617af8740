// dl-vo: binds MER visual odometry (dl_vo) to dl/pose, ddl/camera_request, ddl/stereo_frame and
// dl/relative_pose. See vo_service.hpp and docs/services/dl-vo.md.
#include "vo_service.hpp"

#include <algorithm>

#include "rover/msg/camera_idl.hpp"
#include "rover/msg/health_idl.hpp"
#include "rover/msg/pose_idl.hpp"

namespace rover::dl::vo {

Status VoService::ValidateParameters(const ParamSet& p) const {
  return ReadParams<VoServiceOptions>(p, "").status();
}

void VoService::DeclareParameters(ParamSet& p) { DeclareParams<VoServiceOptions>(p, ""); }

Status VoService::OnConfigure(ServiceContext& ctx, const ParamSet& p) {
  ctx_ = &ctx;
  ROVER_ASSIGN_OR_RETURN(options_, ReadParams<VoServiceOptions>(p, ""));
  cadence_ = std::make_unique<VoCadence>(options_.cadence);
  client_ = std::make_unique<camera_client::CameraRequestClient>(options_.Client());
  pipeline_ = std::make_unique<VoPipeline>(options_.pipeline);
  // Poses for the longest gap between two pairs (interval or timeout) at >= 8 Hz, and more.
  poses_ = msg::PoseHistory(static_cast<std::size_t>(std::max(
      256.0, 20.0 * (options_.cadence.max_interval_s + options_.client.request_timeout_s))));

  ROVER_ASSIGN_OR_RETURN(request_writer_,
                         ctx.MakeWriter<rover_ddl_StereoRequest>("ddl/camera_request"));
  ROVER_ASSIGN_OR_RETURN(relpose_writer_,
                         ctx.MakeWriter<rover_dl_RelativePose>("dl/relative_pose"));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_PoseEstimate>(
      "dl/pose",
      [this](const dds::Sample<rover_dl_PoseEstimate>& s) { return OnPose(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_VoCommand>(
      "dl/vo_command",
      [this](const dds::Sample<rover_dl_VoCommand>& s) { return OnVoCommand(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_StereoFrame>(
      "ddl/stereo_frame",
      [this](const dds::Sample<rover_ddl_StereoFrame>& s) { OnStereoFrame(s.data()); }));
  ctx.executor().AddTimer(Seconds(1.0 / options_.poll_rate_hz), [this] { OnTimer(); });
  ctx.SetHealth(rover_HEALTH_DEGRADED, "no dl/pose received yet: visual odometry waiting");
  return Status::Ok();
}

// ---- inputs -----------------------------------------------------------------------------------

Status VoService::OnPose(const rover_dl_PoseEstimate& m) {
  auto sample = msg::PoseSampleFromIdl(m);
  if (!sample.ok()) return sample.status();  // on sys/health through the input monitor
  Status s = poses_.Add(*sample);
  if (s.code() == StatusCode::kOutOfRange &&
      poses_.WentBackBy(sample->stamp, Seconds(camera_client::kClockResetS))) {
    ResetAll("dl/pose went back in time (run-clock reset)");
    s = poses_.Add(*sample);
  }
  if (!s.ok()) {
    log::Debug("dl/pose sample dropped", {{"reason", s.message()}});
    return Status::Ok();  // readable but out of order: not a rejection
  }
  cadence_->OnPose(sample->stamp, sample->odometer, sample->velocity.norm(),
                   Eigen::Quaterniond(sample->site_from_rover.linear()), sample->stationary);
  return Status::Ok();
}

Status VoService::OnVoCommand(const rover_dl_VoCommand& m) {
  auto c = msg::VoCommandFromIdl(m);
  if (!c.ok()) {
    ++stats_.rejected_commands;
    return c.status();  // on sys/health through the input monitor
  }
  const bool was = imaging();
  if (c->imaging) {
    clients_.insert(c->client);
  } else {
    clients_.erase(c->client);
  }
  if (imaging() == was) return Status::Ok();
  // Imaging starts or stops: the chain restarts with a new reference pair, since the rover
  // moved without VO in between (poses are kept: they are the estimator's, not VO's).
  cadence_->Reset();
  pipeline_->Reset();
  (void)client_->Reset();
  log::Info(imaging() ? "visual odometry imaging on" : "visual odometry imaging off",
            {{"client", c->client}, {"clients", static_cast<std::uint64_t>(clients_.size())}});
  return Status::Ok();
}

void VoService::OnTimer() {
  const Time now = ctx_->Now();
  if (client_->ClockWentBack(now)) ResetAll("the run clock went back");
  if (const auto o = client_->Expire(now)) {
    ++stats_.timeouts;
    Problem("ddl/camera_request timed out", {{"camera_request_id", o->request_id},
                                             {"camera", msg::CameraName(options_.camera)},
                                             {"timeout_s", client_->options().request_timeout_s}});
  }
  MaybeRequest(now);
  UpdateHealth();
}

void VoService::MaybeRequest(Time now) {
  if (!imaging() || !client_->Ready(now)) return;
  const auto latest = poses_.Latest();
  if (!latest.has_value() || ToSeconds(now - latest->stamp) > options_.pose_max_age_s) return;
  const VoCadence::Reason reason = cadence_->Due(now);
  if (reason == VoCadence::Reason::kNone) return;
  const msg::StereoRequest r =
      client_->Issue(now, options_.camera, options_.width, static_cast<std::uint32_t>(reason));
  rover_ddl_StereoRequest m{};
  ctx_->Stamp(m.header, "rover");
  msg::StereoRequestToIdl(r, &m);
  const Status s = request_writer_.Write(m);
  if (!s.ok()) {
    client_->SendFailed(now);
    Problem("ddl/camera_request write failed", {{"error", s.message()}});
    return;
  }
  ++stats_.camera_requests;
  log::Debug("vo pair requested", {{"camera_request_id", r.request_id},
                                   {"reason", CadenceReasonName(reason)},
                                   {"odometer", latest->odometer}});
}

void VoService::OnStereoFrame(const rover_ddl_StereoFrame& m) {
  const auto o = client_->Answer(m.request_id);
  if (!o.has_value()) return;  // not ours
  ++stats_.frames;
  Status s;
  {
    runtime::ScopedActivity vo(ctx_->activities(), "vo");
    s = Process(*o, m);
  }
  if (!s.ok()) {
    ++stats_.bad_frames;
    client_->Failed(ctx_->Now());
    Problem("ddl/stereo_frame dropped", {{"camera_request_id", o->request_id},
                                         {"camera", msg::CameraName(options_.camera)},
                                         {"reason", s.message()}});
    const auto bad =
        pipeline_->BadInput(Time{m.header.stamp_ns}, poses_, Seconds(options_.pose_max_age_s));
    if (bad.has_value()) Publish(*bad);
  }
  UpdateHealth();
}

// ---- processing -------------------------------------------------------------------------------

Status VoService::Process(const camera_client::Outstanding& o, const rover_ddl_StereoFrame& m) {
  ROVER_ASSIGN_OR_RETURN(const msg::StereoFrame frame, msg::StereoFrameFromIdl(m));
  ROVER_RETURN_IF_ERROR(client_->Check(o, frame));
  ROVER_ASSIGN_OR_RETURN(const VoPipeline::Step step,
                         pipeline_->Process(frame, poses_, Seconds(options_.pose_max_age_s)));
  client_->Accepted(frame.stamp);
  if (step.mark.has_value()) {
    cadence_->MarkCaptured(frame.stamp, step.mark->odometer,
                           Eigen::Quaterniond(step.mark->site_from_rover.linear()));
  }
  const MotionEstimate& est = step.estimate;
  const char* reason = CadenceReasonName(static_cast<VoCadence::Reason>(o.tag));
  if (!step.relative_pose.has_value()) {
    ++stats_.references;
    health_.Clear();
    log::Info(
        "visual odometry reference pair",
        {{"t_s", frame.stamp.seconds()}, {"features", est.features_selected}, {"reason", reason}});
    return Status::Ok();
  }
  Publish(*step.relative_pose);
  if (est.converged()) {
    ++stats_.converged;
    health_.Clear();
    log::Info("visual odometry step", {{"dx", est.delta.translation().x()},
                                       {"dy", est.delta.translation().y()},
                                       {"dz", est.delta.translation().z()},
                                       {"inliers", est.inliers},
                                       {"reason", reason}});
  } else {
    Problem("visual odometry step failed", {{"status", MotionStatusName(est.status)},
                                            {"reason", est.message},
                                            {"features", est.features_tracked}});
  }
  return Status::Ok();
}

// ---- outputs and health -----------------------------------------------------------------------

void VoService::Publish(const msg::RelativePose& r) {
  rover_dl_RelativePose m{};
  ctx_->Stamp(m.header, "rover");
  msg::RelativePoseToIdl(r, &m);
  const Status s = relpose_writer_.Write(m);
  if (!s.ok()) {
    Problem("dl/relative_pose write failed", {{"error", s.message()}});
    return;
  }
  ++stats_.published;
}

void VoService::Problem(const std::string& problem, std::initializer_list<log::Field> fields) {
  log::Warn(problem, fields);
  health_.Latch(problem, fields, {"reason", "status"});
  UpdateHealth();
}

void VoService::UpdateHealth() {
  msg::HealthReport inputs;
  const auto latest = poses_.Latest();
  if (!latest.has_value() || ctx_->clock().valid()) {  // the age needs a valid clock
    inputs = msg::FreshnessReport("dl/pose", latest ? std::optional(latest->stamp) : std::nullopt,
                                  ctx_->Now(), options_.pose_max_age_s, ": visual odometry waiting",
                                  ": visual odometry paused");
  }
  const msg::HealthReport h = health_.Report(inputs);
  ctx_->SetHealth(msg::HealthToIdl(h.health), h.reason);
}

void VoService::ResetAll(const std::string& why) {
  log::Info("visual odometry restarted", {{"reason", why}});
  poses_.Clear();
  cadence_->Reset();
  pipeline_->Reset();
  (void)client_->Reset();
}

}  // namespace rover::dl::vo
