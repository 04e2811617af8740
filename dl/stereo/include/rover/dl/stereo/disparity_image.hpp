#pragma once
/// @file
/// The disparity image every stage of the stereo pipeline reads and writes, and the reason code
/// each pixel carries when it has no disparity.
///
/// Disparity d [px] of a left-image pixel (u, v) is u - u_right of its match in the right image
/// of the rectified pair (same row). It is stored as float; a pixel without a disparity holds
/// NaN and a PixelStatus other than kValid saying which stage rejected it. A stage that rejects
/// a pixel keeps the first reason (masks overwrite any reason, see filters.hpp).

#include <array>
#include <cstdint>
#include <limits>
#include <opencv2/core.hpp>

namespace rover::dl::stereo {

/// Why a pixel has no disparity (or kValid). Values are stable: they are written to files.
enum class PixelStatus : std::uint8_t {
  kValid = 0,
  kBorder = 1,       ///< the correlation window or the border margin does not fit the image
  kNoMatch = 2,      ///< no disparity of the search range keeps the window in the right image
  kRangeEdge = 3,    ///< best match at an end of the search range (true minimum may lie outside)
  kFlat = 4,         ///< cost valley too flat (curvature below threshold): little texture
  kNotUnique = 5,    ///< a second minimum (away from the best) is nearly as good: ambiguous
  kLeftRight = 6,    ///< left-right line-of-sight check failed (occlusion or mismatch)
  kBlob = 7,         ///< part of a small isolated region of disparities
  kOverhang = 8,     ///< range looms toward the cameras above nearer-looking terrain
  kVehicle = 9,      ///< inside the fixed vehicle mask
  kWheel = 10,       ///< inside the moving-wheel mask
  kRangeLimit = 11,  ///< reprojected range outside [min_range, max_range] or at infinity
};
inline constexpr int kNumPixelStatus = 12;

/// The disparity value of a pixel without a disparity.
inline constexpr float kInvalidDisparity = std::numeric_limits<float>::quiet_NaN();

/// Stable lower-case name ("valid", "left_right", ...).
const char* PixelStatusName(PixelStatus s);

/// Pixel counts per PixelStatus, indexed by the enum value.
using StatusCounts = std::array<int, kNumPixelStatus>;

/// A dense disparity image with per-pixel status.
struct DisparityImage {
  cv::Mat disparity;  ///< CV_32FC1 [px]; NaN where status != kValid
  cv::Mat status;     ///< CV_8UC1 PixelStatus values

  /// (Re)allocates both images for `size`, every pixel NaN with status `fill`.
  void Reset(cv::Size size, PixelStatus fill);
  cv::Size size() const { return disparity.size(); }
  bool empty() const { return disparity.empty(); }

  /// Sets pixel (u, v) invalid with `reason` if it is valid now (keeps the first reason).
  void Reject(int v, int u, PixelStatus reason) {
    auto& s = status.at<std::uint8_t>(v, u);
    if (s == static_cast<std::uint8_t>(PixelStatus::kValid)) {
      s = static_cast<std::uint8_t>(reason);
      disparity.at<float>(v, u) = kInvalidDisparity;
    }
  }

  /// CV_8UC1, 255 where valid, 0 elsewhere.
  cv::Mat ValidMask() const;
  StatusCounts CountStatus() const;
  int CountValid() const { return CountStatus()[0]; }
};

}  // namespace rover::dl::stereo
