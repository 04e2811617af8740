#include "rover/dl/camera_client/camera_request_client.hpp"

#include <string>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::dl::camera_client {
namespace {

const char* HealthText(msg::SensorHealth h) {
  return h == msg::SensorHealth::kFailed ? "FAILED" : "STALE";
}

}  // namespace

Status CameraClientOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckIntRange("request_id_prefix", request_id_prefix, 1, 255));
  ROVER_RETURN_IF_ERROR(CheckPositive("request_timeout_s", request_timeout_s, "s"));
  return CheckNonNegative("retry_delay_s", retry_delay_s, "s");
}

void CameraClientOptions::BindParams(ParamBinder<CameraClientOptions>& b) {
  b.Bind("request_id_prefix", &CameraClientOptions::request_id_prefix, "",
         "top 8 bits of this service's ddl/camera_request ids (one per requester: dl-stereo 1, "
         "dl-vo 2)")
      .Range(1, 255);
  b.Bind("request_timeout_s", &CameraClientOptions::request_timeout_s, "s",
         "run-clock time the camera driver has to answer a ddl/camera_request")
      .Range(0.1, 600.0);
  b.Bind("exposure_us", &CameraClientOptions::exposure_us, "us",
         "exposure asked of the camera driver; 0 = auto")
      .Range(0, 10000000);
}

CameraRequestClient::CameraRequestClient(const CameraClientOptions& options) : options_(options) {
  ROVER_DEMAND(options_.Validate().ok());
}

msg::StereoRequest CameraRequestClient::Issue(Time now, msg::CameraId camera, int width,
                                              std::uint32_t tag) {
  ROVER_DEMAND(!outstanding_.has_value());
  counter_ = (counter_ + 1) & 0xFFFFFFu;
  if (counter_ == 0) counter_ = 1;
  msg::StereoRequest r;
  r.stamp = now;
  r.request_id = (static_cast<std::uint32_t>(options_.request_id_prefix) << 24) | counter_;
  r.camera = camera;
  r.exposure_us = options_.exposure_us;
  r.width = width;
  outstanding_ = Outstanding{r.request_id, camera, width, now, tag};
  return r;
}

void CameraRequestClient::SendFailed(Time now) {
  outstanding_.reset();
  Failed(now);
}

std::optional<Outstanding> CameraRequestClient::Answer(std::uint32_t request_id) {
  if (!outstanding_.has_value() || outstanding_->request_id != request_id) return std::nullopt;
  const Outstanding o = *outstanding_;
  outstanding_.reset();
  return o;
}

Status CameraRequestClient::Check(const Outstanding& o, const msg::StereoFrame& f) const {
  if (f.camera != o.camera) {
    return InvalidArgument(std::string("frame is from camera ") + msg::CameraName(f.camera) +
                           ", requested " + msg::CameraName(o.camera));
  }
  if (!msg::IsUsable(f.health)) {
    return InvalidArgument(std::string("frame health is ") + HealthText(f.health));
  }
  if (o.width != 0 && f.width != o.width) {
    return InvalidArgument("frame is " + std::to_string(f.width) + " px wide, requested " +
                           std::to_string(o.width));
  }
  if (f.stamp < o.sent - Seconds(kCaptureSkewS)) {
    return InvalidArgument("capture stamp " + FormatNumber(f.stamp.seconds()) +
                           " s is before the request was sent (" + FormatNumber(o.sent.seconds()) +
                           " s): stale or out of time order");
  }
  if (last_capture_.has_value() && f.stamp <= *last_capture_) {
    return InvalidArgument("capture stamp " + FormatNumber(f.stamp.seconds()) +
                           " s is not after the previous frame's (" +
                           FormatNumber(last_capture_->seconds()) + " s): out of time order");
  }
  return Status::Ok();
}

void CameraRequestClient::Accepted(Time capture) { last_capture_ = capture; }

void CameraRequestClient::Failed(Time now) { hold_until_ = now + Seconds(options_.retry_delay_s); }

std::optional<Outstanding> CameraRequestClient::Expire(Time now) {
  if (!outstanding_.has_value() ||
      ToSeconds(now - outstanding_->sent) <= options_.request_timeout_s) {
    return std::nullopt;
  }
  const Outstanding o = *outstanding_;
  outstanding_.reset();
  return o;
}

bool CameraRequestClient::ClockWentBack(Time now) {
  const bool back = now < last_now_ - Seconds(kClockResetS);
  last_now_ = now;
  return back;
}

std::optional<Outstanding> CameraRequestClient::Reset() {
  const std::optional<Outstanding> o = outstanding_;
  outstanding_.reset();
  last_capture_.reset();
  hold_until_ = Time{0};
  return o;
}

}  // namespace rover::dl::camera_client
