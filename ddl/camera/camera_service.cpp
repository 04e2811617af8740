#include "camera_service.hpp"

#include "rover/base/format.hpp"
#include "rover/base/log.hpp"
#include "rover/ddl/driver_support/driver_params.hpp"
#include "rover/msg/camera_idl.hpp"
#include "rover/msg/health_idl.hpp"
#include "rover/msg/hw_idl.hpp"
#include "rover/msg/sensors_idl.hpp"

namespace rover::ddl::camera {

using driver_support::HealthSummary;
using driver_support::IsLogWorthy;
using driver_support::ResolveConfigFile;

void CameraService::DeclareParameters(ParamSet& p) {
  const CameraDriverOptions d;
  p.Declare("camera_file", "deploy/config/cameras.yaml",
            "camera calibration (CAHV/CAHVOR/CAHVORE pairs and mast geometry); relative paths "
            "are looked up in the working directory, then under $ROVER_SOURCE_DIR");
  p.Declare("request_timeout_s", d.request_timeout_s,
            "[s] a request the camera head has not answered by then is dropped (run clock)")
      .Range(0.05, 600.0);
  p.Declare("max_pending", d.max_pending, "requests waiting for the camera head at once")
      .Range(1, 64);
  p.Declare("mast_max_age_s", d.mast_max_age_s,
            "[s] NAVCAM frames whose nearest mast sample is further from the capture are DEGRADED")
      .Range(0.001, 10.0);
  p.Declare("mast_history_s", d.mast_history_s, "[s] mast samples kept for interpolation")
      .Range(0.01, 60.0);
  p.Declare("max_exposure_us", static_cast<std::int64_t>(d.max_exposure_us),
            "[us] longest exposure a request may ask for (0 = auto is always allowed)")
      .Range(0.0, 600.0e6);
  p.Declare("max_binning", d.max_binning,
            "largest b x b binning asked of the camera head for a request narrower than the "
            "sensor (the readout: 1024 px -> 512, 256, ...); 1 = always read the full frame")
      .Range(1, 16);
  p.Declare("joint_state_stale_s", 0.25,
            "[s] ddl/joint_state not arriving for this long makes the service DEGRADED")
      .Range(0.005, 60.0);
  p.Declare("watchdog_rate_hz", 10.0,
            "[Hz] how often request timeouts, staleness and health are judged (run clock)")
      .Range(0.5, 100.0);
  p.Declare("max_future_s", 1.0,
            "[s] inputs stamped further ahead of the run clock are dropped as corrupt")
      .Range(0.001, 60.0);
}

Result<CameraDriver> CameraService::MakeDriver(const ParamSet& p, std::string* path) {
  auto file = ResolveConfigFile(p.GetString("camera_file"));
  if (!file.ok()) return file.status().WithPrefix("camera_file");
  auto cal = LoadCameraCalibration(*file);
  if (!cal.ok()) return cal.status();
  CameraDriverOptions o;
  o.request_timeout_s = p.GetDouble("request_timeout_s");
  o.max_pending = static_cast<int>(p.GetInt("max_pending"));
  o.mast_max_age_s = p.GetDouble("mast_max_age_s");
  o.mast_history_s = p.GetDouble("mast_history_s");
  o.max_exposure_us = static_cast<std::uint32_t>(p.GetInt("max_exposure_us"));
  o.max_binning = static_cast<int>(p.GetInt("max_binning"));
  if (path != nullptr) *path = *file;
  return CameraDriver::Create(std::move(*cal), o);
}

Status CameraService::ValidateParameters(const ParamSet& p) const {
  return MakeDriver(p, nullptr).status();
}

Status CameraService::OnConfigure(ServiceContext& ctx, const ParamSet& p) {
  ctx_ = &ctx;
  std::string path;
  auto driver = MakeDriver(p, &path);
  if (!driver.ok()) return driver.status();
  driver_.emplace(std::move(*driver));
  const CameraDriverOptions& o = driver_->options();
  const double max_future = p.GetDouble("max_future_s");
  joints_.emplace("ddl/joint_state", p.GetDouble("joint_state_stale_s"), max_future);
  frames_.emplace("hw/camera_frame", o.request_timeout_s, max_future);
  mi_frames_.emplace("hw/mi_frame", o.request_timeout_s, max_future);

  auto rw = ctx.MakeWriter<rover_hw_CameraRequest>("hw/camera_request");
  if (!rw.ok()) return rw.status();
  request_writer_ = std::move(*rw);
  auto fw = ctx.MakeWriter<rover_ddl_StereoFrame>("ddl/stereo_frame");
  if (!fw.ok()) return fw.status();
  frame_writer_ = std::move(*fw);
  auto mw = ctx.MakeWriter<rover_hw_MiRequest>("hw/mi_request");
  if (!mw.ok()) return mw.status();
  mi_request_writer_ = std::move(*mw);
  auto mf = ctx.MakeWriter<rover_ddl_MiFrame>("ddl/mi_frame");
  if (!mf.ok()) return mf.status();
  mi_frame_writer_ = std::move(*mf);
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_MiRequest>(
      "ddl/mi_request",
      [this](const dds::Sample<rover_ddl_MiRequest>& s) { OnMiRequest(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_hw_MiFrame>(
      "hw/mi_frame", [this](const dds::Sample<rover_hw_MiFrame>& s) { return OnMiFrame(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_StereoRequest>(
      "ddl/camera_request",
      [this](const dds::Sample<rover_ddl_StereoRequest>& s) { OnRequest(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_JointState>(
      "ddl/joint_state",
      [this](const dds::Sample<rover_ddl_JointState>& s) { return OnJointState(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_hw_CameraFrame>(
      "hw/camera_frame",
      [this](const dds::Sample<rover_hw_CameraFrame>& s) { return OnFrame(s.data()); }));
  ctx.executor().AddTimer(Seconds(1.0 / p.GetDouble("watchdog_rate_hz")), [this] { OnWatchdog(); });
  log::Info("camera calibration loaded", {{"file", path}});
  return Status::Ok();
}

Time CameraService::Now() {
  const Time now = ctx_->Now();
  if (clock_jump_.WentBack(now, ctx_->clock().valid())) {
    log::Warn("run clock went back (simulator reset): pending camera requests dropped",
              {{"pending", driver_->pending()}});
    driver_->Reset();
    joints_->Reset();
    frames_->Reset();
    mi_frames_->Reset();
  }
  return now;
}

void CameraService::OnRequest(const rover_ddl_StereoRequest& request) {
  const Time now = Now();
  auto hw = driver_->HandleRequest(msg::StereoRequestFromIdl(request), now);
  if (!hw.ok()) {
    log::Warn("camera request rejected; no frame will be sent",
              {{"request_id", request.request_id}, {"reason", hw.status().message()}});
    return;
  }
  rover_hw_CameraRequest out{};
  ctx_->Stamp(out.header, "rover");
  msg::CameraRequestToIdl(*hw, &out);
  const Status s = request_writer_.Write(out);
  if (!s.ok()) {
    write_error_ = s.message();
    log::Error("cannot send the camera request", {{"error", s.message()}});
  }
}

void CameraService::OnMiRequest(const rover_ddl_MiRequest& request) {
  const Time now = Now();
  auto hw = driver_->HandleMiRequest(msg::MiRequestFromIdl(request), now);
  if (!hw.ok()) {
    log::Warn("microscopic-imager request rejected; no frame will be sent",
              {{"request_id", request.request_id}, {"reason", hw.status().message()}});
    return;
  }
  rover_hw_MiRequest out{};
  ctx_->Stamp(out.header, "rover");
  msg::MiRequestToIdl(*hw, &out);
  const Status s = mi_request_writer_.Write(out);
  if (!s.ok()) {
    write_error_ = s.message();
    log::Error("cannot send the microscopic-imager request", {{"error", s.message()}});
  }
}

Status CameraService::OnMiFrame(const rover_hw_MiFrame& frame) {
  const Time now = Now();
  const Status s = mi_frames_->Accept(frame.header.stamp_ns, now, ctx_->clock().valid());
  if (!s.ok()) {
    log::Warn("hw/mi_frame dropped", {{"reason", s.message()}});
    return s;
  }
  auto data = driver_->HandleMiFrame(msg::MiFrameFromIdl(frame));
  if (!data.ok()) {
    if (data.status().code() == StatusCode::kNotFound) {
      log::Info("hw/mi_frame ignored", {{"reason", data.status().message()}});
      return Status::Ok();
    }
    camera_error_ = data.status().message();
    log::Warn("hw/mi_frame rejected; no frame will be sent", {{"reason", data.status().message()}});
    return data.status();
  }
  rover_ddl_MiFrame out{};
  ctx_->Stamp(out.header, "mi");
  msg::MiFrameToIdl(*data, &out);  // stamp = capture time; image borrowed
  const Status w = mi_frame_writer_.Write(out);
  if (!w.ok()) {
    write_error_ = w.message();
    log::Error("cannot publish the microscopic-imager frame", {{"error", w.message()}});
  }
  return Status::Ok();
}

Status CameraService::OnJointState(const rover_ddl_JointState& joints) {
  const Time now = Now();
  // Stale or failed joint states do not vouch for the mast angles: they are not used and do not
  // count as fresh input; frames then carry the age of the last usable sample.
  const auto js = msg::JointStateFromIdl(joints);
  if (!js.ok()) return js.status();
  if (!msg::IsUsable(js->health)) return Status::Ok();  // valid, but not for the mast angles
  const Status s = joints_->Accept(joints.header.stamp_ns, now, ctx_->clock().valid());
  if (!s.ok()) {
    if (IsLogWorthy(joints_->rejected())) {
      log::Warn("ddl/joint_state sample dropped", {{"reason", s.message()}});
    }
    return s;
  }
  const Status m = driver_->HandleMast({js->stamp.ns, js->mast_pan, js->mast_tilt});
  if (!m.ok()) log::Warn("ddl/joint_state mast angles ignored", {{"reason", m.message()}});
  return Status::Ok();
}

Status CameraService::OnFrame(const rover_hw_CameraFrame& frame) {
  const Time now = Now();
  const Status s = frames_->Accept(frame.header.stamp_ns, now, ctx_->clock().valid());
  if (!s.ok()) {
    log::Warn("hw/camera_frame dropped", {{"reason", s.message()}});
    return s;
  }
  auto data = driver_->HandleFrame(msg::CameraFrameFromIdl(frame));
  if (!data.ok()) {
    if (data.status().code() == StatusCode::kNotFound) {
      log::Info("hw/camera_frame ignored", {{"reason", data.status().message()}});
    } else {
      camera_error_ = data.status().message();
      log::Warn("hw/camera_frame rejected; no frame will be sent",
                {{"reason", data.status().message()}});
      return data.status();
    }
    return Status::Ok();
  }
  camera_error_.clear();
  if (!data->note.empty()) log::Info("stereo frame note", {{"note", data->note}});
  if (data->health != msg::SensorHealth::kOk) {
    log::Warn("stereo frame not healthy", {{"request_id", data->request_id},
                                           {"health", msg::SensorHealthName(data->health)},
                                           {"reason", data->health_reason}});
  }
  rover_ddl_StereoFrame out{};
  ctx_->Stamp(out.header, "rover");
  msg::StereoFrameToIdl(data->Message(), &out);  // stamp = capture time; images borrowed
  const Status w = frame_writer_.Write(out);
  if (!w.ok()) {
    write_error_ = w.message();
    log::Error("cannot publish the stereo frame", {{"error", w.message()}});
  } else {
    write_error_.clear();
  }
  return Status::Ok();
}

void CameraService::OnWatchdog() {
  const Time now = Now();
  for (const PendingRequest& p : driver_->ExpireRequests(now)) {
    camera_error_ = "camera head did not answer request " + std::to_string(p.request.request_id) +
                    " (" + msg::CameraName(p.request.camera) + ") within " +
                    FormatNumber(driver_->options().request_timeout_s, 3) + " s";
    log::Warn(
        "camera request timed out; no frame will be sent",
        {{"request_id", p.request.request_id}, {"camera", msg::CameraName(p.request.camera)}});
  }
  for (const msg::MiRequest& r : driver_->ExpireMiRequests(now)) {
    camera_error_ = "microscopic imager did not answer request " + std::to_string(r.request_id) +
                    " within " + FormatNumber(driver_->options().request_timeout_s, 3) + " s";
    log::Warn("microscopic-imager request timed out; no frame will be sent",
              {{"request_id", r.request_id}});
  }
  HealthSummary h;
  if (joints_->Stale(now)) {
    h.Worsen(msg::SensorHealth::kDegraded,
             joints_->StaleReason(now) + " (NAVCAM models cannot follow the mast)");
  }
  if (!camera_error_.empty()) h.Worsen(msg::SensorHealth::kDegraded, camera_error_);
  if (!write_error_.empty()) h.Worsen(msg::SensorHealth::kFailed, write_error_);
  ctx_->SetHealth(msg::HealthToIdl(h.health), h.reason);
}

}  // namespace rover::ddl::camera
