#include "rover/dl/stereo/evaluation.hpp"

#include <cmath>
#include <limits>
#include <string>

#include "describe.hpp"

namespace rover::dl::stereo {

using internal::Describe;
Result<DisparityScore> ScoreDisparity(const cv::Mat& estimate, const cv::Mat& truth,
                                      const cv::Mat& nonoccluded, double scale) {
  if (estimate.empty() || truth.empty()) return InvalidArgument("estimate or truth is empty");
  if (estimate.type() != CV_32FC1) {
    return InvalidArgument("estimate is " + Describe(estimate) + "; expected CV_32FC1");
  }
  if (truth.type() != CV_32FC1) {
    return InvalidArgument("truth is " + Describe(truth) + "; expected CV_32FC1");
  }
  if (truth.size() != estimate.size()) {
    return InvalidArgument("truth is " + Describe(truth) + " but estimate is " +
                           Describe(estimate));
  }
  if (!nonoccluded.empty() &&
      (nonoccluded.type() != CV_8UC1 || nonoccluded.size() != estimate.size())) {
    return InvalidArgument("non-occlusion mask is " + Describe(nonoccluded) + "; expected " +
                           std::to_string(estimate.cols) + "x" + std::to_string(estimate.rows) +
                           " CV_8UC1");
  }
  DisparityScore s;
  long long valid = 0, bad1 = 0, bad2 = 0;
  double abs_sum = 0.0;
  for (int v = 0; v < estimate.rows; ++v) {
    const float* e = estimate.ptr<float>(v);
    const float* g = truth.ptr<float>(v);
    const std::uint8_t* m = nonoccluded.empty() ? nullptr : nonoccluded.ptr<std::uint8_t>(v);
    for (int u = 0; u < estimate.cols; ++u) {
      const bool has_e = std::isfinite(e[u]);
      valid += has_e ? 1 : 0;
      const bool known = std::isfinite(g[u]) && g[u] > 0.0f && (m == nullptr || m[u] != 0);
      if (!known) continue;
      ++s.nonoccluded;
      if (!has_e) continue;
      ++s.evaluated;
      const double err = std::abs(scale * e[u] - g[u]);
      abs_sum += err;
      bad1 += err > 1.0 ? 1 : 0;
      bad2 += err > 2.0 ? 1 : 0;
    }
  }
  s.pixels = estimate.rows * estimate.cols;
  s.density = static_cast<double>(valid) / s.pixels;
  if (s.nonoccluded > 0) s.density_nonocc = static_cast<double>(s.evaluated) / s.nonoccluded;
  if (s.evaluated > 0) {
    s.bad_1px = static_cast<double>(bad1) / s.evaluated;
    s.bad_2px = static_cast<double>(bad2) / s.evaluated;
    s.mean_abs_error = abs_sum / s.evaluated;
  }
  return s;
}

Result<cv::Mat> FromOpenCvDisparity(const cv::Mat& fixed_point, int min_disparity) {
  if (fixed_point.empty()) return InvalidArgument("OpenCV disparity is empty");
  if (fixed_point.type() != CV_16SC1) {
    return InvalidArgument("OpenCV disparity is " + Describe(fixed_point) +
                           "; expected CV_16SC1 (disparity * 16)");
  }
  cv::Mat out(fixed_point.size(), CV_32FC1);
  const int invalid_below = min_disparity * 16;
  for (int v = 0; v < out.rows; ++v) {
    const std::int16_t* in = fixed_point.ptr<std::int16_t>(v);
    float* o = out.ptr<float>(v);
    for (int u = 0; u < out.cols; ++u) {
      o[u] = in[u] < invalid_below ? std::numeric_limits<float>::quiet_NaN()
                                   : static_cast<float>(in[u]) / 16.0f;
    }
  }
  return out;
}

}  // namespace rover::dl::stereo
