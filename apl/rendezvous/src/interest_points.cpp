#include "rover/apl/rendezvous/interest_points.hpp"

#include <algorithm>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "rover/base/range_check.hpp"

namespace rover::apl::rendezvous {

Status ForstnerOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckRange("forstner.half_window", half_window, 1, 15, "px"));
  ROVER_RETURN_IF_ERROR(CheckRange("forstner.min_roundness", min_roundness, 0.0, 1.0));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("forstner.min_weight_ratio", min_weight_ratio));
  ROVER_RETURN_IF_ERROR(CheckRange("forstner.suppression_radius", suppression_radius, 1, 200, "px"));
  ROVER_RETURN_IF_ERROR(CheckRange("forstner.max_points", max_points, 1, 10000));
  return Status::Ok();
}

Result<std::vector<InterestPoint>> ForstnerPoints(const cv::Mat& image, const cv::Rect& region,
                                                  const ForstnerOptions& o) {
  ROVER_RETURN_IF_ERROR(o.Validate());
  if (image.empty() || image.type() != CV_8UC1) {
    return InvalidArgument("interest points: the image must be non-empty 8-bit grey");
  }
  const cv::Rect roi = region & cv::Rect(0, 0, image.cols, image.rows);
  const int margin = o.half_window + 2;
  if (roi.width < 2 * margin + 1 || roi.height < 2 * margin + 1) {
    return InvalidArgument("interest points: region " + std::to_string(region.width) + "x" +
                           std::to_string(region.height) + " at (" + std::to_string(region.x) +
                           ", " + std::to_string(region.y) + ") leaves too little of the " +
                           std::to_string(image.cols) + "x" + std::to_string(image.rows) +
                           " image");
  }
  // Work on the region grown by the window so the sums inside are complete.
  const cv::Rect work = cv::Rect(roi.x - margin, roi.y - margin, roi.width + 2 * margin,
                                 roi.height + 2 * margin) &
                        cv::Rect(0, 0, image.cols, image.rows);
  cv::Mat f, gx, gy;
  image(work).convertTo(f, CV_32F);
  cv::Sobel(f, gx, CV_32F, 1, 0, 3, 0.125);
  cv::Sobel(f, gy, CV_32F, 0, 1, 3, 0.125);
  cv::Mat gxx = gx.mul(gx), gyy = gy.mul(gy), gxy = gx.mul(gy);
  const int side = 2 * o.half_window + 1;
  cv::boxFilter(gxx, gxx, CV_32F, cv::Size(side, side), cv::Point(-1, -1), false);
  cv::boxFilter(gyy, gyy, CV_32F, cv::Size(side, side), cv::Point(-1, -1), false);
  cv::boxFilter(gxy, gxy, CV_32F, cv::Size(side, side), cv::Point(-1, -1), false);
  cv::Mat w(f.size(), CV_32F, cv::Scalar(0)), q(f.size(), CV_32F, cv::Scalar(0));
  const cv::Rect inner(roi.x - work.x, roi.y - work.y, roi.width, roi.height);
  double sum_w = 0.0;
  for (int r = inner.y; r < inner.y + inner.height; ++r) {
    for (int c = inner.x; c < inner.x + inner.width; ++c) {
      const double a = gxx.at<float>(r, c), b = gyy.at<float>(r, c), x = gxy.at<float>(r, c);
      const double tr = a + b;
      if (tr <= 1e-9) continue;
      const double det = a * b - x * x;
      w.at<float>(r, c) = static_cast<float>(std::max(0.0, det / tr));
      q.at<float>(r, c) = static_cast<float>(std::clamp(4.0 * det / (tr * tr), 0.0, 1.0));
      sum_w += w.at<float>(r, c);
    }
  }
  const double mean_w = sum_w / static_cast<double>(roi.area());
  const double w_min = std::max(1e-6, o.min_weight_ratio * mean_w);
  // Non-maximum suppression: a pixel is kept when it equals the dilated maximum.
  cv::Mat wmax;
  const int ks = 2 * o.suppression_radius + 1;
  cv::dilate(w, wmax, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(ks, ks)));
  std::vector<InterestPoint> points;
  for (int r = inner.y + o.half_window; r < inner.y + inner.height - o.half_window; ++r) {
    for (int c = inner.x + o.half_window; c < inner.x + inner.width - o.half_window; ++c) {
      const float wv = w.at<float>(r, c);
      if (wv < w_min || q.at<float>(r, c) < o.min_roundness || wv < wmax.at<float>(r, c)) continue;
      points.push_back({Eigen::Vector2d(c + work.x, r + work.y), wv, q.at<float>(r, c)});
    }
  }
  std::sort(points.begin(), points.end(),
            [](const InterestPoint& a, const InterestPoint& b) { return a.weight > b.weight; });
  // Plateaus (equal maxima) leave neighbours: keep the first of any two closer than the radius.
  std::vector<InterestPoint> kept;
  const double r2 = static_cast<double>(o.suppression_radius) * o.suppression_radius;
  for (const InterestPoint& p : points) {
    bool near = false;
    for (const InterestPoint& k : kept) near = near || (k.pixel - p.pixel).squaredNorm() < r2;
    if (!near) kept.push_back(p);
    if (static_cast<int>(kept.size()) >= o.max_points) break;
  }
  return kept;
}

}  // namespace rover::apl::rendezvous
