#include "rover/dl/vo/interest_operator.hpp"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

#include "rover/base/check.hpp"

namespace rover::dl::vo {

void InterestOptions::BindParams(ParamBinder<InterestOptions>& b) {
  b.Bind("cell_size", &InterestOptions::cell_size, "px",
         "interest-operator grid cell (one feature per cell)")
      .Range(4, 256);
  b.Bind("min_separation", &InterestOptions::min_separation, "px", "between two features")
      .Range(0.0, 256.0);
}

Status InterestOptions::Validate() const {
  if (cell_size < 4) {
    return InvalidArgument("interest.cell_size=" + std::to_string(cell_size) + " must be >= 4");
  }
  if (window_radius < 1 || window_radius > 10) {
    return InvalidArgument("interest.window_radius=" + std::to_string(window_radius) +
                           " must be in [1, 10]");
  }
  if (!std::isfinite(min_strength) || min_strength <= 0.0) {
    return InvalidArgument("interest.min_strength must be finite and > 0");
  }
  if (!std::isfinite(min_roundness) || min_roundness < 0.0 || min_roundness > 1.0) {
    return InvalidArgument("interest.min_roundness must be in [0, 1]");
  }
  if (!std::isfinite(min_separation) || min_separation < 0.0) {
    return InvalidArgument("interest.min_separation must be finite and >= 0");
  }
  if (border < 0) return InvalidArgument("interest.border must be >= 0");
  if (max_features < 0) return InvalidArgument("interest.max_features must be >= 0");
  return Status::Ok();
}

void ForstnerOperator(const cv::Mat& image, int window_radius, cv::Mat* strength,
                      cv::Mat* roundness) {
  ROVER_DEMAND(image.channels() == 1 && !image.empty());
  ROVER_DEMAND(strength != nullptr && roundness != nullptr);
  cv::Mat f;
  image.convertTo(f, CV_32F);
  cv::Mat gx, gy;
  // Sobel 3x3 has a gain of 8 for a unit ramp; scale to grey levels per pixel.
  cv::Sobel(f, gx, CV_32F, 1, 0, 3, 1.0 / 8.0, 0.0, cv::BORDER_REFLECT101);
  cv::Sobel(f, gy, CV_32F, 0, 1, 3, 1.0 / 8.0, 0.0, cv::BORDER_REFLECT101);
  cv::Mat gxx = gx.mul(gx), gyy = gy.mul(gy), gxy = gx.mul(gy);
  const cv::Size win(2 * window_radius + 1, 2 * window_radius + 1);
  cv::boxFilter(gxx, gxx, CV_32F, win, cv::Point(-1, -1), true, cv::BORDER_REFLECT101);
  cv::boxFilter(gyy, gyy, CV_32F, win, cv::Point(-1, -1), true, cv::BORDER_REFLECT101);
  cv::boxFilter(gxy, gxy, CV_32F, win, cv::Point(-1, -1), true, cv::BORDER_REFLECT101);
  strength->create(image.size(), CV_32F);
  roundness->create(image.size(), CV_32F);
  for (int y = 0; y < image.rows; ++y) {
    const float* a = gxx.ptr<float>(y);
    const float* b = gyy.ptr<float>(y);
    const float* c = gxy.ptr<float>(y);
    float* w = strength->ptr<float>(y);
    float* q = roundness->ptr<float>(y);
    for (int x = 0; x < image.cols; ++x) {
      const double tr = static_cast<double>(a[x]) + b[x];
      const double det = static_cast<double>(a[x]) * b[x] - static_cast<double>(c[x]) * c[x];
      if (tr <= 1e-12 || det <= 0.0) {
        w[x] = 0.0f;
        q[x] = 0.0f;
      } else {
        w[x] = static_cast<float>(det / tr);
        q[x] = static_cast<float>(4.0 * det / (tr * tr));
      }
    }
  }
}

std::vector<InterestPoint> DetectInterestPoints(const cv::Mat& image,
                                                const InterestOptions& options) {
  ROVER_DEMAND(options.Validate().ok());
  cv::Mat w, q;
  ForstnerOperator(image, options.window_radius, &w, &q);
  const int b = std::max(options.border, options.window_radius + 1);
  const int cs = options.cell_size;
  const int ncx = (image.cols + cs - 1) / cs;
  const int ncy = (image.rows + cs - 1) / cs;
  std::vector<InterestPoint> best(static_cast<std::size_t>(ncx * ncy));
  for (int y = b; y < image.rows - b; ++y) {
    const float* wp = w.ptr<float>(y);
    const float* wu = w.ptr<float>(y - 1);
    const float* wd = w.ptr<float>(y + 1);
    const float* qp = q.ptr<float>(y);
    for (int x = b; x < image.cols - b; ++x) {
      const float v = wp[x];
      if (v < options.min_strength || qp[x] < options.min_roundness) continue;
      // 3x3 local maximum (ties broken towards the first pixel in raster order).
      if (v < wp[x - 1] || v <= wp[x + 1] || v < wu[x - 1] || v < wu[x] || v < wu[x + 1] ||
          v <= wd[x - 1] || v <= wd[x] || v <= wd[x + 1]) {
        continue;
      }
      InterestPoint& cell = best[static_cast<std::size_t>((y / cs) * ncx + x / cs)];
      if (v > cell.strength) cell = InterestPoint{x, y, v, qp[x]};
    }
  }
  std::vector<InterestPoint> candidates;
  for (const InterestPoint& p : best) {
    if (p.strength > 0.0) candidates.push_back(p);
  }
  std::sort(candidates.begin(), candidates.end(),
            [](const InterestPoint& a, const InterestPoint& c) {
              if (a.strength != c.strength) return a.strength > c.strength;
              return a.y != c.y ? a.y < c.y : a.x < c.x;
            });
  std::vector<InterestPoint> selected;
  const double sep2 = options.min_separation * options.min_separation;
  for (const InterestPoint& p : candidates) {
    bool ok = true;
    for (const InterestPoint& s : selected) {
      const double dx = p.x - s.x, dy = p.y - s.y;
      if (dx * dx + dy * dy < sep2) {
        ok = false;
        break;
      }
    }
    if (!ok) continue;
    selected.push_back(p);
    if (options.max_features > 0 && static_cast<int>(selected.size()) >= options.max_features) {
      break;
    }
  }
  return selected;
}

}  // namespace rover::dl::vo
