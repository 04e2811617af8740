#include "rover/dl/vo/vo_pipeline.hpp"

#include <cmath>
#include <utility>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/log.hpp"
#include "rover/dl/stereo/frame_images.hpp"
#include "rover/dl/stereo/rectification.hpp"

namespace rover::dl::vo {
namespace {

// The rectified camera moved on the rover by more than this between two pairs: no VO step.
constexpr double kCameraMoveM = 1e-3;
constexpr double kCameraTurnRad = 1e-3;

bool SameCamera(const StereoCamera& a, const StereoCamera& b) {
  return a.width == b.width && a.height == b.height && a.fx == b.fx && a.fy == b.fy &&
         a.cx == b.cx && a.cy == b.cy && a.baseline == b.baseline;
}

bool CameraMoved(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::Isometry3d d = a.inverse() * b;
  return d.translation().norm() > kCameraMoveM || RotationAngle(d.linear()) > kCameraTurnRad;
}

std::optional<msg::PoseSample> PoseAt(const msg::PoseHistory& poses, Time t, Duration max_age) {
  if (auto p = poses.At(t, max_age); p.ok()) return *p;
  return std::nullopt;
}

msg::RelativePose ToMessage(const MotionEstimate& body, msg::RelativePoseStatus status,
                            std::uint32_t features) {
  msg::RelativePose r;
  r.stamp = body.t_to;
  r.source = msg::MotionSource::kVisualOdometry;
  r.t_from = body.t_from;
  r.t_to = body.t_to;
  r.delta = body.delta;
  r.covariance = body.covariance;
  r.status = status;
  r.features = features;
  return r;
}

}  // namespace

Status VoPipelineOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(prior.Validate());
  return vo.Validate().WithPrefix("vo options");
}

void VoPipelineOptions::BindParams(ParamBinder<VoPipelineOptions>& b) {
  b.Nest("vo.", &VoPipelineOptions::vo);
  b.Nest("prior.", &VoPipelineOptions::prior);
  b.Bind("rectification_cache_size", &VoPipelineOptions::rectification_cache_size, "",
         "camera-model pairs whose remap tables are kept")
      .Range(1, 32);
}

msg::RelativePoseStatus RelativePoseStatusOf(MotionStatus status) {
  switch (status) {
    case MotionStatus::kConverged:
      return msg::RelativePoseStatus::kConverged;
    case MotionStatus::kTooFewFeatures:
      return msg::RelativePoseStatus::kTooFewFeatures;
    case MotionStatus::kLimitsFailed:
      return msg::RelativePoseStatus::kLimitsFailed;
    case MotionStatus::kNotConverged:
      return msg::RelativePoseStatus::kNotConverged;
    case MotionStatus::kBadInput:
    case MotionStatus::kNoReference:
      return msg::RelativePoseStatus::kBadInput;
  }
  return msg::RelativePoseStatus::kBadInput;
}

VoPipeline::VoPipeline(const VoPipelineOptions& options)
    : options_(options), cache_(static_cast<std::size_t>(options.rectification_cache_size)) {
  ROVER_DEMAND(options_.Validate().ok());
}

MotionPrior VoPipeline::PriorTo(const std::optional<msg::PoseSample>& to) const {
  if (!reference_.has_value() || !reference_->pose.has_value() || !to.has_value()) {
    return VaguePrior(options_.prior);
  }
  return OdometryPrior(reference_->pose->site_from_rover, to->site_from_rover, options_.prior);
}

Result<VoPipeline::Step> VoPipeline::Process(const msg::StereoFrame& frame,
                                             const msg::PoseHistory& poses, Duration pose_max_age) {
  auto setup = cache_.Get(frame.left_model, frame.right_model);
  if (!setup.ok()) return setup.status();
  const stereo::StereoSetup& st = **setup;
  if (std::abs(st.camera.model.doffs_px) > 1e-9) {
    return InvalidArgument("rectified pair has principal points " +
                           FormatNumber(st.camera.model.doffs_px) +
                           " px apart; visual odometry needs equal ones");
  }
  const stereo::FrameImages images = stereo::ViewFrameImages(frame);
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
    ROVER_ASSIGN_OR_RETURN(VisualOdometry vo, VisualOdometry::Create(options_.vo, cam));
    if (reference_.has_value()) {
      log::Warn("rectified camera changed: visual odometry restarted from this pair",
                {{"fx", cam.fx}, {"width", cam.width}, {"baseline", cam.baseline}});
    }
    vo_.emplace(std::move(vo));
    reference_.reset();
  } else if (reference_.has_value() &&
             CameraMoved(reference_->rover_from_camera, st.camera.rover_from_camera)) {
    log::Warn(
        "camera moved on the rover since the last pair: no step, this pair is the new "
        "reference",
        {{"camera", msg::CameraName(frame.camera)}});
    vo_->Reset();
    reference_.reset();
  }

  const std::optional<msg::PoseSample> pose = PoseAt(poses, frame.stamp, pose_max_age);
  const MotionPrior body_prior = PriorTo(pose);
  if (reference_.has_value() && !pose.has_value()) {
    log::Warn("no dl/pose at the capture time: vague prior", {{"t_s", frame.stamp.seconds()}});
  }
  const Eigen::Isometry3d& t_rc = st.camera.rover_from_camera;
  StereoFrame rectified;
  rectified.stamp = frame.stamp;
  rectified.left = rect_left_;
  rectified.right = rect_right_;
  auto est = vo_->Process(rectified, ToCameraFrame(body_prior, t_rc));
  if (!est.ok()) return est.status().WithPrefix("visual odometry");

  Step step;
  step.mark = pose.has_value() ? pose : poses.Latest();
  reference_ = Reference{frame.stamp, pose, t_rc};
  if (est->status == MotionStatus::kNoReference) {
    step.estimate = *est;
    return step;
  }
  step.estimate = ToBodyFrame(*est, t_rc);
  step.relative_pose = ToMessage(
      step.estimate, RelativePoseStatusOf(est->status),
      static_cast<std::uint32_t>(est->converged() ? est->inliers : est->features_tracked));
  return step;
}

std::optional<msg::RelativePose> VoPipeline::BadInput(Time t_to, const msg::PoseHistory& poses,
                                                      Duration pose_max_age) const {
  if (!reference_.has_value()) return std::nullopt;
  const MotionPrior prior = PriorTo(PoseAt(poses, t_to, pose_max_age));
  MotionEstimate e;
  e.status = MotionStatus::kBadInput;
  e.t_from = reference_->stamp;
  e.t_to = t_to;
  e.delta = prior.delta;
  e.covariance = prior.covariance;
  return ToMessage(e, msg::RelativePoseStatus::kBadInput, 0);
}

void VoPipeline::Reset() {
  if (vo_.has_value()) vo_->Reset();
  reference_.reset();
}

}  // namespace rover::dl::vo
