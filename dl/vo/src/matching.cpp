#include "rover/dl/vo/matching.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <string>

#include "rover/base/check.hpp"

namespace rover::dl::vo {

Status MatchOptions::Validate() const {
  if (template_radius < 1 || template_radius > 15) {
    return InvalidArgument("match.template_radius=" + std::to_string(template_radius) +
                           " must be in [1, 15]");
  }
  if (!std::isfinite(min_correlation) || min_correlation <= 0.0 || min_correlation >= 1.0) {
    return InvalidArgument("match.min_correlation must be in (0, 1)");
  }
  if (!std::isfinite(min_curvature) || min_curvature < 0.0) {
    return InvalidArgument("match.min_curvature must be finite and >= 0");
  }
  if (!std::isfinite(min_template_stddev) || min_template_stddev <= 0.0) {
    return InvalidArgument("match.min_template_stddev must be finite and > 0");
  }
  if (min_disparity < 0 || max_disparity <= min_disparity) {
    return InvalidArgument("match disparity range [" + std::to_string(min_disparity) + ", " +
                           std::to_string(max_disparity) + "] must satisfy 0 <= min < max");
  }
  if (!std::isfinite(max_lr_error)) return InvalidArgument("match.max_lr_error must be finite");
  if (!std::isfinite(max_vertical_offset) || max_vertical_offset <= 0.0) {
    return InvalidArgument("match.max_vertical_offset must be finite and > 0");
  }
  if (pyramid_levels < 1 || pyramid_levels > 6) {
    return InvalidArgument("match.pyramid_levels=" + std::to_string(pyramid_levels) +
                           " must be in [1, 6]");
  }
  if (coarse_radius < 2) return InvalidArgument("match.coarse_radius must be >= 2");
  return Status::Ok();
}

ImagePyramid::ImagePyramid(const cv::Mat& image, int levels) {
  ROVER_DEMAND(levels >= 1 && !image.empty() && image.channels() == 1);
  cv::Mat current;
  image.convertTo(current, CV_32F);
  levels_.emplace_back(current);
  for (int l = 1; l < levels; ++l) {
    if (current.cols < 16 || current.rows < 16) break;
    cv::Mat next;
    cv::pyrDown(current, next);
    levels_.emplace_back(next);
    current = next;
  }
}

StereoMatch MatchStereo(const CorrelationImage& left, const CorrelationImage& right,
                        const Eigen::Vector2d& left_px, const MatchOptions& options) {
  StereoMatch m;
  const int x = static_cast<int>(std::lround(left_px.x()));
  const int y = static_cast<int>(std::lround(left_px.y()));
  const int r = options.template_radius;
  Template t;
  if (!ExtractTemplate(left, x, y, r, &t)) {
    m.failure = "template outside the left image";
    return m;
  }
  if (t.StdDev() < options.min_template_stddev) {
    m.failure = "flat template";
    return m;
  }
  // Search x_r in [x - max_d, x - min_d] on row y (a symmetric window covering it).
  const int half = (options.max_disparity - options.min_disparity + 1) / 2;
  const WindowMatch w = SearchWindow(t, right, x - options.min_disparity - half, y, half, 0);
  if (!w.ok) {
    m.failure = w.failure;
    return m;
  }
  m.score = w.score;
  if (w.score < options.min_correlation) {
    m.failure = "low correlation";
    return m;
  }
  if (w.curvature < options.min_curvature) {
    m.failure = "flat correlation peak";
    return m;
  }
  const double dv = w.position.y() - y;
  if (std::abs(dv) > options.max_vertical_offset) {
    m.failure = "vertical offset";
    return m;
  }
  const double d = x - w.position.x();
  if (d < options.min_disparity - 0.5 || d > options.max_disparity + 0.5) {
    m.failure = "disparity out of range";
    return m;
  }
  if (options.max_lr_error > 0.0) {
    // Right-to-left: the right template must come back to the left pixel.
    const int xr = static_cast<int>(std::lround(w.position.x()));
    Template tr;
    if (!ExtractTemplate(right, xr, y, r, &tr)) {
      m.failure = "template outside the right image";
      return m;
    }
    const WindowMatch back = SearchWindow(tr, left, xr + options.min_disparity + half, y, half, 0);
    if (!back.ok ||
        std::abs(back.position.x() - (x + (xr - w.position.x()))) > options.max_lr_error) {
      m.failure = "left-right check";
      return m;
    }
  }
  m.ok = true;
  m.right = Eigen::Vector2d(w.position.x() + (left_px.x() - x), w.position.y() + (left_px.y() - y));
  return m;
}

TrackMatch TrackFeature(const ImagePyramid& previous, const ImagePyramid& current,
                        const TrackRequest& request, const MatchOptions& options) {
  TrackMatch m;
  ROVER_DEMAND(!previous.empty() && !current.empty());
  const int max_level = std::min(previous.levels(), current.levels()) - 1;
  const double w = std::max(request.half_window.x(), request.half_window.y());
  int level = 0;
  while (level < max_level && w / std::ldexp(1.0, level) > options.coarse_radius) ++level;
  m.level = level;
  const Eigen::Matrix2d a_inv = request.warp.inverse();
  if (!a_inv.allFinite()) {
    m.failure = "singular warp";
    return m;
  }
  const int r = options.template_radius;
  Eigen::Vector2d predicted = request.predicted / std::ldexp(1.0, level);
  int rx = static_cast<int>(std::ceil(request.half_window.x() / std::ldexp(1.0, level)));
  int ry = static_cast<int>(std::ceil(request.half_window.y() / std::ldexp(1.0, level)));
  WindowMatch wm;
  for (int l = level; l >= 0; --l) {
    const double scale = std::ldexp(1.0, l);
    Template t;
    if (!ExtractWarpedTemplate(previous.level(l), request.from / scale, a_inv, r, &t)) {
      m.failure = "template outside the previous image";
      return m;
    }
    if (t.StdDev() < options.min_template_stddev) {
      m.failure = "flat template";
      return m;
    }
    wm = SearchWindow(t, current.level(l), static_cast<int>(std::lround(predicted.x())),
                      static_cast<int>(std::lround(predicted.y())), rx, ry);
    if (!wm.ok) {
      m.failure = wm.failure;
      return m;
    }
    if (wm.score < options.min_correlation) {
      m.score = wm.score;
      m.failure = "low correlation";
      return m;
    }
    predicted = wm.position * 2.0;
    rx = ry = 2;
  }
  m.score = wm.score;
  if (wm.curvature < options.min_curvature) {
    m.failure = "flat correlation peak";
    return m;
  }
  m.ok = true;
  m.to = wm.position;
  return m;
}

}  // namespace rover::dl::vo
