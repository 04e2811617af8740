#pragma once
/// @file
/// Förstner interest operator over a grid of cells, as selected by MER visual odometry.
///
/// With image gradients g = (gx, gy) [grey levels / px] (3x3 Sobel / 8), the operator averages
/// the structure tensor over a (2r+1) x (2r+1) window W:
///   N = mean_W [gx^2, gx gy; gx gy, gy^2]
/// and scores each pixel with
///   strength  w = det N / trace N      [(grey/px)^2]   (about the smaller eigenvalue)
///   roundness q = 4 det N / (trace N)^2 in [0, 1]     (1 = isotropic corner, 0 = edge)
/// A pixel is a candidate if w >= min_strength, q >= min_roundness and w is a 3x3 local maximum.
/// The image is divided into cells of cell_size x cell_size pixels; the strongest candidate of
/// each cell is kept. Candidates are then accepted strongest first, skipping any closer than
/// min_separation pixels to an accepted one: MER found that clustered features gave false
/// motion estimates. The absolute strength threshold is what makes a featureless (constant or
/// smooth) image yield no features at all.

#include <opencv2/core.hpp>
#include <vector>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"

namespace rover::dl::vo {

struct InterestOptions {
  int cell_size = 16;          ///< [px] side of a grid cell; at most one feature per cell
  int window_radius = 2;       ///< [px] structure-tensor window half size (5x5)
  double min_strength = 4.0;   ///< [(grey/px)^2] minimum Förstner w
  double min_roundness = 0.2;  ///< minimum q in [0, 1]
  double min_separation = 8;   ///< [px] minimum distance between two selected features
  int border = 12;             ///< [px] no feature closer than this to the image edge
  int max_features = 0;        ///< keep at most this many (strongest); 0 = no limit

  Status Validate() const;
  /// dl-vo's keys vo.cell_size and vo.min_separation (without the prefix).
  static void BindParams(ParamBinder<InterestOptions>& b);
};

/// A selected feature: integer pixel of the left image.
struct InterestPoint {
  int x = 0;               ///< [px] column
  int y = 0;               ///< [px] row
  double strength = 0.0;   ///< Förstner w
  double roundness = 0.0;  ///< Förstner q
};

/// Förstner strength w and roundness q for every pixel of an 8-bit or float single-channel
/// image; both outputs are CV_32F of the image size. Precondition: image is single-channel.
void ForstnerOperator(const cv::Mat& image, int window_radius, cv::Mat* strength,
                      cv::Mat* roundness);

/// Selects features as described above, strongest first. Precondition: options valid, image
/// single-channel (8-bit or float).
std::vector<InterestPoint> DetectInterestPoints(const cv::Mat& image,
                                                const InterestOptions& options);

}  // namespace rover::dl::vo
