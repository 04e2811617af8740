// dl-vo: binds MER visual odometry (dl_vo) to dl/pose, ddl/camera_request, ddl/stereo_frame and
// dl/relative_pose. See vo_service.hpp and docs/services/dl-vo.md.
#include "vo_service.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include "rover/base/check.hpp"
#include "rover/dl/stereo/frame_images.hpp"
#include "rover/dl/stereo/rectification.hpp"
#include "rover/msg/camera_idl.hpp"
#include "rover/msg/pose_idl.hpp"

namespace rover::dl::vo {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
// A capture stamp this much before the request was sent is a stale (or reordered) frame.
constexpr double kCaptureSkewS = 0.1;
// The run clock going back by more than this is a reset (simulator reset).
constexpr double kClockResetS = 1.0;
// The rectified camera moved on the rover by more than this between two pairs: no VO step.
constexpr double kCameraMoveM = 1e-3;
constexpr double kCameraTurnRad = 1e-3;

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

rover_CameraId CameraFromName(const std::string& name) {
  if (name == "navcam") return rover_CAMERA_NAVCAM;
  if (name == "rear_hazcam") return rover_CAMERA_REAR_HAZCAM;
  return rover_CAMERA_FRONT_HAZCAM;
}

std::string Num(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

bool SameCamera(const StereoCamera& a, const StereoCamera& b) {
  return a.width == b.width && a.height == b.height && a.fx == b.fx && a.fy == b.fy &&
         a.cx == b.cx && a.cy == b.cy && a.baseline == b.baseline;
}

bool CameraMoved(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::Isometry3d d = a.inverse() * b;
  return d.translation().norm() > kCameraMoveM || RotationAngle(d.linear()) > kCameraTurnRad;
}

struct Config {
  CadenceOptions cadence;
  OdometryPriorOptions prior;
  Options vo = Options::Rover();
};

// The library options the parameters describe; errors name the parameter or field.
Result<Config> ConfigFromParams(const ParamSet& p) {
  Config c;
  c.cadence.step_distance = p.GetDouble("step_distance");
  c.cadence.step_angle = p.GetDouble("step_angle_deg") * kDeg;
  c.cadence.max_interval_s = p.GetDouble("max_interval_s");
  c.cadence.moving_speed = p.GetDouble("moving_speed");
  c.cadence.moving_rate = p.GetDouble("moving_rate_deg_s") * kDeg;
  c.cadence.settle_s = p.GetDouble("settle_s");
  c.cadence.min_distance = p.GetDouble("min_distance");
  c.cadence.min_angle = p.GetDouble("min_angle_deg") * kDeg;
  ROVER_RETURN_IF_ERROR(c.cadence.Validate());

  c.prior.translation_sigma_min = p.GetDouble("prior.translation_sigma_min");
  c.prior.translation_sigma_fraction = p.GetDouble("prior.translation_sigma_fraction");
  c.prior.rotation_sigma_min = p.GetDouble("prior.rotation_sigma_min_deg") * kDeg;
  c.prior.rotation_sigma_fraction = p.GetDouble("prior.rotation_sigma_fraction");
  c.prior.vague_translation_sigma = p.GetDouble("prior.vague_translation_sigma");
  c.prior.vague_rotation_sigma = p.GetDouble("prior.vague_rotation_sigma_deg") * kDeg;
  ROVER_RETURN_IF_ERROR(c.prior.Validate());

  c.vo.pixel_sigma = p.GetDouble("vo.pixel_sigma");
  c.vo.min_range = p.GetDouble("vo.min_range");
  c.vo.max_range = p.GetDouble("vo.max_range");
  c.vo.interest.cell_size = static_cast<int>(p.GetInt("vo.cell_size"));
  c.vo.interest.min_separation = p.GetDouble("vo.min_separation");
  c.vo.min_features = static_cast<int>(p.GetInt("vo.min_features"));
  c.vo.min_inliers = static_cast<int>(p.GetInt("vo.min_inliers"));
  c.vo.min_inlier_fraction = p.GetDouble("vo.min_inlier_fraction");
  c.vo.max_translation = p.GetDouble("vo.max_translation");
  c.vo.max_rotation = p.GetDouble("vo.max_rotation_deg") * kDeg;
  c.vo.max_prior_mahalanobis_sq = p.GetDouble("vo.max_prior_mahalanobis_sq");
  ROVER_RETURN_IF_ERROR(c.vo.Validate().WithPrefix("vo options"));
  if (c.cadence.step_distance >= c.vo.max_translation) {
    return InvalidArgument("step_distance " + Num(c.cadence.step_distance) +
                           " m must be below vo.max_translation " + Num(c.vo.max_translation) +
                           " m");
  }

  return c;
}

}  // namespace

Status VoService::ValidateParameters(const ParamSet& p) const {
  return ConfigFromParams(p).status();
}

rover_dl_RelativePoseStatus RelativePoseStatusOf(MotionStatus status) {
  switch (status) {
    case MotionStatus::kConverged:
      return rover_dl_RELPOSE_CONVERGED;
    case MotionStatus::kTooFewFeatures:
      return rover_dl_RELPOSE_TOO_FEW_FEATURES;
    case MotionStatus::kLimitsFailed:
      return rover_dl_RELPOSE_LIMITS_FAILED;
    case MotionStatus::kNotConverged:
      return rover_dl_RELPOSE_NOT_CONVERGED;
    case MotionStatus::kBadInput:
    case MotionStatus::kNoReference:
      return rover_dl_RELPOSE_BAD_INPUT;
  }
  return rover_dl_RELPOSE_BAD_INPUT;
}

// ---- parameters -------------------------------------------------------------------------------

void VoService::DeclareParameters(ParamSet& p) {
  p.Declare("camera", "front_hazcam",
            "stereo pair used: front_hazcam (fixed, 45 deg down), navcam (mast; keep it still "
            "while driving, MER pointed it ~45 deg down) or rear_hazcam")
      .OneOf({"front_hazcam", "navcam", "rear_hazcam"});
  p.Declare("width", 512,
            "[px] processing width asked of the camera driver; 0 = full size. MER processed "
            "256x256 NAVCAM images; the 120 deg HAZCAM needs 512 for enough tracked features")
      .Range(0, 4096);
  p.Declare("exposure_us", 0, "[us] exposure asked of the camera driver; 0 = auto")
      .Range(0, 10000000);
  const CadenceOptions c;
  p.Declare("step_distance", c.step_distance,
            "[m] odometer travelled between two pairs while driving (MER: <= ~0.6 m)")
      .Range(0.05, 0.9);
  p.Declare("step_angle_deg", c.step_angle / kDeg,
            "[deg] turn between two pairs while driving (turns in place move no odometer)")
      .Range(1.0, 20.0);
  p.Declare("max_interval_s", c.max_interval_s,
            "[s] run-clock time between two pairs while driving, at most")
      .Range(0.5, 3600.0);
  p.Declare("moving_speed", c.moving_speed,
            "[m/s] dl/pose speed or odometer rate above which the rover is driving")
      .Range(0.0001, 1.0);
  p.Declare("moving_rate_deg_s", c.moving_rate / kDeg,
            "[deg/s] turn rate above which the rover is driving")
      .Range(0.001, 30.0);
  p.Declare("settle_s", c.settle_s, "[s] at rest before the end-of-drive pair").Range(0.0, 60.0);
  p.Declare("min_distance", c.min_distance,
            "[m] moved since the last pair for an end-of-drive pair")
      .Range(0.0, 0.9);
  p.Declare("min_angle_deg", c.min_angle / kDeg,
            "[deg] turned since the last pair for an end-of-drive pair")
      .Range(0.0, 20.0);
  p.Declare("request_timeout_s", 10.0,
            "[s] run-clock time the camera driver has to answer a ddl/camera_request")
      .Range(0.1, 600.0);
  p.Declare("retry_delay_s", 1.0, "[s] run-clock wait after a bad frame before the next request")
      .Range(0.0, 600.0);
  p.Declare("pose_max_age_s", 1.0,
            "[s] dl/pose must lie within this of a capture time (for the prior) and of now (else "
            "the cadence pauses)")
      .Range(0.01, 60.0);
  p.Declare("request_id_prefix", 2,
            "top 8 bits of this service's ddl/camera_request ids (dl-stereo uses 1)")
      .Range(1, 255);
  p.Declare("poll_rate_hz", 10.0, "[Hz] run-clock rate of the cadence, timeout and health checks")
      .Range(1.0, 100.0);
  p.Declare("rectification_cache_size", 2, "camera-model pairs whose remap tables are kept")
      .Range(1, 32);
  const OdometryPriorOptions o;
  p.Declare("prior.translation_sigma_min", o.translation_sigma_min,
            "[m] wheel-odometry prior: 1-sigma translation floor")
      .Range(0.001, 10.0);
  p.Declare("prior.translation_sigma_fraction", o.translation_sigma_fraction,
            "wheel-odometry prior: added 1-sigma per metre of step (slip)")
      .Range(0.0, 10.0);
  p.Declare("prior.rotation_sigma_min_deg", o.rotation_sigma_min / kDeg,
            "[deg] wheel-odometry prior: 1-sigma rotation floor")
      .Range(0.01, 90.0);
  p.Declare("prior.rotation_sigma_fraction", o.rotation_sigma_fraction,
            "wheel-odometry prior: added 1-sigma per radian of turn")
      .Range(0.0, 10.0);
  p.Declare("prior.vague_translation_sigma", o.vague_translation_sigma,
            "[m] prior 1-sigma when dl/pose is missing at a capture time")
      .Range(0.01, 10.0);
  p.Declare("prior.vague_rotation_sigma_deg", o.vague_rotation_sigma / kDeg,
            "[deg] prior 1-sigma when dl/pose is missing at a capture time")
      .Range(0.1, 90.0);
  const Options v = Options::Rover();
  p.Declare("vo.pixel_sigma", v.pixel_sigma, "[px] 1-sigma matching noise in the covariance")
      .Range(0.01, 10.0);
  p.Declare("vo.min_range", v.min_range, "[m] nearer features are dropped").Range(0.05, 100.0);
  p.Declare("vo.max_range", v.max_range, "[m] farther features are dropped").Range(0.1, 1000.0);
  p.Declare("vo.cell_size", v.interest.cell_size,
            "[px] interest-operator grid cell (one feature per cell)")
      .Range(4, 256);
  p.Declare("vo.min_separation", v.interest.min_separation, "[px] between two features")
      .Range(0.0, 256.0);
  p.Declare("vo.min_features", v.min_features, "tracked features needed").Range(3, 10000);
  p.Declare("vo.min_inliers", v.min_inliers, "RANSAC/ML inliers needed").Range(3, 10000);
  p.Declare("vo.min_inlier_fraction", v.min_inlier_fraction, "inliers / tracked, at least")
      .Range(0.0, 1.0);
  p.Declare("vo.max_translation", v.max_translation, "[m] of one step, at most (sanity limit)")
      .Range(0.01, 10.0);
  p.Declare("vo.max_rotation_deg", v.max_rotation / kDeg,
            "[deg] of one step, at most (sanity limit)")
      .Range(0.1, 90.0);
  p.Declare("vo.max_prior_mahalanobis_sq", v.max_prior_mahalanobis_sq,
            "gate on the estimate's distance from the odometry prior; 0 = off")
      .Range(0.0, 1e6);
}

Status VoService::OnConfigure(ServiceContext& ctx, const ParamSet& p) {
  ctx_ = &ctx;
  camera_ = CameraFromName(p.GetString("camera"));
  width_ = static_cast<std::uint16_t>(p.GetInt("width"));
  exposure_us_ = static_cast<std::uint32_t>(p.GetInt("exposure_us"));
  request_timeout_s_ = p.GetDouble("request_timeout_s");
  retry_delay_s_ = p.GetDouble("retry_delay_s");
  pose_max_age_s_ = p.GetDouble("pose_max_age_s");
  request_prefix_ = static_cast<std::uint32_t>(p.GetInt("request_id_prefix"));

  auto config = ConfigFromParams(p);
  if (!config.ok()) return config.status();
  cadence_options_ = config->cadence;
  prior_options_ = config->prior;
  vo_options_ = config->vo;

  cadence_ = std::make_unique<VoCadence>(cadence_options_);
  cache_ = std::make_unique<stereo::StereoSetupCache>(
      static_cast<std::size_t>(p.GetInt("rectification_cache_size")));
  // Poses for the longest gap between two pairs (interval or timeout) at >= 8 Hz, and more.
  poses_ = stereo::PoseHistory(static_cast<std::size_t>(
      std::max(256.0, 20.0 * (cadence_options_.max_interval_s + request_timeout_s_))));

  auto rw = ctx.MakeWriter<rover_ddl_StereoRequest>("ddl/camera_request");
  if (!rw.ok()) return rw.status();
  request_writer_ = std::move(*rw);
  auto pw = ctx.MakeWriter<rover_dl_RelativePose>("dl/relative_pose");
  if (!pw.ok()) return pw.status();
  relpose_writer_ = std::move(*pw);

  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_PoseEstimate>(
      "dl/pose", [this](const dds::Sample<rover_dl_PoseEstimate>& s) { OnPose(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_StereoFrame>(
      "ddl/stereo_frame",
      [this](const dds::Sample<rover_ddl_StereoFrame>& s) { OnStereoFrame(s.data()); }));
  ctx.executor().AddTimer(Seconds(1.0 / p.GetDouble("poll_rate_hz")), [this] { OnTimer(); });
  ctx.SetHealth(rover_HEALTH_DEGRADED, "no dl/pose received yet: visual odometry waiting");
  return Status::Ok();
}

// ---- inputs -----------------------------------------------------------------------------------

void VoService::OnPose(const rover_dl_PoseEstimate& m) {
  auto sample = msg::PoseSampleFromIdl(m);
  if (!sample.ok()) {
    log::Warn("dl/pose sample dropped", {{"reason", sample.status().message()}});
    return;
  }
  Status s = poses_.Add(*sample);
  if (s.code() == StatusCode::kOutOfRange) {
    const auto latest = poses_.Latest();
    if (latest.has_value() && ToSeconds(latest->stamp - sample->stamp) > kClockResetS) {
      ResetAll("dl/pose went back in time (run-clock reset)");
      s = poses_.Add(*sample);
    }
  }
  if (!s.ok()) {
    log::Debug("dl/pose sample dropped", {{"reason", s.message()}});
    return;
  }
  cadence_->OnPose(sample->stamp, sample->odometer, sample->velocity.norm(),
                   Eigen::Quaterniond(sample->site_from_rover.linear()), sample->stationary);
}

void VoService::OnTimer() {
  const Time now = ctx_->Now();
  if (now < last_now_ - Seconds(kClockResetS)) ResetAll("the run clock went back");
  last_now_ = now;
  if (outstanding_.has_value() && ToSeconds(now - outstanding_->sent) > request_timeout_s_) {
    const Outstanding o = *outstanding_;
    outstanding_.reset();
    ++stats_.timeouts;
    Problem("ddl/camera_request timed out", {{"camera_request_id", o.id},
                                             {"camera", CameraName(camera_)},
                                             {"timeout_s", request_timeout_s_}});
  }
  MaybeRequest(now);
  UpdateHealth();
}

void VoService::MaybeRequest(Time now) {
  if (outstanding_.has_value() || now < hold_until_) return;
  const auto latest = poses_.Latest();
  if (!latest.has_value() || ToSeconds(now - latest->stamp) > pose_max_age_s_) return;
  const VoCadence::Reason reason = cadence_->Due(now);
  if (reason == VoCadence::Reason::kNone) return;
  counter_ = (counter_ + 1) & 0xFFFFFFu;
  if (counter_ == 0) counter_ = 1;
  rover_ddl_StereoRequest m{};
  ctx_->Stamp(m.header, "rover");
  m.request_id = (request_prefix_ << 24) | counter_;
  m.camera = camera_;
  m.exposure_us = exposure_us_;
  m.width = width_;
  const Status s = request_writer_.Write(m);
  if (!s.ok()) {
    Problem("ddl/camera_request write failed", {{"error", s.message()}});
    hold_until_ = now + Seconds(retry_delay_s_);
    return;
  }
  ++stats_.camera_requests;
  outstanding_ = Outstanding{m.request_id, now, reason};
  log::Debug("vo pair requested", {{"camera_request_id", m.request_id},
                                   {"reason", CadenceReasonName(reason)},
                                   {"odometer", latest->odometer}});
}

void VoService::OnStereoFrame(const rover_ddl_StereoFrame& m) {
  if (!outstanding_.has_value() || m.request_id != outstanding_->id) return;  // not ours
  const Outstanding o = *outstanding_;
  outstanding_.reset();
  ++stats_.frames;
  const Status s = Process(o, m);
  if (!s.ok()) {
    ++stats_.bad_frames;
    hold_until_ = ctx_->Now() + Seconds(retry_delay_s_);
    Problem(
        "ddl/stereo_frame dropped",
        {{"camera_request_id", o.id}, {"camera", CameraName(camera_)}, {"reason", s.message()}});
    if (reference_.has_value()) PublishBadInput(Time{m.header.stamp_ns}, s.message());
  }
  UpdateHealth();
}

// ---- processing -------------------------------------------------------------------------------

MotionPrior VoService::PriorTo(const std::optional<msg::PoseSample>& to) const {
  if (!reference_.has_value() || !reference_->pose.has_value() || !to.has_value()) {
    return VaguePrior(prior_options_);
  }
  return OdometryPrior(reference_->pose->site_from_rover, to->site_from_rover, prior_options_);
}

Status VoService::Process(const Outstanding& o, const rover_ddl_StereoFrame& m) {
  if (m.camera != camera_) {
    return InvalidArgument(std::string("frame is from camera ") + CameraName(m.camera) +
                           ", requested " + CameraName(camera_));
  }
  if (m.health == rover_HEALTH_FAILED || m.health == rover_HEALTH_STALE) {
    return InvalidArgument("frame health is " +
                           std::string(m.health == rover_HEALTH_FAILED ? "FAILED" : "STALE"));
  }
  auto pair = msg::StereoFrameFromIdl(m);
  if (!pair.ok()) return pair.status();
  const stereo::FrameImages images = stereo::ViewFrameImages(*pair);
  if (width_ != 0 && pair->width != width_) {
    return InvalidArgument("frame is " + std::to_string(pair->width) + " px wide, requested " +
                           std::to_string(width_));
  }
  if (pair->stamp < o.sent - Seconds(kCaptureSkewS)) {
    return InvalidArgument("capture stamp " + Num(pair->stamp.seconds()) +
                           " s is before the request was sent (" + Num(o.sent.seconds()) +
                           " s): stale or out of time order");
  }
  if (last_frame_stamp_.has_value() && pair->stamp <= *last_frame_stamp_) {
    return InvalidArgument("capture stamp " + Num(pair->stamp.seconds()) +
                           " s is not after the previous pair's (" +
                           Num(last_frame_stamp_->seconds()) + " s): out of time order");
  }
  auto setup = cache_->Get(pair->left_model, pair->right_model);
  if (!setup.ok()) return setup.status();
  const stereo::StereoSetup& st = **setup;
  if (std::abs(st.camera.model.doffs_px) > 1e-9) {
    return InvalidArgument("rectified pair has principal points " + Num(st.camera.model.doffs_px) +
                           " px apart; visual odometry needs equal ones");
  }
  ROVER_RETURN_IF_ERROR(
      stereo::Rectify(st.maps, images.left, images.right, &rect_left_, &rect_right_));

  StereoCamera cam;
  cam.width = rect_left_.cols;
  cam.height = rect_left_.rows;
  cam.fx = cam.fy = st.camera.model.focal_px;
  cam.cx = st.camera.model.cx;
  cam.cy = st.camera.model.cy;
  cam.baseline = st.camera.model.baseline_m;
  if (!vo_.has_value() || !SameCamera(vo_->camera(), cam)) {
    auto vo = VisualOdometry::Create(vo_options_, cam);
    if (!vo.ok()) return vo.status();
    if (reference_.has_value()) {
      log::Warn("rectified camera changed: visual odometry restarted from this pair",
                {{"fx", cam.fx}, {"width", cam.width}, {"baseline", cam.baseline}});
    }
    vo_.emplace(std::move(*vo));
    reference_.reset();
  } else if (reference_.has_value() &&
             CameraMoved(reference_->rover_from_camera, st.camera.rover_from_camera)) {
    log::Warn(
        "camera moved on the rover since the last pair: no step, this pair is the new "
        "reference",
        {{"camera", CameraName(camera_)}});
    vo_->Reset();
    reference_.reset();
  }

  std::optional<msg::PoseSample> pose;
  if (auto p = poses_.At(pair->stamp, Seconds(pose_max_age_s_)); p.ok()) pose = *p;
  const MotionPrior body_prior = PriorTo(pose);
  if (reference_.has_value() && !pose.has_value()) {
    log::Warn("no dl/pose at the capture time: vague prior", {{"t_s", pair->stamp.seconds()}});
  }
  const Eigen::Isometry3d& t_rc = st.camera.rover_from_camera;
  StereoFrame frame;
  frame.stamp = pair->stamp;
  frame.left = rect_left_;
  frame.right = rect_right_;
  auto est = vo_->Process(frame, ToCameraFrame(body_prior, t_rc));
  if (!est.ok()) return est.status().WithPrefix("visual odometry");

  last_frame_stamp_ = pair->stamp;
  const std::optional<msg::PoseSample> mark = pose.has_value() ? pose : poses_.Latest();
  if (mark.has_value()) {
    cadence_->MarkCaptured(pair->stamp, mark->odometer,
                           Eigen::Quaterniond(mark->site_from_rover.linear()));
  }
  reference_ = Reference{pair->stamp, pose, t_rc};

  if (est->status == MotionStatus::kNoReference) {
    ++stats_.references;
    last_problem_.clear();
    log::Info("visual odometry reference pair", {{"t_s", pair->stamp.seconds()},
                                                 {"features", est->features_selected},
                                                 {"reason", CadenceReasonName(o.reason)}});
    return Status::Ok();
  }
  const MotionEstimate body = ToBodyFrame(*est, t_rc);
  const rover_dl_RelativePoseStatus status = RelativePoseStatusOf(est->status);
  Publish(body, status,
          static_cast<std::uint32_t>(est->converged() ? est->inliers : est->features_tracked));
  if (est->converged()) {
    ++stats_.converged;
    last_problem_.clear();
    log::Info("visual odometry step", {{"dx", body.delta.translation().x()},
                                       {"dy", body.delta.translation().y()},
                                       {"dz", body.delta.translation().z()},
                                       {"inliers", est->inliers},
                                       {"reason", CadenceReasonName(o.reason)}});
  } else {
    Problem("visual odometry step failed", {{"status", MotionStatusName(est->status)},
                                            {"reason", est->message},
                                            {"features", est->features_tracked}});
  }
  return Status::Ok();
}

// ---- outputs ----------------------------------------------------------------------------------

void VoService::Publish(const MotionEstimate& body, rover_dl_RelativePoseStatus status,
                        std::uint32_t features) {
  rover_dl_RelativePose r{};
  ctx_->Stamp(r.header, "rover");
  r.header.stamp_ns = body.t_to.ns;
  r.source = rover_dl_SOURCE_VISUAL_ODOMETRY;
  r.t_from_ns = body.t_from.ns;
  r.t_to_ns = body.t_to.ns;
  const Eigen::Vector3d t = body.delta.translation();
  const Eigen::Quaterniond q(body.delta.linear());
  r.delta.position = {t.x(), t.y(), t.z()};
  r.delta.orientation = {q.w(), q.x(), q.y(), q.z()};
  for (int i = 0; i < 6; ++i) {
    for (int j = 0; j < 6; ++j) r.covariance[i * 6 + j] = body.covariance(i, j);
  }
  r.status = status;
  r.features = features;
  const Status s = relpose_writer_.Write(r);
  if (!s.ok()) {
    Problem("dl/relative_pose write failed", {{"error", s.message()}});
    return;
  }
  ++stats_.published;
}

void VoService::PublishBadInput(Time t_to, const std::string& why) {
  std::optional<msg::PoseSample> pose;
  if (auto p = poses_.At(t_to, Seconds(pose_max_age_s_)); p.ok()) pose = *p;
  const MotionPrior prior = PriorTo(pose);
  MotionEstimate e;
  e.status = MotionStatus::kBadInput;
  e.t_from = reference_->stamp;
  e.t_to = t_to;
  e.delta = prior.delta;
  e.covariance = prior.covariance;
  e.message = why;
  Publish(e, rover_dl_RELPOSE_BAD_INPUT, 0);
}

// ---- health -----------------------------------------------------------------------------------

void VoService::Problem(const std::string& problem, std::initializer_list<log::Field> fields) {
  log::Warn(problem, fields);
  std::string detail = problem;
  for (const log::Field& f : fields) {
    if (f.key == "reason" || f.key == "status") detail += " " + f.key + "=" + f.value;
  }
  last_problem_ = detail;
  UpdateHealth();
}

void VoService::UpdateHealth() {
  if (!last_problem_.empty()) {
    ctx_->SetHealth(rover_HEALTH_DEGRADED, last_problem_);
    return;
  }
  const auto latest = poses_.Latest();
  if (!latest.has_value()) {
    ctx_->SetHealth(rover_HEALTH_DEGRADED, "no dl/pose received yet: visual odometry waiting");
    return;
  }
  if (ctx_->clock().valid()) {
    const double age = ToSeconds(ctx_->Now() - latest->stamp);
    if (age > pose_max_age_s_) {
      ctx_->SetHealth(rover_HEALTH_DEGRADED,
                      "dl/pose is stale (" + Num(age) + " s old): visual odometry paused");
      return;
    }
  }
  ctx_->SetHealth(rover_HEALTH_OK, "");
}

void VoService::ResetAll(const std::string& why) {
  log::Info("visual odometry restarted", {{"reason", why}});
  poses_.Clear();
  cadence_->Reset();
  if (vo_.has_value()) vo_->Reset();
  reference_.reset();
  outstanding_.reset();
  last_frame_stamp_.reset();
  hold_until_ = Time{0};
}

}  // namespace rover::dl::vo
