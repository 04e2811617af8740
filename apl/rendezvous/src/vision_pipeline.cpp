#include "rover/apl/rendezvous/vision_pipeline.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>

#include "rover/base/format.hpp"

namespace rover::apl::rendezvous {
namespace {

std::shared_ptr<cv::Mat> Bgr(const cv::Mat& gray) {
  auto out = std::make_shared<cv::Mat>();
  cv::cvtColor(gray, *out, cv::COLOR_GRAY2BGR);
  return out;
}

std::string Name(const char* what, int n) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%s_%02d", what, n);
  return buf;
}

}  // namespace

VisionPipeline::VisionPipeline(const hwconfig::LanderDescription& lander,
                               const VisionOptions& options)
    : lander_(lander), options_(options) {}

DetectionImage VisionPipeline::LastDrawing() {
  DetectionImage d = std::move(drawing_);
  drawing_ = {};
  return d;
}

Result<LanderFix> VisionPipeline::SightFar(const NavcamPair& pair, LanderPrior prior) {
  const cv::Mat none;
  prior.bearing_window = FarSearchHalfWindow(prior.range, options_.prior_gate);
  prior.range_window = options_.prior_gate + 0.3 * prior.range;
  ROVER_ASSIGN_OR_RETURN(const FarSighting s,
                         DetectLanderFar(*pair.left, *pair.left_model,
                                         pair.right != nullptr ? *pair.right : none,
                                         pair.right != nullptr ? pair.right_model : nullptr,
                                         lander_, options_.far, prior));
  auto bgr = Bgr(*pair.left);
  DrawFarSighting(bgr.get(), s);
  drawing_ = {Name("far", ++sightings_), bgr};
  LanderFix f;
  f.found = s.found;
  f.far = true;
  f.why = s.reason;
  f.features = s.features;
  if (!s.found) return f;
  f.center_rover = s.center;
  f.covariance = s.center_covariance;
  return f;
}

Result<LanderFix> VisionPipeline::SightLander(const NavcamPair& pair,
                                              const Eigen::Vector3d& prior_rover) {
  if (pair.left == nullptr || pair.left_model == nullptr) {
    return InvalidArgument("NAVCAM pair without a left image or model");
  }
  const cv::Mat none;
  LanderPrior prior;  // from R's origin, as the detector measures
  prior.bearing = std::atan2(prior_rover.y(), prior_rover.x());
  prior.range = std::max(1.0, std::hypot(prior_rover.x(), prior_rover.y()));
  prior.ground_z = prior_rover.z();
  if (prior.range > options_.far_range) return SightFar(pair, prior);
  prior.bearing_window = std::clamp(std::atan2(options_.prior_gate, prior.range), 0.05, 0.45);
  prior.range_window = options_.prior_gate + 0.1 * prior.range;
  ROVER_ASSIGN_OR_RETURN(
      const LanderSighting s,
      DetectLander(*pair.left, pair.right != nullptr ? *pair.right : none, *pair.left_model,
                   pair.right != nullptr ? pair.right_model : nullptr, lander_, options_.lander,
                   prior));
  // Where the two detectors' ranges overlap (the mid-range one misses some views at 25-35 m,
  // e.g. along the ramp axis), a mid-range miss falls back to the long-range detector.
  if (!s.found && prior.range >= options_.far.min_range) {
    ROVER_ASSIGN_OR_RETURN(LanderFix far, SightFar(pair, prior));
    if (far.found) {
      far.features = "mid range: " + s.reason + "; " + far.features;
      return far;
    }
  }
  auto bgr = Bgr(*pair.left);
  DrawLanderSighting(bgr.get(), s);
  drawing_ = {Name("lander", ++sightings_), bgr};
  LanderFix f;
  f.found = s.found;
  f.why = s.reason;
  f.features = s.features;
  if (!s.found) return f;
  f.center_rover = s.center;  // deck top centre, rover frame (range and bearing from R's origin)
  f.covariance = s.center_covariance;
  return f;
}

Result<RampFix> VisionPipeline::SightRamp(const NavcamPair& pair) {
  if (pair.left == nullptr || pair.left_model == nullptr) {
    return InvalidArgument("NAVCAM pair without a left image or model");
  }
  ROVER_ASSIGN_OR_RETURN(const StripeDetection left, DetectStripes(*pair.left, options_.stripes));
  std::optional<StripeDetection> right;
  if (pair.right != nullptr && pair.right_model != nullptr) {
    ROVER_ASSIGN_OR_RETURN(right, DetectStripes(*pair.right, options_.stripes));
  }
  auto bgr = Bgr(*pair.left);
  DrawStripeDetection(bgr.get(), left);
  drawing_ = {Name("stripes", ++sightings_), bgr};
  RampFix f;
  f.ramp = left.BestRamp();
  f.stripes = f.ramp >= 0 ? static_cast<int>(left.OfRamp(f.ramp).size()) : 0;
  f.features = "stripes " + std::to_string(f.stripes) +
               (f.ramp >= 0 ? " (ramp " + std::to_string(f.ramp) + ")" : "");
  if (f.ramp < 0) {
    f.why = left.why.empty() ? "no stripes identified" : left.why;
    return f;
  }
  RampPoseOptions po = options_.pose;
  po.ramp = f.ramp;
  const Result<RampPose> pose = EstimateRampPose(lander_, left, *pair.left_model,
                                                 right ? &*right : nullptr,
                                                 right ? pair.right_model : nullptr, po);
  if (!pose.ok()) {
    f.why = pose.status().message();
    return f;  // found stays false: too few stripes or no convergence
  }
  f.found = true;
  f.stripes = pose->stripes_used;
  f.rms_px = pose->rms_px;
  f.rover_from_ramp = pose->rover_from_ramp;
  // Sigmas: translation block (in G, near-isotropic) and the rotation about w (yaw).
  f.base_sigma = std::sqrt(std::max(0.0, pose->covariance.topLeftCorner<3, 3>().trace() / 3.0));
  f.yaw_sigma = std::sqrt(std::max(0.0, pose->covariance(5, 5)));
  f.features = "stripes " + std::to_string(pose->stripes_used) + " (ramp " +
               std::to_string(f.ramp) + "), " + FormatNumber(pose->rms_px) + " px";
  return f;
}

}  // namespace rover::apl::rendezvous
