// dl-stereo: binds the stereo ranger (dl_stereo) to dl/range_request, ddl/camera_request,
// ddl/stereo_frame, dl/pose and dl/range_image. See stereo_service.hpp and
// docs/services/dl-stereo.md.
#include "stereo_service.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "rover/msg/camera_idl.hpp"
#include "rover/msg/health_idl.hpp"
#include "rover/msg/pose_idl.hpp"
#include "rover/msg/range_idl.hpp"

namespace rover::dl::stereo {
namespace {

using camera_client::CameraClientOptions;

}  // namespace

Status StereoService::ValidateParameters(const ParamSet& p) const {
  ROVER_RETURN_IF_ERROR(ReadParams<CameraClientOptions>(p, "").status());
  ROVER_RETURN_IF_ERROR(ReadParams<hwconfig::RoverDescription>(p, "geometry.").status());
  ROVER_RETURN_IF_ERROR(ReadParams<VehicleMaskOptions>(p, "vehicle_mask.").status());
  return ReadParams<StereoRangerOptions>(p, "").status();
}

void StereoService::DeclareParameters(ParamSet& p) {
  p.Declare("default_width", 256,
            "[px] processing width asked of the camera driver when dl/range_request.width is 0 "
            "(0 = full sensor size; MER ranged 256 px wide images)")
      .Range(0, 4096);
  DeclareParams<CameraClientOptions>(p, "");
  DeclareParams<StereoRangerOptions>(p, "");
  DeclareParams<VehicleMaskOptions>(p, "vehicle_mask.");
  DeclareParams<hwconfig::RoverDescription>(p, "geometry.");
  p.Declare("max_queue", 4, "range requests waiting behind the outstanding one, at most")
      .Range(1, 64);
  p.Declare("pose_max_age_s", 1.0,
            "[s] the dl/pose estimate used for rover_pose must lie within this of the capture "
            "time; also the age after which dl/pose counts as stale for the health")
      .Range(0.01, 60.0);
  p.Declare("require_pose", true,
            "true: no range image without a dl/pose estimate at the capture time; false: send "
            "it with an identity rover_pose (and a warning)");
  p.Declare("poll_rate_hz", 10.0, "[Hz] run-clock rate of the timeout and health checks")
      .Range(1.0, 100.0);
}

Status StereoService::OnConfigure(ServiceContext& ctx, const ParamSet& p) {
  ctx_ = &ctx;
  default_width_ = static_cast<int>(p.GetInt("default_width"));
  max_queue_ = static_cast<std::size_t>(p.GetInt("max_queue"));
  pose_max_age_s_ = p.GetDouble("pose_max_age_s");
  require_pose_ = p.GetBool("require_pose");
  ROVER_ASSIGN_OR_RETURN(const CameraClientOptions client, ReadParams<CameraClientOptions>(p, ""));
  ROVER_ASSIGN_OR_RETURN(const StereoRangerOptions ranger, ReadParams<StereoRangerOptions>(p, ""));
  client_ = std::make_unique<camera_client::CameraRequestClient>(client);
  ROVER_ASSIGN_OR_RETURN(const hwconfig::RoverDescription rover,
                         ReadParams<hwconfig::RoverDescription>(p, "geometry."));
  ROVER_ASSIGN_OR_RETURN(const VehicleMaskOptions mask,
                         ReadParams<VehicleMaskOptions>(p, "vehicle_mask."));
  ranger_ = std::make_unique<StereoRanger>(ranger, VehicleMask(rover, mask));
  const std::pair<msg::CameraId, std::string> pixel_masks[] = {
      {msg::CameraId::kFrontHazcam, mask.front_hazcam_pixels},
      {msg::CameraId::kRearHazcam, mask.rear_hazcam_pixels},
      {msg::CameraId::kNavcam, mask.navcam_pixels}};
  for (const auto& [camera, path] : pixel_masks) {
    if (path.empty()) continue;
    const std::string key = std::string("vehicle_mask.") + msg::CameraName(camera) + "_pixels";
    auto pixels = LoadPixelMask(path);
    if (!pixels.ok()) return pixels.status().WithPrefix(key);
    ROVER_RETURN_IF_ERROR(ranger_->SetPixelMask(camera, std::move(*pixels)).WithPrefix(key));
  }
  // Enough dl/pose history to cover a request that takes the whole timeout (>= 8 Hz poses).
  poses_ =
      msg::PoseHistory(static_cast<std::size_t>(std::max(64.0, 50.0 * client.request_timeout_s)));

  ROVER_ASSIGN_OR_RETURN(request_writer_,
                         ctx.MakeWriter<rover_ddl_StereoRequest>("ddl/camera_request"));
  ROVER_ASSIGN_OR_RETURN(range_writer_, ctx.MakeWriter<rover_dl_RangeImage>("dl/range_image"));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_RangeRequest>(
      "dl/range_request",
      [this](const dds::Sample<rover_dl_RangeRequest>& s) { OnRangeRequest(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_StereoFrame>(
      "ddl/stereo_frame",
      [this](const dds::Sample<rover_ddl_StereoFrame>& s) { OnStereoFrame(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_PoseEstimate>(
      "dl/pose",
      [this](const dds::Sample<rover_dl_PoseEstimate>& s) { return OnPose(s.data()); }));
  ctx.executor().AddTimer(Seconds(1.0 / p.GetDouble("poll_rate_hz")), [this] { OnTimer(); });
  ctx.SetHealth(rover_HEALTH_OK, "");
  return Status::Ok();
}

// ---- inputs -----------------------------------------------------------------------------------

void StereoService::OnRangeRequest(const rover_dl_RangeRequest& m) {
  msg::RangeRequest r = msg::RangeRequestFromIdl(m);
  if (!msg::IsKnownCamera(r.camera)) {
    ++stats_.rejected_requests;
    Fail("dl/range_request rejected: unknown camera",
         {{"request_id", r.request_id}, {"camera", static_cast<std::int64_t>(r.camera)}});
    return;
  }
  if (queue_.size() >= max_queue_) {
    ++stats_.rejected_requests;
    Fail("dl/range_request dropped: queue full",
         {{"request_id", r.request_id}, {"max_queue", static_cast<std::int64_t>(max_queue_)}});
    return;
  }
  if (r.width == 0) r.width = default_width_;
  queue_.push_back(r);
  ++stats_.range_requests;
  SendNext();
}

void StereoService::SendNext() {
  const Time now = ctx_->Now();
  if (!client_->Ready(now) || queue_.empty() || !ctx_->clock().valid()) return;
  const msg::RangeRequest r = queue_.front();
  queue_.pop_front();
  const msg::StereoRequest c = client_->Issue(now, r.camera, r.width, r.request_id);
  rover_ddl_StereoRequest m{};
  ctx_->Stamp(m.header, "rover");
  msg::StereoRequestToIdl(c, &m);
  const Status s = request_writer_.Write(m);
  if (!s.ok()) {
    client_->SendFailed(now);
    Fail("ddl/camera_request write failed", {{"request_id", r.request_id}, {"error", s.message()}});
    return;
  }
  ++stats_.camera_requests;
  log::Debug("camera request sent", {{"range_request_id", r.request_id},
                                     {"camera_request_id", c.request_id},
                                     {"camera", msg::CameraName(r.camera)},
                                     {"width", r.width}});
}

Status StereoService::OnPose(const rover_dl_PoseEstimate& m) {
  auto sample = msg::PoseSampleFromIdl(m);
  if (!sample.ok()) return sample.status();  // on sys/health through the input monitor
  Status s = poses_.Add(*sample);
  if (s.code() == StatusCode::kOutOfRange &&
      poses_.WentBackBy(sample->stamp, Seconds(camera_client::kClockResetS))) {
    poses_.Clear();  // the run clock went back: a new run
    s = poses_.Add(*sample);
  }
  if (!s.ok()) log::Debug("dl/pose sample dropped", {{"reason", s.message()}});
  return Status::Ok();  // an out-of-order sample is readable: not a rejection
}

void StereoService::OnStereoFrame(const rover_ddl_StereoFrame& m) {
  const auto o = client_->Answer(m.request_id);
  if (!o.has_value()) return;  // another requester's frame, or one after its timeout
  ++stats_.frames;
  Status s;
  {
    runtime::ScopedActivity stereo(ctx_->activities(), "stereo");
    s = Process(*o, m);
  }
  if (!s.ok()) {
    ++stats_.bad_frames;
    Fail("ddl/stereo_frame dropped, no range image sent", {{"range_request_id", o->tag},
                                                           {"camera_request_id", o->request_id},
                                                           {"camera", msg::CameraName(o->camera)},
                                                           {"reason", s.message()}});
  }
  SendNext();
}

Status StereoService::Process(const camera_client::Outstanding& o, const rover_ddl_StereoFrame& m) {
  ROVER_ASSIGN_OR_RETURN(const msg::StereoFrame frame, msg::StereoFrameFromIdl(m));
  ROVER_RETURN_IF_ERROR(client_->Check(o, frame));
  const PoseLookup pose{&poses_, Seconds(pose_max_age_s_), require_pose_};
  ROVER_ASSIGN_OR_RETURN(const msg::RangeImage image, ranger_->Range(frame, o.tag, pose));
  client_->Accepted(frame.stamp);
  rover_dl_RangeImage out{};
  ctx_->Stamp(out.header, "rover");
  ROVER_RETURN_IF_ERROR(msg::RangeImageToIdl(image, &out));  // stamp = capture time
  ROVER_RETURN_IF_ERROR(range_writer_.Write(out).WithPrefix("dl/range_image write"));
  ++stats_.published;
  health_.Clear();
  UpdateHealth();
  const auto valid = static_cast<double>(std::count(image.valid.begin(), image.valid.end(), 1));
  log::Info("range image published",
            {{"range_request_id", o.tag},
             {"camera", msg::CameraName(frame.camera)},
             {"size", std::to_string(image.width) + "x" + std::to_string(image.height)},
             {"valid_fraction", image.valid.empty() ? 0.0 : valid / image.valid.size()},
             {"vehicle_masked", ranger_->last_masked()},
             {"processing_ms", ranger_->last_timings().total_ms}});
  return Status::Ok();
}

// ---- timer, health ----------------------------------------------------------------------------

void StereoService::OnTimer() {
  const Time now = ctx_->Now();
  if (client_->ClockWentBack(now)) {
    log::Info("run clock went back: pose history cleared, outstanding request re-sent",
              {{"to_s", now.seconds()}});
    poses_.Clear();
    if (const auto o = client_->Reset()) queue_.push_front({o->sent, o->tag, o->camera, o->width});
  }
  if (const auto o = client_->Expire(now)) {
    ++stats_.timeouts;
    Fail("ddl/camera_request timed out, no range image sent",
         {{"range_request_id", o->tag},
          {"camera_request_id", o->request_id},
          {"camera", msg::CameraName(o->camera)},
          {"timeout_s", client_->options().request_timeout_s}});
  }
  SendNext();
  UpdateHealth();
}

void StereoService::Fail(const std::string& problem, std::initializer_list<log::Field> fields) {
  log::Warn(problem, fields);
  health_.Latch(problem, fields, {"reason", "range_request_id"});
  UpdateHealth();
}

void StereoService::UpdateHealth() {
  msg::HealthReport inputs;
  if (require_pose_ && ctx_->clock().valid()) {
    const auto latest = poses_.Latest();
    inputs = msg::FreshnessReport("dl/pose", latest ? std::optional(latest->stamp) : std::nullopt,
                                  ctx_->Now(), pose_max_age_s_);
  }
  const msg::HealthReport h = health_.Report(inputs);
  ctx_->SetHealth(msg::HealthToIdl(h.health), h.reason);
}

}  // namespace rover::dl::stereo
