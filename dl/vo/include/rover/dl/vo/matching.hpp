#pragma once
/// @file
/// Feature matching by correlation: stereo matching along the epipolar line of a rectified pair
/// (the same image row) and tracking between two left images, coarse to fine.
///
/// Stereo: the template around the left pixel is correlated with the right image at disparities
/// d in [min_disparity, max_disparity] on the same row; the 3x3 scores around the best
/// disparity (rows above and below included) give the sub-pixel right position by the
/// biquadratic fit, so a small vertical offset left by rectification is measured too. The match
/// is accepted if the score, the peak curvature, the vertical offset and a right-to-left
/// consistency check (the right template must find the left pixel again, within max_lr_error)
/// all pass.
///
/// Tracking: the template around the feature in the previous left image is (optionally) warped
/// by the predicted local image motion A = d(u_new)/d(u_old), then searched in the new left image
/// in a window of half size w around the predicted position. If w is larger than
/// coarse_radius, the search starts on the coarsest pyramid level where w / 2^L <= coarse_radius
/// and is refined on each finer level in a +-2 pixel window.

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/dl/vo/correlation.hpp"

namespace rover::dl::vo {

struct MatchOptions {
  int template_radius = 5;           ///< [px] correlation window (2r+1)^2, 11x11
  double min_correlation = 0.75;     ///< minimum pseudo-normalised correlation at the peak
  double min_curvature = 0.005;      ///< [1/px^2] minimum peak curvature
  double min_template_stddev = 2.0;  ///< [grey levels] flatter templates are not matched
  int min_disparity = 1;             ///< [px] nearest search is max_disparity, farthest this
  int max_disparity = 128;           ///< [px]
  double max_lr_error = 1.0;         ///< [px] right-to-left consistency; <= 0 disables the check
  double max_vertical_offset = 1.0;  ///< [px] largest accepted |v_right - v_left|
  int pyramid_levels = 4;            ///< levels including full resolution (1 = no pyramid)
  int coarse_radius = 8;             ///< [px] largest half window searched on one level

  Status Validate() const;
};

/// A Gaussian pyramid (cv::pyrDown) of correlation images; level L pixel (x, y) is level-0
/// pixel (2^L x, 2^L y).
class ImagePyramid {
 public:
  ImagePyramid() = default;
  /// Precondition: `image` single-channel, 8-bit or float; levels >= 1.
  ImagePyramid(const cv::Mat& image, int levels);
  int levels() const { return static_cast<int>(levels_.size()); }
  const CorrelationImage& level(int l) const { return levels_[static_cast<std::size_t>(l)]; }
  bool empty() const { return levels_.empty(); }

 private:
  std::vector<CorrelationImage> levels_;
};

struct StereoMatch {
  bool ok = false;
  Eigen::Vector2d right{0.0, 0.0};  ///< [px] sub-pixel position in the right image
  double score = 0.0;
  const char* failure = "";
};

/// Matches left pixel `left_px` (sub-pixel allowed: the template is taken at the nearest pixel
/// and the sub-pixel remainder carried over) into the right image.
StereoMatch MatchStereo(const CorrelationImage& left, const CorrelationImage& right,
                        const Eigen::Vector2d& left_px, const MatchOptions& options);

struct TrackRequest {
  Eigen::Vector2d from{0.0, 0.0};       ///< [px] feature in the previous left image
  Eigen::Vector2d predicted{0.0, 0.0};  ///< [px] predicted position in the new left image
  Eigen::Vector2d half_window{4, 4};    ///< [px] search half sizes (u, v) at full resolution
  Eigen::Matrix2d warp = Eigen::Matrix2d::Identity();  ///< A = d(u_new)/d(u_old)
};

struct TrackMatch {
  bool ok = false;
  Eigen::Vector2d to{0.0, 0.0};  ///< [px] sub-pixel position in the new left image
  double score = 0.0;
  int level = 0;  ///< pyramid level the search started on
  const char* failure = "";
};

TrackMatch TrackFeature(const ImagePyramid& previous, const ImagePyramid& current,
                        const TrackRequest& request, const MatchOptions& options);

}  // namespace rover::dl::vo
