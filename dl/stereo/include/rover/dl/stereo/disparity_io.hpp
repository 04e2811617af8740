#pragma once
/// @file
/// Reading images and writing disparity/range images for tools and people.
///
/// PFM ("Pf", little-endian, bottom row first) is the Middlebury float format; invalid pixels
/// are written as +inf (Middlebury's convention) and read back as NaN. TIFF float images go
/// through OpenCV (32-bit float, NaN kept). The colour image maps [d_lo, d_hi] through the
/// TURBO colour map (near = red), invalid pixels black.

#include <opencv2/core.hpp>
#include <string>

#include "rover/base/status.hpp"

namespace rover::dl::stereo {

/// Loads an image as single-channel CV_8UC1 or CV_16UC1 (colour is converted to grey).
/// Errors: kNotFound if the file does not exist, kInvalidArgument if it cannot be decoded or
/// has an unsupported depth.
Result<cv::Mat> LoadGrayImage(const std::string& path);

/// Writes a CV_32FC1 image as PFM. Errors: wrong type, empty, cannot open or write the file.
Status WritePfm(const std::string& path, const cv::Mat& image);
/// Reads a single-channel PFM into CV_32FC1 (non-finite -> NaN). Errors name the file and what
/// is wrong with it.
Result<cv::Mat> ReadPfm(const std::string& path);

/// Writes a CV_32FC1 image as .pfm or .tif/.tiff by extension. Errors: other extensions.
Status WriteFloatImage(const std::string& path, const cv::Mat& image);

/// CV_8UC3 (BGR) rendering of a CV_32FC1 disparity; if d_hi <= d_lo the finite range of the
/// image is used. Errors: wrong type or empty.
Result<cv::Mat> ColorizeDisparity(const cv::Mat& disparity, double d_lo = 0.0, double d_hi = -1.0);

}  // namespace rover::dl::stereo
