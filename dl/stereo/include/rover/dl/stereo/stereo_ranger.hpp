#pragma once
/// @file
/// StereoRanger: what dl-stereo does with an answered stereo frame, DDS-free. The models are
/// converted (msg::CameraModelFromFields) and rectified once per model pair (StereoSetupCache);
/// the raw pair is remapped, correlated and filtered by a StereoPipeline; the disparities are
/// reprojected with the rectified left camera's pose in the rover frame into a msg::RangeImage:
/// stamp = capture time, XYZ [m] in the rover frame (NaN where invalid), valid (1/0),
/// disparity [px of the processed image] (-1 where invalid), rover_pose = the pose history's
/// estimate at the capture time.
///
/// The disparity search range is stereo.num_disparities, or with 0 derived from the nearest
/// range of interest: ceil(f B / min_range_m) + 2 at the processing level, clamped to
/// [16, max_disparities]; one pipeline is kept per search range.
///
/// With a VehicleMask, points on the rover's own wheels and body or hidden behind them (seen from
/// the rectified left camera's optical centre) are invalid (status kWheel / kVehicle) before the
/// range image is built.

#include <Eigen/Geometry>
#include <array>
#include <map>
#include <memory>
#include <optional>
#include <string>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/dl/stereo/pipeline.hpp"
#include "rover/dl/stereo/setup_cache.hpp"
#include "rover/dl/stereo/vehicle_mask.hpp"
#include "rover/msg/camera.hpp"
#include "rover/msg/pose_history.hpp"
#include "rover/msg/range.hpp"

namespace rover::dl::stereo {

/// dl-stereo's keys stereo.* and rectification_cache_size (defaults: dl-stereo's).
struct StereoRangerOptions {
  int pyramid_levels = 0;
  int window = 7;
  int num_disparities = 0;  ///< 0 = derived from min_range_m
  int max_disparities = 256;
  double min_range_m = 0.3;
  double max_range_m = 50.0;
  PrefilterKind prefilter = PrefilterKind::kLaplacianOfGaussian;
  double uniqueness_ratio = 0.05;
  double min_curvature = 0.5;
  int lr_max_diff = 1;
  int blob_min_area = 40;
  bool overhang = true;
  int num_threads = 2;
  int rectification_cache_size = 4;

  /// The pipeline options these describe, with `num_disparities` as the search range.
  StereoOptions Pipeline(int num_disparities) const;
  /// max_range_m above min_range_m, and the pipeline's own checks (e.g. an odd window).
  Status Validate() const;
  static void BindParams(ParamBinder<StereoRangerOptions>& b);
};

/// Where the range image's rover_pose comes from.
struct PoseLookup {
  const msg::PoseHistory* poses = nullptr;  ///< not owned
  Duration max_age = Seconds(1.0);          ///< the estimate must lie this close to the capture
  bool required = true;  ///< no range image without it (else identity, with a warning)
};

class StereoRanger {
 public:
  /// Precondition: options.Validate() is Ok. Without `mask` no point is masked.
  explicit StereoRanger(const StereoRangerOptions& options,
                        std::optional<VehicleMask> mask = std::nullopt);

  /// Ranges a frame whose basics the camera client checked. Errors (nothing is produced): bad,
  /// corrupt or singular models, no pose at the capture time (when required), the pipeline's.
  Result<msg::RangeImage> Range(const msg::StereoFrame& frame, std::uint32_t request_id,
                                const PoseLookup& pose);

  /// Timings of the last Range() call.
  const StereoTimings& last_timings() const { return output_.timings; }
  const StereoSetupCache& setup_cache() const { return cache_; }
  const StereoRangerOptions& options() const { return options_; }
  /// Pixels the vehicle masks (fixed pixel mask and 3-D volumes) removed in the last Range().
  int last_masked() const { return last_masked_; }
  /// Fixed pixel mask of `camera` (CV_8UC1, non-zero = rover, any size: scaled to the rectified
  /// image, nearest neighbour). An empty mask removes it. Errors: unknown camera, wrong type.
  Status SetPixelMask(msg::CameraId camera, cv::Mat mask);

 private:
  Result<StereoPipeline*> PipelineFor(const StereoSetup& setup);

  StereoRangerOptions options_;
  StereoSetupCache cache_;
  std::map<int, StereoPipeline> pipelines_;  // by number of disparities
  StereoOutput output_;
  std::optional<VehicleMask> mask_;
  std::array<cv::Mat, msg::kNumCameras> pixel_masks_;
  cv::Mat scaled_pixel_mask_;
  int last_masked_ = 0;
};

}  // namespace rover::dl::stereo
