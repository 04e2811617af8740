#include "rover/ddl/camera/camera_driver.hpp"

#include <algorithm>
#include <cmath>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"

namespace rover::ddl::camera {
namespace {

std::string CameraList() {
  std::string s;
  for (int i = 0; i < kNumCameras; ++i) {
    s += (i ? ", " : "") + std::to_string(i) + " (" +
         msg::CameraName(static_cast<msg::CameraId>(i)) + ")";
  }
  return s;
}

}  // namespace

Status CameraDriverOptions::Validate() const {
  auto positive = [](const char* k, double v) -> Status {
    if (!std::isfinite(v) || v <= 0.0) {
      return InvalidArgument(std::string(k) + ": " + FormatNumber(v, 3) +
                             " must be finite and > 0");
    }
    return Status::Ok();
  };
  ROVER_RETURN_IF_ERROR(positive("request_timeout_s", request_timeout_s));
  ROVER_RETURN_IF_ERROR(positive("mast_max_age_s", mast_max_age_s));
  ROVER_RETURN_IF_ERROR(positive("mast_history_s", mast_history_s));
  if (mast_history_s < mast_max_age_s) {
    return InvalidArgument("mast_history_s: " + FormatNumber(mast_history_s, 3) +
                           " must be >= mast_max_age_s (" + FormatNumber(mast_max_age_s, 3) + ")");
  }
  if (max_pending < 1) {
    return InvalidArgument("max_pending: " + std::to_string(max_pending) + " must be >= 1");
  }
  if (max_binning < 1 || max_binning > 16) {
    return InvalidArgument("max_binning: " + std::to_string(max_binning) +
                           " is out of range [1, 16] (1 = always the full frame)");
  }
  return Status::Ok();
}

Result<CameraDriver> CameraDriver::Create(CameraCalibration calibration,
                                          const CameraDriverOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  if (calibration.cameras.size() != static_cast<std::size_t>(kNumCameras)) {
    return InvalidArgument("camera calibration has " + std::to_string(calibration.cameras.size()) +
                           " stereo pairs; expected " + std::to_string(kNumCameras));
  }
  return CameraDriver(std::move(calibration), options);
}

CameraDriver::CameraDriver(CameraCalibration calibration, const CameraDriverOptions& options)
    : calibration_(std::move(calibration)), options_(options) {}

Status CameraDriver::Admit(const std::string& id, std::uint32_t exposure_us) const {
  if (exposure_us > options_.max_exposure_us) {
    return InvalidArgument(id + ": exposure_us " + std::to_string(exposure_us) +
                           " is out of range [0, " + std::to_string(options_.max_exposure_us) +
                           "] (0 = auto)");
  }
  if (pending() >= static_cast<std::size_t>(options_.max_pending)) {
    return Busy(id + ": " + std::to_string(pending()) +
                " requests already wait for the camera head (max_pending)");
  }
  return Status::Ok();
}

std::uint32_t CameraDriver::NextHwId() {
  const std::uint32_t id = next_hw_id_++;
  if (next_hw_id_ == 0) next_hw_id_ = 1;
  return id;
}

Result<hw::CameraRequest> CameraDriver::HandleRequest(const msg::StereoRequest& r, Time now) {
  const std::string id = "request " + std::to_string(r.request_id);
  if (!msg::IsKnownCamera(r.camera)) {
    return InvalidArgument(id + ": camera " + std::to_string(static_cast<int>(r.camera)) +
                           " is not one of " + CameraList());
  }
  const StereoCameraCalibration& cam = calibration_.cameras[static_cast<std::size_t>(r.camera)];
  if (r.width < 0 || r.width > cam.left.width()) {
    return InvalidArgument(id + ": width " + std::to_string(r.width) + " is out of range [0, " +
                           std::to_string(cam.left.width()) + "] for " + cam.name +
                           " (0 = full size; no upsampling)");
  }
  ROVER_RETURN_IF_ERROR(Admit(id, r.exposure_us));
  PendingRequest p{NextHwId(), r, now};
  pending_.push_back(p);
  return hw::CameraRequest{now.ns, p.hw_request_id, static_cast<int>(r.camera), r.exposure_us,
                           ReadoutFor(r.width, cam.left.width())};
}

int CameraDriver::ReadoutFor(int width, int sensor_width) const {
  ROVER_DEMAND(sensor_width >= 1 && width >= 0 && width <= sensor_width);
  if (width == 0) return 0;
  for (int b = options_.max_binning; b > 1; --b) {
    if (sensor_width % b == 0 && sensor_width / b >= width) return sensor_width / b;
  }
  return 0;
}

Status CameraDriver::HandleMast(const MastSample& s) {
  if (!std::isfinite(s.pan) || !std::isfinite(s.tilt)) {
    return InvalidArgument("mast angles pan " + FormatNumber(s.pan, 3) + ", tilt " +
                           FormatNumber(s.tilt, 3) + " are not finite");
  }
  if (!mast_.empty() && s.stamp_ns <= mast_.back().stamp_ns) return Status::Ok();
  mast_.push_back(s);
  const auto keep_ns = static_cast<std::int64_t>(options_.mast_history_s * 1e9);
  while (mast_.size() > 2 && s.stamp_ns - mast_[1].stamp_ns > keep_ns) mast_.pop_front();
  return Status::Ok();
}

bool CameraDriver::MastAt(std::int64_t t, double* pan, double* tilt, double* gap_s) const {
  if (mast_.empty()) return false;
  auto it = std::lower_bound(mast_.begin(), mast_.end(), t,
                             [](const MastSample& m, std::int64_t x) { return m.stamp_ns < x; });
  if (it == mast_.end()) {
    const MastSample& m = mast_.back();
    *pan = m.pan;
    *tilt = m.tilt;
    *gap_s = (t - m.stamp_ns) * 1e-9;
    return true;
  }
  if (it == mast_.begin() || it->stamp_ns == t) {
    *pan = it->pan;
    *tilt = it->tilt;
    *gap_s = std::abs(static_cast<double>(it->stamp_ns - t)) * 1e-9;
    return true;
  }
  const MastSample& b = *it;
  const MastSample& a = *(it - 1);
  const double u =
      static_cast<double>(t - a.stamp_ns) / static_cast<double>(b.stamp_ns - a.stamp_ns);
  *pan = a.pan + u * (b.pan - a.pan);
  *tilt = a.tilt + u * (b.tilt - a.tilt);
  *gap_s = std::min(t - a.stamp_ns, b.stamp_ns - t) * 1e-9;
  return true;
}

Result<StereoFrameData> CameraDriver::HandleFrame(const hw::CameraFrame& f) {
  auto it = std::find_if(pending_.begin(), pending_.end(),
                         [&](const PendingRequest& p) { return p.hw_request_id == f.request_id; });
  if (it == pending_.end()) {
    return NotFound("frame for hardware request " + std::to_string(f.request_id) +
                    ": no such request is pending (late, duplicate or not ours)");
  }
  const PendingRequest req = *it;
  pending_.erase(it);
  const std::string id = "frame for request " + std::to_string(req.request.request_id);

  if (f.camera != static_cast<int>(req.request.camera)) {
    return InvalidArgument(id + ": camera " + std::to_string(f.camera) + " but " +
                           msg::CameraName(req.request.camera) + " was requested");
  }
  if (f.width < 1 || f.height < 1) {
    return InvalidArgument(id + ": empty image size " + FormatSize(f.width, f.height));
  }
  const std::size_t bytes = static_cast<std::size_t>(f.width) * static_cast<std::size_t>(f.height);
  if (f.left.size() != bytes || f.right.size() != bytes) {
    return InvalidArgument(id + ": " + std::to_string(f.left.size()) + " left and " +
                           std::to_string(f.right.size()) + " right bytes for a " +
                           FormatSize(f.width, f.height) + " image");
  }
  const StereoCameraCalibration& cam = calibration_.cameras[static_cast<std::size_t>(f.camera)];
  const int cw = cam.left.width(), ch = cam.left.height();
  if (static_cast<std::int64_t>(f.width) * ch != static_cast<std::int64_t>(f.height) * cw ||
      f.width > cw) {
    return InvalidArgument(id + ": image size " + FormatSize(f.width, f.height) + " is not " +
                           FormatSize(cw, ch) + " or a binning of it (the " + cam.name +
                           " calibration's size)");
  }

  msg::SensorHealth health = msg::SensorHealth::kOk;
  std::string health_reason;
  double pan = 0.0, tilt = 0.0, gap = 0.0;
  if (cam.mount == CameraMount::kMastHead) {
    if (!MastAt(f.stamp_ns, &pan, &tilt, &gap)) {
      health = msg::SensorHealth::kFailed;
      health_reason =
          "mast pose unknown (no ddl/joint_state yet): " + cam.name + " models are not valid";
    } else if (gap > options_.mast_max_age_s) {
      health = msg::SensorHealth::kDegraded;
      health_reason = "nearest mast sample is " + FormatNumber(gap, 3) + " s from the capture time";
    }
  }
  auto models = cam.InRover(pan, tilt, calibration_.mast);
  if (f.width != cw) {
    const double sx = static_cast<double>(f.width) / cw;
    const double sy = static_cast<double>(f.height) / ch;
    models.first = geometry::Scale(models.first, sx, sy);
    models.second = geometry::Scale(models.second, sx, sy);
  }

  int out_width = req.request.width;
  std::string note;
  if (out_width > f.width) {
    note = "requested width " + std::to_string(out_width) + " is larger than the " +
           std::to_string(f.width) + " px frame; sent at full size";
    out_width = 0;
  }
  GrayImage left{f.width, f.height, std::vector<std::uint8_t>(f.left.begin(), f.left.end())};
  GrayImage right{f.width, f.height, std::vector<std::uint8_t>(f.right.begin(), f.right.end())};
  auto pair = DownsampleStereo(left, right, models.first, models.second, out_width);
  if (!pair.ok()) return pair.status().WithPrefix(id);
  auto lf = msg::CameraModelFieldsFromModel(pair->left_model);
  if (!lf.ok()) return Internal(id + ": left model: " + lf.status().message());
  auto rf = msg::CameraModelFieldsFromModel(pair->right_model);
  if (!rf.ok()) return Internal(id + ": right model: " + rf.status().message());
  return StereoFrameData{f.stamp_ns,
                         req.request.request_id,
                         f.camera,
                         f.exposure_us,
                         std::move(*pair),
                         std::move(*lf),
                         std::move(*rf),
                         pan,
                         tilt,
                         health,
                         std::move(health_reason),
                         std::move(note)};
}

msg::StereoFrame StereoFrameData::Message() const {
  msg::StereoFrame m;
  m.stamp = Time{stamp_ns};
  m.request_id = request_id;
  m.camera = static_cast<msg::CameraId>(camera);
  m.exposure_us = exposure_us;
  m.width = pair.left.width;
  m.height = pair.left.height;
  m.left_model = left_fields;
  m.right_model = right_fields;
  m.left = pair.left.pixels;
  m.right = pair.right.pixels;
  m.health = health;
  return m;
}

std::vector<PendingRequest> CameraDriver::ExpireRequests(Time now) {
  std::vector<PendingRequest> expired;
  for (auto it = pending_.begin(); it != pending_.end();) {
    if (ToSeconds(now - it->issued) > options_.request_timeout_s) {
      expired.push_back(*it);
      it = pending_.erase(it);
    } else {
      ++it;
    }
  }
  return expired;
}

Result<hw::MiRequest> CameraDriver::HandleMiRequest(const msg::MiRequest& r, Time now) {
  ROVER_RETURN_IF_ERROR(
      Admit("microscopic-imager request " + std::to_string(r.request_id), r.exposure_us));
  PendingMi p{NextHwId(), r, now};
  pending_mi_.push_back(p);
  return hw::MiRequest{now.ns, p.hw_request_id, r.exposure_us};
}

Result<msg::MiFrame> CameraDriver::HandleMiFrame(const hw::MiFrame& f) {
  auto it = std::find_if(pending_mi_.begin(), pending_mi_.end(),
                         [&](const PendingMi& p) { return p.hw_request_id == f.request_id; });
  if (it == pending_mi_.end()) {
    return NotFound("hw/mi_frame " + std::to_string(f.request_id) +
                    " answers no pending microscopic-imager request (late, duplicate or not ours)");
  }
  const PendingMi req = *it;
  pending_mi_.erase(it);
  msg::MiFrame m;
  m.stamp = Time{f.stamp_ns};
  m.request_id = req.request.request_id;
  m.exposure_us = f.exposure_us;
  m.width = f.width;
  m.height = f.height;
  m.image = f.image;
  const Status ok = msg::CheckMiFrame(m);
  if (!ok.ok()) {
    return InvalidArgument("hw/mi_frame " + std::to_string(f.request_id) + ": " + ok.message());
  }
  return m;
}

std::vector<msg::MiRequest> CameraDriver::ExpireMiRequests(Time now) {
  std::vector<msg::MiRequest> expired;
  for (auto it = pending_mi_.begin(); it != pending_mi_.end();) {
    if (ToSeconds(now - it->issued) > options_.request_timeout_s) {
      expired.push_back(it->request);
      it = pending_mi_.erase(it);
    } else {
      ++it;
    }
  }
  return expired;
}

void CameraDriver::Reset() {
  pending_.clear();
  pending_mi_.clear();
  mast_.clear();
}

}  // namespace rover::ddl::camera
