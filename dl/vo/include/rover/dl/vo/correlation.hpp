#pragma once
/// @file
/// Pseudo-normalised correlation (Moravec; used by MER stereo and visual odometry) and the
/// biquadratic sub-pixel peak fit.
///
/// For a template a and an image window b of n = (2r+1)^2 pixels,
///   C(a, b) = 2 sum (a - mean a)(b - mean b) / ( sum (a - mean a)^2 + sum (b - mean b)^2 )
/// lies in [-1, 1], is 1 only for b = a + const, and, unlike normalised cross-correlation,
/// falls when the contrasts differ (so a flat window never matches a textured template).
/// Window sums of b and b^2 come from integral images, so a score costs n multiply-adds.
///
/// Sub-pixel peak: a least-squares biquadratic f(x, y) = c0 + c1 x + c2 y + c3 x^2 + c4 x y
/// + c5 y^2 is fitted to the 3x3 scores around the integer peak; its stationary point is the
/// sub-pixel offset, and the smaller eigenvalue of -Hessian(f) [score/px^2] is the peak
/// curvature (low on smooth, ambiguous images).

#include <Eigen/Core>
#include <array>
#include <opencv2/core.hpp>
#include <vector>

namespace rover::dl::vo {

/// A single-channel float image with integral images of values and squares.
class CorrelationImage {
 public:
  CorrelationImage() = default;
  /// Precondition: `image` single-channel, 8-bit or float, not empty.
  explicit CorrelationImage(const cv::Mat& image);

  const cv::Mat& image() const { return image_; }  ///< CV_32F
  int width() const { return image_.cols; }
  int height() const { return image_.rows; }
  bool empty() const { return image_.empty(); }
  /// True if the (2r+1)^2 window centred on (x, y) lies inside the image.
  bool WindowInside(int x, int y, int r) const {
    return x - r >= 0 && y - r >= 0 && x + r < image_.cols && y + r < image_.rows;
  }
  /// Sum and sum of squares over the window. Precondition: WindowInside(x, y, r).
  void WindowStats(int x, int y, int r, double* sum, double* sum_sq) const;

 private:
  cv::Mat image_;
  cv::Mat sum_;     // CV_64F (h+1) x (w+1)
  cv::Mat sq_sum_;  // CV_64F (h+1) x (w+1)
};

/// A zero-mean square template of (2 radius + 1)^2 samples, row-major.
struct Template {
  int radius = 0;
  std::vector<float> values;  ///< a - mean a
  double energy = 0.0;        ///< sum (a - mean a)^2
  /// Standard deviation of the template [grey levels].
  double StdDev() const;
};

/// Template of the window centred on integer pixel (x, y). Returns false if it leaves the image.
bool ExtractTemplate(const CorrelationImage& image, int x, int y, int radius, Template* out);

/// Template resampled (bilinear) at centre + a_inv * o for integer offsets o in [-r, r]^2: the
/// appearance of the patch predicted under the local image warp a (a_inv = a^-1). Returns false
/// if a sample leaves the image.
bool ExtractWarpedTemplate(const CorrelationImage& image, const Eigen::Vector2d& centre,
                           const Eigen::Matrix2d& a_inv, int radius, Template* out);

/// Score of the template centred on image pixel (x, y); -2 if the window leaves the image.
double CorrelationScore(const Template& t, const CorrelationImage& image, int x, int y);

/// Result of the biquadratic fit to 3x3 scores s[(dy + 1) * 3 + (dx + 1)].
struct SubpixelPeak {
  bool ok = false;         ///< false if the fit has no maximum within one pixel
  double dx = 0.0;         ///< [px] offset of the maximum from the centre sample
  double dy = 0.0;         ///< [px]
  double curvature = 0.0;  ///< [score/px^2] smaller eigenvalue of -Hessian
};
SubpixelPeak FitBiquadratic(const std::array<double, 9>& scores);

/// Best match of a template in a search window.
struct WindowMatch {
  bool ok = false;
  Eigen::Vector2d position{0.0, 0.0};  ///< [px] sub-pixel position of the template centre
  double score = -2.0;                 ///< correlation at the integer peak
  double curvature = 0.0;              ///< biquadratic peak curvature
  const char* failure = "";            ///< why not ok (static string)
};

/// Searches integer centres x in [x0 - rx, x0 + rx], y in [y0 - ry, y0 + ry] (clipped to the
/// image), then fits the biquadratic to the 3x3 scores around the best one (evaluated outside the
/// window if needed). Fails if the peak lies on the window edge with a better score outside it,
/// or if the fit has no maximum. Accuracy on band-limited texture: about 0.07 px rms per
/// coordinate, unbiased (the correlation surface is not exactly a quadric over +-1 px).
WindowMatch SearchWindow(const Template& t, const CorrelationImage& image, int x0, int y0, int rx,
                         int ry);

}  // namespace rover::dl::vo
