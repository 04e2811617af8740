// dl-stereo: binds the stereo pipeline (dl_stereo) to dl/range_request, ddl/camera_request,
// ddl/stereo_frame, dl/pose and dl/range_image. See stereo_service.hpp and
// docs/services/dl-stereo.md.
#include "stereo_service.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "rover/base/check.hpp"
#include "rover/dl/stereo/frame_images.hpp"
#include "rover/msg/camera_idl.hpp"
#include "rover/msg/pose_idl.hpp"

namespace rover::dl::stereo {
namespace {

// A capture stamp this much before the request was sent is a stale (or reordered) frame.
constexpr double kCaptureSkewS = 0.1;
// The run clock going back by more than this is a reset (simulator reset).
constexpr double kClockResetS = 1.0;

const char* CameraName(rover_CameraId c) {
  switch (c) {
    case rover_CAMERA_NAVCAM:
      return "navcam";
    case rover_CAMERA_FRONT_HAZCAM:
      return "front_hazcam";
    case rover_CAMERA_REAR_HAZCAM:
      return "rear_hazcam";
  }
  return "unknown";
}

bool KnownCamera(std::int64_t c) {
  return c >= rover_CAMERA_NAVCAM && c <= rover_CAMERA_REAR_HAZCAM;
}

std::string Num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

Result<PrefilterKind> PrefilterFromName(const std::string& name) {
  if (name == "log") return PrefilterKind::kLaplacianOfGaussian;
  if (name == "dog") return PrefilterKind::kDifferenceOfGaussians;
  if (name == "none") return PrefilterKind::kNone;
  return InvalidArgument("stereo.prefilter '" + name + "' is not one of: log, dog, none");
}

// The pipeline options the parameters describe; errors name the parameter. The correlator's
// num_disparities is a placeholder when stereo.num_disparities is 0 (derived per camera).
Result<StereoOptions> StereoOptionsFromParams(const ParamSet& p) {
  StereoOptions o;
  o.pyramid_levels = static_cast<int>(p.GetInt("stereo.pyramid_levels"));
  o.correlator.window = static_cast<int>(p.GetInt("stereo.window"));
  const int d = static_cast<int>(p.GetInt("stereo.num_disparities"));
  o.correlator.num_disparities = d > 0 ? d : 64;
  o.correlator.uniqueness_ratio = p.GetDouble("stereo.uniqueness_ratio");
  o.correlator.min_curvature = p.GetDouble("stereo.min_curvature");
  o.correlator.lr_max_diff = static_cast<int>(p.GetInt("stereo.lr_max_diff"));
  o.correlator.num_threads = static_cast<int>(p.GetInt("stereo.num_threads"));
  o.filters.blob_min_area = static_cast<int>(p.GetInt("stereo.blob_min_area"));
  o.filters.overhang = p.GetBool("stereo.overhang");
  o.reprojection.min_range_m = p.GetDouble("stereo.min_range_m");
  o.reprojection.max_range_m = p.GetDouble("stereo.max_range_m");
  auto prefilter = PrefilterFromName(p.GetString("stereo.prefilter"));
  if (!prefilter.ok()) return prefilter.status();
  o.prefilter.kind = *prefilter;
  if (o.reprojection.max_range_m <= o.reprojection.min_range_m) {
    return InvalidArgument("stereo.max_range_m " + Num(o.reprojection.max_range_m) +
                           " must be larger than stereo.min_range_m " +
                           Num(o.reprojection.min_range_m));
  }
  ROVER_RETURN_IF_ERROR(o.Validate().WithPrefix("stereo parameters"));
  return o;
}

}  // namespace

Status StereoService::ValidateParameters(const ParamSet& p) const {
  return StereoOptionsFromParams(p).status();
}

void StereoService::DeclareParameters(ParamSet& p) {
  p.Declare("default_width", 256,
            "[px] processing width asked of the camera driver when dl/range_request.width is 0 "
            "(0 = full sensor size; MER ranged 256 px wide images)")
      .Range(0, 4096);
  p.Declare("exposure_us", 0, "[us] exposure asked of the camera driver; 0 = auto")
      .Range(0, 10000000);
  p.Declare("request_timeout_s", 10.0,
            "[s] run-clock time the camera driver has to answer a ddl/camera_request")
      .Range(0.1, 600.0);
  p.Declare("max_queue", 4, "range requests waiting behind the outstanding one, at most")
      .Range(1, 64);
  p.Declare("pose_max_age_s", 1.0,
            "[s] the dl/pose estimate used for rover_pose must lie within this of the capture "
            "time; also the age after which dl/pose counts as stale for the health")
      .Range(0.01, 60.0);
  p.Declare("require_pose", true,
            "true: no range image without a dl/pose estimate at the capture time; false: send "
            "it with an identity rover_pose (and a warning)");
  p.Declare("request_id_prefix", 1,
            "top 8 bits of this service's ddl/camera_request ids (keeps them apart from other "
            "requesters such as dl-vo, prefix 2)")
      .Range(1, 255);
  p.Declare("poll_rate_hz", 10.0, "[Hz] run-clock rate of the timeout and health checks")
      .Range(1.0, 100.0);
  p.Declare("rectification_cache_size", 4, "camera-model pairs whose remap tables are kept")
      .Range(1, 32);
  p.Declare("stereo.pyramid_levels", 0,
            "2x2 block-mean levels before correlation (the driver already downsampled to the "
            "processing width)")
      .Range(0, 4);
  p.Declare("stereo.window", 7, "[px] SAD window, odd").Range(3, 15);
  p.Declare("stereo.num_disparities", 0,
            "[px] disparity search range; 0 = derived from stereo.min_range_m")
      .Range(0, 512);
  p.Declare("stereo.max_disparities", 256, "[px] cap of the derived search range").Range(16, 512);
  p.Declare("stereo.min_range_m", 0.3,
            "[m] nearest range of interest: sets the derived search range and drops nearer "
            "points")
      .Range(0.05, 100.0);
  p.Declare("stereo.max_range_m", 50.0, "[m] farther points are invalid (range_limit)")
      .Range(0.1, 10000.0);
  p.Declare("stereo.prefilter", "log", "band-pass prefilter: log, dog or none")
      .OneOf({"log", "dog", "none"});
  p.Declare("stereo.uniqueness_ratio", 0.05, "secondary-minimum margin; 0 = off").Range(0.0, 2.0);
  p.Declare("stereo.min_curvature", 0.5,
            "flat-valley threshold per window pixel (low texture); 0 = off")
      .Range(0.0, 255.0);
  p.Declare("stereo.lr_max_diff", 1, "[px] left/right consistency tolerance; -1 = off")
      .Range(-1, 64);
  p.Declare("stereo.blob_min_area", 40, "[px] smaller disparity regions are removed; 0 = off")
      .Range(0, 1000000);
  p.Declare("stereo.overhang", true, "remove ranges that loom over nearer terrain");
  p.Declare("stereo.num_threads", 2, "correlation threads").Range(1, 16);
}

Status StereoService::OnConfigure(ServiceContext& ctx, const ParamSet& p) {
  ctx_ = &ctx;
  default_width_ = static_cast<int>(p.GetInt("default_width"));
  exposure_us_ = static_cast<std::uint32_t>(p.GetInt("exposure_us"));
  request_timeout_s_ = p.GetDouble("request_timeout_s");
  max_queue_ = static_cast<std::size_t>(p.GetInt("max_queue"));
  pose_max_age_s_ = p.GetDouble("pose_max_age_s");
  require_pose_ = p.GetBool("require_pose");
  request_prefix_ = static_cast<std::uint32_t>(p.GetInt("request_id_prefix"));
  num_disparities_ = static_cast<int>(p.GetInt("stereo.num_disparities"));
  max_disparities_ = static_cast<int>(p.GetInt("stereo.max_disparities"));
  min_range_m_ = p.GetDouble("stereo.min_range_m");

  auto options = StereoOptionsFromParams(p);
  if (!options.ok()) return options.status();
  options_ = *options;

  cache_ = std::make_unique<StereoSetupCache>(
      static_cast<std::size_t>(p.GetInt("rectification_cache_size")));
  // Enough dl/pose history to cover a request that takes the whole timeout (>= 8 Hz poses).
  poses_ = PoseHistory(static_cast<std::size_t>(std::max(64.0, 50.0 * request_timeout_s_)));

  auto rw = ctx.MakeWriter<rover_ddl_StereoRequest>("ddl/camera_request");
  if (!rw.ok()) return rw.status();
  request_writer_ = std::move(*rw);
  auto iw = ctx.MakeWriter<rover_dl_RangeImage>("dl/range_image");
  if (!iw.ok()) return iw.status();
  range_writer_ = std::move(*iw);

  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_RangeRequest>(
      "dl/range_request",
      [this](const dds::Sample<rover_dl_RangeRequest>& s) { OnRangeRequest(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_StereoFrame>(
      "ddl/stereo_frame",
      [this](const dds::Sample<rover_ddl_StereoFrame>& s) { OnStereoFrame(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_PoseEstimate>(
      "dl/pose", [this](const dds::Sample<rover_dl_PoseEstimate>& s) { OnPose(s.data()); }));
  ctx.executor().AddTimer(Seconds(1.0 / p.GetDouble("poll_rate_hz")), [this] { OnTimer(); });
  ctx.SetHealth(rover_HEALTH_OK, "");
  return Status::Ok();
}

// ---- inputs -----------------------------------------------------------------------------------

void StereoService::OnRangeRequest(const rover_dl_RangeRequest& m) {
  if (!KnownCamera(static_cast<std::int64_t>(m.camera))) {
    ++stats_.rejected_requests;
    Fail("dl/range_request rejected: unknown camera",
         {{"request_id", m.request_id}, {"camera", static_cast<std::int64_t>(m.camera)}});
    return;
  }
  if (queue_.size() >= max_queue_) {
    ++stats_.rejected_requests;
    Fail("dl/range_request dropped: queue full",
         {{"request_id", m.request_id}, {"max_queue", static_cast<std::int64_t>(max_queue_)}});
    return;
  }
  Request r;
  r.range_request_id = m.request_id;
  r.camera = m.camera;
  r.width = m.width != 0 ? m.width : static_cast<std::uint16_t>(default_width_);
  queue_.push_back(r);
  ++stats_.range_requests;
  SendNext();
}

void StereoService::SendNext() {
  if (outstanding_.has_value() || queue_.empty() || !ctx_->clock().valid()) return;
  const Request r = queue_.front();
  queue_.pop_front();
  counter_ = (counter_ + 1) & 0xFFFFFFu;
  if (counter_ == 0) counter_ = 1;
  rover_ddl_StereoRequest m{};
  ctx_->Stamp(m.header, "rover");
  m.request_id = (request_prefix_ << 24) | counter_;
  m.camera = r.camera;
  m.exposure_us = exposure_us_;
  m.width = r.width;
  const Status s = request_writer_.Write(m);
  if (!s.ok()) {
    Fail("ddl/camera_request write failed",
         {{"request_id", r.range_request_id}, {"error", s.message()}});
    return;
  }
  ++stats_.camera_requests;
  outstanding_ = Outstanding{r, m.request_id, Time{m.header.stamp_ns}};
  log::Debug("camera request sent", {{"range_request_id", r.range_request_id},
                                     {"camera_request_id", m.request_id},
                                     {"camera", CameraName(r.camera)},
                                     {"width", r.width}});
}

void StereoService::OnPose(const rover_dl_PoseEstimate& m) {
  auto sample = msg::PoseSampleFromIdl(m);
  if (!sample.ok()) {
    log::Warn("dl/pose sample dropped", {{"reason", sample.status().message()}});
    return;
  }
  Status s = poses_.Add(*sample);
  if (s.code() == StatusCode::kOutOfRange) {
    const auto latest = poses_.Latest();
    if (latest.has_value() && ToSeconds(latest->stamp - sample->stamp) > kClockResetS) {
      poses_.Clear();  // the run clock went back: a new run
      s = poses_.Add(*sample);
    }
  }
  if (!s.ok()) log::Debug("dl/pose sample dropped", {{"reason", s.message()}});
}

void StereoService::OnStereoFrame(const rover_ddl_StereoFrame& m) {
  if (!outstanding_.has_value() || m.request_id != outstanding_->camera_request_id) {
    return;  // another requester's frame, or one that came after its timeout
  }
  const Outstanding o = *outstanding_;
  outstanding_.reset();
  ++stats_.frames;
  const Status s = Process(o, m);
  if (!s.ok()) {
    ++stats_.bad_frames;
    Fail("ddl/stereo_frame dropped, no range image sent",
         {{"range_request_id", o.request.range_request_id},
          {"camera_request_id", o.camera_request_id},
          {"camera", CameraName(o.request.camera)},
          {"reason", s.message()}});
  }
  SendNext();
}

// ---- processing -------------------------------------------------------------------------------

Result<StereoPipeline*> StereoService::PipelineFor(const StereoSetup& setup) {
  int d = num_disparities_;
  if (d == 0) {
    const RectifiedStereoModel level = setup.camera.model.Downsampled(options_.pyramid_levels);
    const double nearest = level.DisparityFromDepth(min_range_m_);
    const double wanted = std::isfinite(nearest) ? std::ceil(nearest) + 2.0 : max_disparities_;
    d = static_cast<int>(std::clamp(wanted, 16.0, static_cast<double>(max_disparities_)));
  }
  auto it = pipelines_.find(d);
  if (it == pipelines_.end()) {
    StereoOptions o = options_;
    o.correlator.num_disparities = d;
    auto pipe = StereoPipeline::Create(o);
    if (!pipe.ok()) return pipe.status().WithPrefix("stereo pipeline");
    it = pipelines_.emplace(d, std::move(*pipe)).first;
    log::Info("stereo pipeline created", {{"num_disparities", d}});
  }
  return &it->second;
}

Status StereoService::Process(const Outstanding& o, const rover_ddl_StereoFrame& m) {
  if (m.camera != o.request.camera) {
    return InvalidArgument(std::string("frame is from camera ") + CameraName(m.camera) +
                           ", requested " + CameraName(o.request.camera));
  }
  if (m.health == rover_HEALTH_FAILED || m.health == rover_HEALTH_STALE) {
    return InvalidArgument("frame health is " +
                           std::string(m.health == rover_HEALTH_FAILED ? "FAILED" : "STALE"));
  }
  auto pair = msg::StereoFrameFromIdl(m);
  if (!pair.ok()) return pair.status();
  const FrameImages images = ViewFrameImages(*pair);
  if (o.request.width != 0 && pair->width != o.request.width) {
    return InvalidArgument("frame is " + std::to_string(pair->width) + " px wide, requested " +
                           std::to_string(o.request.width));
  }
  if (pair->stamp < o.sent - Seconds(kCaptureSkewS)) {
    return InvalidArgument("capture stamp " + Num(pair->stamp.seconds()) +
                           " s is before the request was sent (" + Num(o.sent.seconds()) +
                           " s): stale or out of time order");
  }
  if (last_frame_stamp_.has_value() && pair->stamp <= *last_frame_stamp_) {
    return InvalidArgument("capture stamp " + Num(pair->stamp.seconds()) +
                           " s is not after the previous frame's (" +
                           Num(last_frame_stamp_->seconds()) + " s): out of time order");
  }
  auto setup = cache_->Get(pair->left_model, pair->right_model);
  if (!setup.ok()) return setup.status();
  const StereoSetup& st = **setup;

  rover_Pose3 rover_pose{};
  rover_pose.orientation.w = 1.0;
  auto pose = poses_.At(pair->stamp, Seconds(pose_max_age_s_));
  if (pose.ok()) {
    const Eigen::Quaterniond q(pose->site_from_rover.linear());
    const Eigen::Vector3d t = pose->site_from_rover.translation();
    rover_pose.position = {t.x(), t.y(), t.z()};
    rover_pose.orientation = {q.w(), q.x(), q.y(), q.z()};
  } else if (require_pose_) {
    return pose.status().WithPrefix("rover pose at capture");
  } else {
    log::Warn("range image sent with an identity rover_pose",
              {{"reason", pose.status().message()}});
  }

  auto pipe = PipelineFor(st);
  if (!pipe.ok()) return pipe.status();
  StereoInput in;
  in.left = images.left;
  in.right = images.right;
  in.rectification = &st.maps;
  ROVER_RETURN_IF_ERROR((*pipe)->Process(in, &output_));
  const RectifiedStereoModel level_model = st.camera.model.Downsampled(output_.level);
  cv::Mat range, xyz;
  ROVER_RETURN_IF_ERROR(Reproject(level_model, st.camera.rover_from_camera, options_.reprojection,
                                  &output_.disparity, &range, &xyz));
  last_frame_stamp_ = pair->stamp;

  // ---- publish ----
  const int w = output_.disparity.disparity.cols;
  const int h = output_.disparity.disparity.rows;
  const auto n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  std::vector<float> xyz_out(3 * n);
  std::vector<std::uint8_t> valid_out(n);
  std::vector<float> disparity_out(n);
  std::size_t valid_count = 0;
  for (int v = 0; v < h; ++v) {
    const auto* st_row = output_.disparity.status.ptr<std::uint8_t>(v);
    const auto* d_row = output_.disparity.disparity.ptr<float>(v);
    const auto* p_row = xyz.ptr<cv::Vec3f>(v);
    for (int u = 0; u < w; ++u) {
      const std::size_t i =
          static_cast<std::size_t>(v) * static_cast<std::size_t>(w) + static_cast<std::size_t>(u);
      const bool ok = st_row[u] == static_cast<std::uint8_t>(PixelStatus::kValid);
      valid_out[i] = ok ? 1 : 0;
      disparity_out[i] = ok ? d_row[u] : -1.0F;
      const float nan = std::numeric_limits<float>::quiet_NaN();
      for (int k = 0; k < 3; ++k)
        xyz_out[3 * i + static_cast<std::size_t>(k)] = ok ? p_row[u][k] : nan;
      valid_count += ok ? 1 : 0;
    }
  }
  rover_dl_RangeImage out{};
  ctx_->Stamp(out.header, "rover");
  out.header.stamp_ns = pair->stamp.ns;  // capture time
  out.request_id = o.request.range_request_id;
  out.camera = m.camera;
  out.width = static_cast<std::uint16_t>(w);
  out.height = static_cast<std::uint16_t>(h);
  out.rover_pose = rover_pose;
  dds::BorrowSequence(out.xyz, xyz_out);
  dds::BorrowSequence(out.valid, valid_out);
  dds::BorrowSequence(out.disparity, disparity_out);
  ROVER_RETURN_IF_ERROR(range_writer_.Write(out).WithPrefix("dl/range_image write"));
  ++stats_.published;
  last_problem_.clear();
  UpdateHealth();
  log::Info(
      "range image published",
      {{"range_request_id", o.request.range_request_id},
       {"camera", CameraName(m.camera)},
       {"size", std::to_string(w) + "x" + std::to_string(h)},
       {"valid_fraction", n > 0 ? static_cast<double>(valid_count) / static_cast<double>(n) : 0.0},
       {"processing_ms", output_.timings.total_ms}});
  return Status::Ok();
}

// ---- timer, health ----------------------------------------------------------------------------

void StereoService::OnTimer() {
  const Time now = ctx_->Now();
  if (now < last_now_ - Seconds(kClockResetS)) {
    log::Info("run clock went back: pose history cleared, outstanding request re-sent",
              {{"from_s", last_now_.seconds()}, {"to_s", now.seconds()}});
    poses_.Clear();
    last_frame_stamp_.reset();
    if (outstanding_.has_value()) {
      queue_.push_front(outstanding_->request);
      outstanding_.reset();
    }
  }
  last_now_ = now;
  if (outstanding_.has_value() && ToSeconds(now - outstanding_->sent) > request_timeout_s_) {
    const Outstanding o = *outstanding_;
    outstanding_.reset();
    ++stats_.timeouts;
    Fail("ddl/camera_request timed out, no range image sent",
         {{"range_request_id", o.request.range_request_id},
          {"camera_request_id", o.camera_request_id},
          {"camera", CameraName(o.request.camera)},
          {"timeout_s", request_timeout_s_}});
  }
  SendNext();
  UpdateHealth();
}

void StereoService::Fail(const std::string& problem, std::initializer_list<log::Field> fields) {
  log::Warn(problem, fields);
  std::string detail = problem;
  for (const log::Field& f : fields) {
    if (f.key == "reason" || f.key == "range_request_id") detail += " " + f.key + "=" + f.value;
  }
  last_problem_ = detail;
  UpdateHealth();
}

void StereoService::UpdateHealth() {
  if (!last_problem_.empty()) {
    ctx_->SetHealth(rover_HEALTH_DEGRADED, last_problem_);
    return;
  }
  if (require_pose_ && ctx_->clock().valid()) {
    const auto latest = poses_.Latest();
    const double age = latest.has_value() ? ToSeconds(ctx_->Now() - latest->stamp) : -1.0;
    if (!latest.has_value() || age > pose_max_age_s_) {
      ctx_->SetHealth(rover_HEALTH_DEGRADED, latest.has_value()
                                                 ? "dl/pose is stale (" + Num(age) + " s old)"
                                                 : "no dl/pose received yet");
      return;
    }
  }
  ctx_->SetHealth(rover_HEALTH_OK, "");
}

}  // namespace rover::dl::stereo
