#pragma once
/// @file
/// Disparity quality against ground truth (Middlebury conventions, Scharstein & Szeliski 2003)
/// and conversions of OpenCV matcher outputs, shared by the tests and the benchmark.
///
/// Given an estimate E (NaN = no disparity), ground truth G (0 or non-finite = unknown) and a
/// non-occlusion mask M (non-zero = visible in both views):
///   evaluated   = pixels with M != 0, G known and E valid
///   bad(t)      = share of evaluated pixels with |E - G| > t
///   density     = share of all pixels with E valid
///   density_nonocc = share of pixels with M != 0 and G known that have E valid

#include <opencv2/core.hpp>

#include "rover/base/status.hpp"

namespace rover::dl::stereo {

struct DisparityScore {
  int pixels = 0;               ///< all pixels
  int nonoccluded = 0;          ///< M != 0 and G known
  int evaluated = 0;            ///< ... and E valid
  double bad_1px = 0.0;         ///< bad(1)
  double bad_2px = 0.0;         ///< bad(2)
  double mean_abs_error = 0.0;  ///< over evaluated pixels [px]
  double density = 0.0;
  double density_nonocc = 0.0;
};

/// Scores `estimate` (CV_32FC1) against `truth` (CV_32FC1) inside `nonoccluded` (CV_8UC1; empty
/// = everywhere). `scale` multiplies the estimate first (e.g. 2^L for a level-L estimate
/// compared with full-resolution truth of the same size). Errors: empty, wrong type or size.
Result<DisparityScore> ScoreDisparity(const cv::Mat& estimate, const cv::Mat& truth,
                                      const cv::Mat& nonoccluded, double scale = 1.0);

/// Converts an OpenCV StereoBM/StereoSGBM output (CV_16SC1, disparity * 16; values below
/// min_disparity * 16 mean "none") to CV_32FC1 pixels with NaN for "none".
Result<cv::Mat> FromOpenCvDisparity(const cv::Mat& fixed_point, int min_disparity);

}  // namespace rover::dl::stereo
