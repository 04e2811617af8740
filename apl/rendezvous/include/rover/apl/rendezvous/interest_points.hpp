#pragma once
/// @file
/// Förstner's interest operator (Förstner & Gülch 1987), as FIDO ran it on the first left image
/// of a science-target approach (seed 004, step 4): points whose grey-value corner is both
/// precise and round.
///
/// With gradients gx, gy and the structure matrix summed over a (2 half_window + 1)^2 window,
///   N = [sum gx^2, sum gx gy; sum gx gy, sum gy^2],
/// the weight w = det N / tr N (the inverse size of the point's error ellipse: large where the
/// corner is sharp) and the roundness q = 4 det N / tr^2 N in [0, 1] (1: a round ellipse, 0: an
/// edge). A pixel is a point when q >= min_roundness, w >= min_weight_ratio x the mean w over the
/// region, and w is the largest within suppression_radius; the strongest max_points are kept.
/// Units: pixels (image convention of core/geometry camera_model.hpp: pixel centres at integers).

#include <Eigen/Core>
#include <vector>

#include "rover/base/status.hpp"

namespace cv {
class Mat;
template <typename T>
class Rect_;
using Rect = Rect_<int>;
}  // namespace cv

namespace rover::apl::rendezvous {

struct ForstnerOptions {
  int half_window = 2;            ///< [px] structure-matrix window (2 h + 1)^2
  double min_roundness = 0.5;     ///< q threshold
  double min_weight_ratio = 1.0;  ///< w threshold as a multiple of the region's mean w
  int suppression_radius = 8;     ///< [px] non-maximum suppression
  int max_points = 40;            ///< strongest kept (>= 1)
  /// Ok, or InvalidArgument naming the field (prefix "forstner.").
  Status Validate() const;
};

struct InterestPoint {
  Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
  double weight = 0.0;     ///< w [grey^2 / px^2]
  double roundness = 0.0;  ///< q
};

/// Interest points of an 8-bit grey image inside `region` (clipped to the image), strongest
/// first. Errors: an empty or non-8-bit image, a region that misses the image, bad options.
Result<std::vector<InterestPoint>> ForstnerPoints(const cv::Mat& image, const cv::Rect& region,
                                                  const ForstnerOptions& options = {});

}  // namespace rover::apl::rendezvous
