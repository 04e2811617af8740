#pragma once
/// @file
/// The whole stereo ranging step of JPL/MER-style rover navigation, per image pair:
///
///   raw pair --rectify (optional maps)--> rectified pair --8-bit + gamma--> --pyramid (2x2
///   block means, L levels)--> --prefilter (LoG/DoG)--> --SAD correlation + range-edge / flat /
///   uniqueness / left-right tests + sub-pixel peak--> --border, vehicle mask, wheel mask, blob,
///   overhang filters--> disparity --> range and XYZ in the rover frame (with a camera).
///
/// Everything after the pyramid runs at level L: the output images are (W >> L) x (H >> L)
/// (floor at every level) and disparities are in level-L pixels. Masks and wheel polygons are
/// given in full-resolution rectified pixels. See the component README for parameters.

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/dl/stereo/correlator.hpp"
#include "rover/dl/stereo/disparity_image.hpp"
#include "rover/dl/stereo/filters.hpp"
#include "rover/dl/stereo/image_prep.hpp"
#include "rover/dl/stereo/rectification.hpp"
#include "rover/dl/stereo/reprojection.hpp"

namespace rover::dl::stereo {

struct StereoOptions {
  int pyramid_levels = 0;      ///< [0, 4]
  double white_level = 255.0;  ///< input value mapped to 255 (e.g. 4095 for 12-bit data)
  double gamma = 1.0;          ///< [0.1, 10]; 1 = no gamma correction
  PrefilterOptions prefilter;
  CorrelatorOptions correlator;
  FilterOptions filters;
  ReprojectionOptions reprojection;

  Status Validate() const;
};

struct StereoInput {
  cv::Mat left, right;  ///< CV_8UC1 or CV_16UC1, raw (with maps) or rectified
  /// Optional: resample the raw pair through these maps first. Not owned; may be null.
  const RectificationMaps* rectification = nullptr;
  /// Optional fixed vehicle mask: CV_8UC1 of the rectified full-resolution size, non-zero =
  /// rover body.
  cv::Mat vehicle_mask;
  /// Optional moving-wheel mask: polygons in rectified full-resolution pixels.
  std::vector<std::vector<cv::Point2f>> wheel_polygons;
};

/// Wall time of the stages of the last Process() [ms] (for reports; never used for logic).
struct StereoTimings {
  double rectify_ms = 0, prepare_ms = 0, prefilter_ms = 0, correlate_ms = 0, filter_ms = 0,
         reproject_ms = 0, total_ms = 0;
};

struct StereoOutput {
  DisparityImage disparity;  ///< level-L disparity [px] and per-pixel status
  cv::Mat valid;             ///< CV_8UC1, 255 where disparity (and range) are valid
  cv::Mat range;             ///< CV_32FC1 [m], NaN where invalid; empty without a camera
  cv::Mat xyz_rover;  ///< CV_32FC3 [m] rover frame, NaN where invalid; empty without a camera
  int level = 0;      ///< pyramid level of the outputs
  std::optional<RectifiedStereoModel> model;  ///< model at level L (with a camera)
  StatusCounts counts{};                      ///< pixels per PixelStatus
  StereoTimings timings;
};

class StereoPipeline {
 public:
  /// `camera` (full-resolution rectified model and pose on the rover) enables range and XYZ.
  /// Errors: invalid options or camera.
  static Result<StereoPipeline> Create(const StereoOptions& options,
                                       std::optional<StereoCamera> camera = std::nullopt);

  /// Runs the pipeline on one pair, reusing the buffers of `output` where sizes allow.
  /// Errors: empty images, wrong types, mismatched sizes, images too small for the pyramid or
  /// the disparity range, masks or polygons of the wrong size or shape, bad rectification
  /// maps. Input errors are found before `output` is touched.
  Status Process(const StereoInput& input, StereoOutput* output);

  const StereoOptions& options() const { return options_; }
  const std::optional<StereoCamera>& camera() const { return camera_; }
  const Correlator& correlator() const { return correlator_; }

 private:
  StereoPipeline(const StereoOptions& options, std::optional<StereoCamera> camera,
                 Correlator correlator);

  StereoOptions options_;
  std::optional<StereoCamera> camera_;
  Correlator correlator_;
  cv::Mat rect_[2], work_[2], filtered_[2];
};

}  // namespace rover::dl::stereo
