#pragma once
/// @file
/// VoPipeline: what dl-vo does with an answered stereo frame, DDS-free. Per frame:
///   1. the camera models are converted and rectified once per model pair (dl_stereo's
///      StereoSetupCache) and the raw pair is remapped into the rectified pinhole pair
///      VisualOdometry works on (equal principal points are required);
///   2. camera-change detection: if the rectified intrinsics change, VisualOdometry is
///      recreated; if the camera moved on the rover since the reference pair (mast pointing: more
///      than 1 mm or 1 mrad), the new pair only becomes the reference (no step across it);
///   3. the prior: the change of the dl/pose estimate between the two capture times (from the
///      pose history, within pose_max_age of each), in the rover frame (OdometryPrior), or a
///      vague prior when either pose is unknown;
///   4. visual odometry (camera frame), the result in the rover frame at t_from (ToBodyFrame
///      with the rectified left camera's pose in the rover frame) as the dl/relative_pose to
///      publish: source VISUAL_ODOMETRY, features = inliers when converged, else tracked.
/// Every processed pair becomes the reference of the next step (as on MER).
///
/// Frames and units: rover frame x forward, y left, z up; metres, radians; run-clock times.

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/dl/stereo/setup_cache.hpp"
#include "rover/dl/vo/odometry_prior.hpp"
#include "rover/dl/vo/visual_odometry.hpp"
#include "rover/msg/camera.hpp"
#include "rover/msg/pose.hpp"
#include "rover/msg/pose_history.hpp"

namespace rover::dl::vo {

/// dl-vo's keys vo.*, prior.* and rectification_cache_size.
struct VoPipelineOptions {
  Options vo = Options::Rover();
  OdometryPriorOptions prior;
  int rectification_cache_size = 2;  ///< camera-model pairs whose remap tables are kept

  /// The VO and prior options' checks (messages prefixed "vo options" / the field).
  Status Validate() const;
  static void BindParams(ParamBinder<VoPipelineOptions>& b);
};

/// The dl/relative_pose status of a library status (kNoReference has none: BAD_INPUT).
msg::RelativePoseStatus RelativePoseStatusOf(MotionStatus status);

class VoPipeline {
 public:
  /// Precondition: options.Validate() is Ok.
  explicit VoPipeline(const VoPipelineOptions& options);

  /// The outcome of one usable frame.
  struct Step {
    /// The estimate in the rover frame at t_from (status kNoReference: the pair only became
    /// the reference; then nothing is published).
    MotionEstimate estimate;
    /// What to publish on dl/relative_pose (absent for a reference pair).
    std::optional<msg::RelativePose> relative_pose;
    /// The rover pose for the cadence: at the capture time if known, else the latest.
    std::optional<msg::PoseSample> mark;
  };

  /// Processes a frame whose basics the camera client checked (camera, health, sizes, width,
  /// capture stamps). Errors (a bad frame; the pair does not become the reference): bad or
  /// singular models, rectification, principal points apart, visual odometry's errors.
  Result<Step> Process(const msg::StereoFrame& frame, const msg::PoseHistory& poses,
                       Duration pose_max_age);

  /// The RELPOSE_BAD_INPUT relative pose for a frame captured at `t_to` that could not be used
  /// (`why`): the prior's delta and covariance from the reference, so operators see the
  /// failure (the EKF ignores it). nullopt without a reference.
  std::optional<msg::RelativePose> BadInput(Time t_to, const msg::PoseHistory& poses,
                                            Duration pose_max_age) const;

  /// Forgets the reference (a run-clock reset).
  void Reset();

  bool has_reference() const { return reference_.has_value(); }
  const stereo::StereoSetupCache& setup_cache() const { return cache_; }
  const VoPipelineOptions& options() const { return options_; }

 private:
  struct Reference {
    Time stamp;
    std::optional<msg::PoseSample> pose;  // rover pose at capture, if known
    Eigen::Isometry3d rover_from_camera;  // rectified left camera
  };

  MotionPrior PriorTo(const std::optional<msg::PoseSample>& to) const;

  VoPipelineOptions options_;
  stereo::StereoSetupCache cache_;
  std::optional<VisualOdometry> vo_;
  std::optional<Reference> reference_;
  cv::Mat rect_left_, rect_right_;
};

}  // namespace rover::dl::vo
