#pragma once
/// @file
/// The rectified stereo camera model and the rectification step.
///
/// Rectified pair: both cameras share the focal length f [px] and the image rows; the right
/// camera sits baseline B [m] to the right of the left one (along the left camera's +x). With
/// the left principal point (cx, cy) and doffs = cx_right - cx_left [px], a left pixel (u, v)
/// with disparity d [px] is the point, in the rectified left camera frame (x right, y down,
/// z forward; metres):
///     Z = f B / (d + doffs),   X = (u - cx) Z / f,   Y = (v - cy) Z / f.
/// This is OpenCV's reprojection matrix Q (stereoRectify) with
///     Q = [1 0 0 -cx; 0 1 0 -cy; 0 0 0 f; 0 0 1/B doffs/B],  (X Y Z W)' = Q (u v d 1)'.
///
/// Rectification resamples a raw pair through precomputed maps (for each rectified pixel, the
/// raw pixel to sample), e.g. from core/geometry's CAHVOR/pinhole stereo rectification or from
/// cv::initUndistortRectifyMap. Without maps the pipeline takes an already rectified pair.

#include <opencv2/core.hpp>

#include "rover/base/status.hpp"

namespace rover::dl::stereo {

struct RectifiedStereoModel {
  double focal_px = 0.0;    ///< f [px], > 0
  double cx = 0.0;          ///< left principal point column [px]
  double cy = 0.0;          ///< left principal point row [px]
  double baseline_m = 0.0;  ///< B [m], > 0
  double doffs_px = 0.0;    ///< cx_right - cx_left [px]

  Status Validate() const;

  /// Depth Z [m] of disparity d; +inf if d + doffs <= 0.
  double DepthFromDisparity(double d) const;
  /// Disparity [px] of depth Z [m] (Z > 0).
  double DisparityFromDepth(double z) const;

  /// The model of the image after `levels` 2x2 block-averaging steps (image_prep.hpp):
  /// f and doffs halve, c -> (c - 0.5) / 2 per level.
  RectifiedStereoModel Downsampled(int levels) const;

  /// OpenCV's Q (see file comment).
  cv::Matx44d ToQ() const;
  /// Reads a Q of the form above (e.g. from cv::stereoRectify). Errors if Q is not of that
  /// form (non-zero entries elsewhere, f <= 0, baseline <= 0, Q(0,0) or Q(1,1) != 1).
  static Result<RectifiedStereoModel> FromQ(const cv::Matx44d& q);
};

/// Remap tables for the two cameras: rectified pixel (u, v) takes the raw pixel
/// (x(v,u), y(v,u)). Either CV_32FC1 x and y maps, or OpenCV's fixed-point form (x: CV_16SC2,
/// y: CV_16UC1, from cv::convertMaps). All four maps have the rectified image size.
struct RectificationMaps {
  cv::Mat left_x, left_y, right_x, right_y;
  cv::Size raw_size;  ///< size of the raw images the maps sample from

  Status Validate() const;
  cv::Size rectified_size() const { return left_x.size(); }
};

/// Resamples a raw pair (CV_8UC1 or CV_16UC1, both of maps.raw_size) into the rectified pair
/// (bilinear; outside the raw image -> 0). Errors name the wrong image or map.
Status Rectify(const RectificationMaps& maps, const cv::Mat& raw_left, const cv::Mat& raw_right,
               cv::Mat* rect_left, cv::Mat* rect_right);

}  // namespace rover::dl::stereo
