#pragma once
/// @file
/// Disparity to range and 3-D points in the rover frame.
///
/// With the rectified model at the processing level (rectification.hpp), a valid pixel (u, v)
/// with disparity d becomes p_C = (X, Y, Z) in the rectified left camera frame C (x right,
/// y down, z forward; metres), then
///     p_R = T_RC p_C        (rover frame R: x forward, y left, z up)
///     range = |p_C|         (distance from the left camera's optical centre) [m].
/// Pixels whose d + doffs <= 0 (at or beyond infinity) or whose range is outside
/// [min_range_m, max_range_m] get status kRangeLimit.

#include <Eigen/Geometry>
#include <limits>
#include <opencv2/core.hpp>

#include "rover/base/status.hpp"
#include "rover/dl/stereo/disparity_image.hpp"
#include "rover/dl/stereo/rectification.hpp"

namespace rover::dl::stereo {

/// The rectified pair at full resolution and where it sits on the rover.
struct StereoCamera {
  RectifiedStereoModel model;
  /// T_RC: maps points from the rectified left camera frame to the rover frame.
  Eigen::Isometry3d rover_from_camera = Eigen::Isometry3d::Identity();

  Status Validate() const;
};

struct ReprojectionOptions {
  double min_range_m = 0.0;                                      ///< >= 0
  double max_range_m = std::numeric_limits<double>::infinity();  ///< > min_range_m

  Status Validate() const;
};

/// Fills `range` (CV_32FC1 [m], NaN where invalid) and `xyz_rover` (CV_32FC3 [m] in the rover
/// frame, NaN where invalid) from `disparity`, whose pixels are in the frame of `model` (the
/// model at the processing level) and whose status gains kRangeLimit where the range is out of
/// limits. Either output may be null. Errors: invalid model, pose or options, empty image.
Status Reproject(const RectifiedStereoModel& model, const Eigen::Isometry3d& rover_from_camera,
                 const ReprojectionOptions& options, DisparityImage* disparity, cv::Mat* range,
                 cv::Mat* xyz_rover);

}  // namespace rover::dl::stereo
