#pragma once
/// @file
/// Auto-focus maths of the microscopic imager (MI) on the arm's instrument face (no DDS, no
/// camera, no arm: images and numbers in, numbers out).
///
/// The MI has a depth of field of a few millimetres. To focus, the arm lowers the face in about
/// ten steps through best focus and measures the focus of the image taken after each step
/// (WaveletFocusMeasure); FindFocusPeak then picks the height of best focus from the sweep.
///
/// The focus measure. Let I be the 8-bit image (DN) and mu its mean intensity over all pixels.
/// A Haar decomposition of 2x2 blocks
///
///     | a  b |     A  = (a + b + c + d) / 4     approximation (input of the next level)
///     | c  d |     LH = (a + b - c - d) / 4     horizontal edges (rows differ)
///                  HL = (a - b + c - d) / 4     vertical edges (columns differ)
///                  HH = (a - b - c + d) / 4     diagonal
///
/// runs on I for level 1 and on the previous level's A for each further level; an odd last row
/// or column is dropped at each level. Level k (1 = finest) therefore sees structure at a scale
/// of 2^k px and has floor(H / 2^k) x floor(W / 2^k) blocks. With N_k that number of blocks,
///
///     E_k = (1 / (3 N_k)) sum over the blocks of (LH^2 + HL^2 + HH^2)      [DN^2]
///
/// (the mean square of all detail coefficients of the level) and
///
///     measure = (sum of E_k for k = first_level .. levels) / mu^2          [dimensionless]
///
/// Dividing by mu^2 makes the measure independent of exposure (an image scaled by a gain gives
/// the same measure, up to 8-bit rounding). Because the coefficients are averages, the details
/// of white sensor noise of variance s^2 have E_k = s^2 / 4^k, so skipping level 1
/// (first_level = 2) keeps most of the noise out while texture at 4-8 px scales (levels 2, 3)
/// still counts. Defocus blur removes fine detail first, so the measure falls as the image
/// blurs.
///
/// The peak of a sweep: see FindFocusPeak.

#include <opencv2/core/mat.hpp>
#include <span>

#include "rover/base/status.hpp"

namespace rover::dl::arm {

/// Which Haar levels the focus measure computes and counts.
struct FocusMeasureOptions {
  int levels = 3;       ///< levels computed (the coarsest counted is `levels`, scale 2^levels px)
  int first_level = 2;  ///< finest level counted (1 = 2x2 px; skipping it keeps noise out)

  /// levels in [1, 6], first_level in [1, levels]. Messages start with the field
  /// ("focus.levels = 9 is outside [1, 6]").
  Status Validate() const;
};

/// The wavelet focus measure of `image` (see the file comment for the maths): the mean squared
/// Haar detail coefficients of levels first_level .. levels, summed, divided by the squared mean
/// intensity. Larger is sharper; dimensionless; 0 for an all-black image (mean 0).
/// Preconditions (else InvalidArgument naming the problem): `options` valid, `image` non-empty,
/// of type CV_8UC1, and at least 2^levels px wide and high. Any row stride (ROIs) is fine.
Result<double> WaveletFocusMeasure(const cv::Mat& image, const FocusMeasureOptions& options = {});

/// One step of a focus sweep.
struct FocusSample {
  double height;   ///< [m] height of the instrument face (any monotone position along the sweep)
  double measure;  ///< focus measure at that height (WaveletFocusMeasure), >= 0
};

/// The best focus found in a sweep.
struct FocusPeak {
  double best_height;  ///< [m] interpolated height of best focus (h(peak_index) if not bracketed)
  int peak_index;      ///< index of the largest measure (the first one on a tie)
  bool bracketed;      ///< the peak is neither the first nor the last sample
  double contrast;     ///< largest / smallest measure (1 if all are 0; at most kMaxFocusContrast)
};

/// Upper bound of FocusPeak::contrast; reported when the smallest measure is 0 (or so small that
/// the ratio would exceed it), so that contrast is always finite.
inline constexpr double kMaxFocusContrast = 1e12;

/// Finds the height of best focus in `samples`, given in sweep order (heights strictly
/// increasing or strictly decreasing).
///
/// With p the index of the largest measure m_p (the first on a tie): bracketed = 0 < p < n-1.
/// When bracketed, a parabola y(h) is fitted through (h_i, log m_i), i = p-1, p, p+1 (the
/// heights need not be equally spaced; a Gaussian focus curve is exactly a parabola in log):
///
///     d1 = (y_p - y_{p-1}) / (h_p - h_{p-1}),   d2 = (y_{p+1} - y_p) / (h_{p+1} - h_p),
///     a  = (d2 - d1) / (h_{p+1} - h_{p-1}),
///     best_height = (h_{p-1} + h_p) / 2 - d1 / (2 a),
///
/// clamped to the interval spanned by h_{p-1} and h_{p+1}. It falls back to h_p when the three
/// points are not strictly concave (a >= 0; cannot happen with p the maximum unless measures
/// tie) or a neighbour's measure is 0 (log undefined). When not bracketed, best_height = h_p:
/// the best focus is at or beyond the end of the sweep, which should be extended.
/// contrast = max m / min m: near 1 means the sweep saw no focus change (a textureless target,
/// or a sweep far from focus); it is kMaxFocusContrast when min m is 0 (or the ratio exceeds
/// it) and 1 when every measure is 0.
///
/// Errors (InvalidArgument naming the index and values): fewer than 3 samples, a non-finite
/// height or measure, a negative measure, heights not strictly monotone.
Result<FocusPeak> FindFocusPeak(std::span<const FocusSample> samples);

}  // namespace rover::dl::arm
