#include "rover/sim/render/depth_of_field.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "rover/base/check.hpp"
#include "rover/base/range_check.hpp"

namespace rover::sim::render {

Status DepthOfField::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckRange("depth_of_field.focus_distance", focus_distance,
                                   Bounds::OpenLow(0.0, 10.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("depth_of_field.blur_constant", blur_constant,
                                   Bounds::OpenLow(0.0, 1e4), "px m"));
  ROVER_RETURN_IF_ERROR(
      CheckRange("depth_of_field.near", near, Bounds{0.0, focus_distance, true, true}, "m"));
  return CheckRange("depth_of_field.max_sigma_px", max_sigma_px, 1.0, 64.0, "px");
}

double DepthOfField::BlurDiameterPx(double z) const {
  if (!(z > 0.0)) return 4.0 * max_sigma_px;
  return blur_constant * std::abs(z - focus_distance) / (z * focus_distance);
}

cv::Mat ApplyDepthOfField(const cv::Mat& radiance, const cv::Mat& depth, const DepthOfField& dof) {
  ROVER_DEMAND(radiance.type() == CV_32FC1 && depth.type() == CV_32FC1);
  ROVER_DEMAND(radiance.size() == depth.size());
  ROVER_DEMAND(dof.Validate().ok());
  // Sigma per pixel, and the ladder of blurred copies up to the largest one needed: sigma 0,
  // then a geometric ladder of ratio sqrt(2) from 0.35 px.
  cv::Mat sigma(radiance.size(), CV_32FC1);
  double max_needed = 0.0;
  for (int r = 0; r < radiance.rows; ++r) {
    const float* d = depth.ptr<float>(r);
    float* s = sigma.ptr<float>(r);
    for (int c = 0; c < radiance.cols; ++c) {
      const double v = std::min(dof.max_sigma_px, dof.BlurDiameterPx(d[c]) / 4.0);
      s[c] = static_cast<float>(v);
      max_needed = std::max(max_needed, v);
    }
  }
  std::vector<double> ladder{0.0};
  for (double v = 0.35; ladder.back() < max_needed; v *= std::sqrt(2.0)) {
    ladder.push_back(std::min(v, dof.max_sigma_px));
    if (v >= dof.max_sigma_px) break;
  }
  if (ladder.size() == 1) return radiance.clone();
  std::vector<cv::Mat> copies(ladder.size());
  copies[0] = radiance;
  for (std::size_t k = 1; k < ladder.size(); ++k) {
    cv::GaussianBlur(radiance, copies[k], cv::Size(0, 0), ladder[k], ladder[k],
                     cv::BORDER_REFLECT);
  }
  cv::Mat out(radiance.size(), CV_32FC1);
  for (int r = 0; r < radiance.rows; ++r) {
    const float* s = sigma.ptr<float>(r);
    float* o = out.ptr<float>(r);
    for (int c = 0; c < radiance.cols; ++c) {
      const double v = s[c];
      std::size_t k = 0;
      while (k + 1 < ladder.size() && ladder[k + 1] <= v) ++k;
      if (k + 1 >= ladder.size()) {
        o[c] = copies[k].at<float>(r, c);
        continue;
      }
      const double t = (v - ladder[k]) / (ladder[k + 1] - ladder[k]);
      o[c] = static_cast<float>((1.0 - t) * copies[k].at<float>(r, c) +
                                t * copies[k + 1].at<float>(r, c));
    }
  }
  return out;
}

}  // namespace rover::sim::render
