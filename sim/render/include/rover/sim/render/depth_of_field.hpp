#pragma once
/// @file
/// Depth of field of a close-up camera (the microscopic imager on the arm): a thin lens
/// focused at distance s blurs a surface point at axial distance z (along the optical axis,
/// metres) into a disc of diameter
///   c(z) = K |z - s| / (z s)   [px],   K = focal length [px] * entrance-pupil diameter [m],
/// which the renderer applies to the radiance before the sensor model: per pixel a Gaussian of
/// sigma = c / 4 (the per-axis standard deviation of a uniform disc), interpolated between
/// a fixed ladder of blurred copies of the image (a gather approximation: it does not model
/// occlusion at depth edges, which the imager's near-planar scenes hardly have).

#include <opencv2/core.hpp>

#include "rover/base/status.hpp"

namespace rover::sim::render {

struct DepthOfField {
  double focus_distance = 0.06;  ///< [m] s, axial distance of the plane of best focus
  double blur_constant = 3.0;    ///< [px m] K = focal_px * aperture
  double near = 0.002;           ///< [m] near clipping plane of the close-up render
  double max_sigma_px = 24.0;    ///< [px] the blur is capped here (far out of focus)

  /// focus_distance (0, 10] m, blur_constant (0, 1e4], near (0, focus_distance), max_sigma_px
  /// [1, 64]; messages start with "depth_of_field." + the field.
  Status Validate() const;
  /// c(z) [px]; z <= 0 (no surface) gives the cap (4 max_sigma_px).
  double BlurDiameterPx(double z) const;
};

/// Blurs `radiance` (CV_32FC1) by the defocus of each pixel's axial distance `depth` (CV_32FC1,
/// same size, metres; 0 = no surface, blurred at the cap). Preconditions (ROVER_DEMAND): the
/// types and sizes above, options valid.
cv::Mat ApplyDepthOfField(const cv::Mat& radiance, const cv::Mat& depth, const DepthOfField& dof);

}  // namespace rover::sim::render
