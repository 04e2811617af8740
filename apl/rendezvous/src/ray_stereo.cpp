#include "rover/apl/rendezvous/ray_stereo.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::apl::rendezvous {

Status RayMatchOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckRange("ray_match.half_window", half_window, 1, 40, "px"));
  ROVER_RETURN_IF_ERROR(CheckRange("ray_match.t_min", t_min, Bounds::Positive(), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("ray_match.t_max", t_max, Bounds::OpenLow(t_min, 1e4), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("ray_match.step_px", step_px, Bounds::OpenLow(0.0, 2.0), "px"));
  ROVER_RETURN_IF_ERROR(CheckRange("ray_match.min_ncc", min_ncc, -1.0, 1.0));
  ROVER_RETURN_IF_ERROR(CheckNonNegative("ray_match.min_texture", min_texture));
  ROVER_RETURN_IF_ERROR(CheckRange("ray_match.sigma_px", sigma_px, Bounds::OpenLow(0.0, 10.0), "px"));
  return Status::Ok();
}

Result<RayMatch> MatchAlongRay(const cv::Mat& left, const geometry::CameraModel& left_model,
                               const cv::Mat& right, const geometry::CameraModel& right_model,
                               const Eigen::Vector2d& pixel, const RayMatchOptions& o) {
  ROVER_RETURN_IF_ERROR(o.Validate());
  if (left.empty() || right.empty() || left.type() != CV_8UC1 || right.type() != CV_8UC1) {
    return InvalidArgument("stereo pair: both images must be non-empty 8-bit grey");
  }
  if (left.cols != left_model.width() || left.rows != left_model.height() ||
      right.cols != right_model.width() || right.rows != right_model.height()) {
    return InvalidArgument("stereo pair: image sizes " + std::to_string(left.cols) + "x" +
                           std::to_string(left.rows) + " / " + std::to_string(right.cols) + "x" +
                           std::to_string(right.rows) + " differ from the models' " +
                           std::to_string(left_model.width()) + "x" +
                           std::to_string(left_model.height()));
  }
  if (!(std::isfinite(pixel.x()) && std::isfinite(pixel.y()) && pixel.x() >= -0.5 &&
        pixel.y() >= -0.5 && pixel.x() < left.cols - 0.5 && pixel.y() < left.rows - 0.5)) {
    return InvalidArgument("pixel (" + FormatNumber(pixel.x()) + ", " + FormatNumber(pixel.y()) +
                           ") is outside the " + std::to_string(left.cols) + "x" +
                           std::to_string(left.rows) + " left image");
  }
  RayMatch m;
  const auto ray = left_model.Unproject(pixel);
  if (!ray) {
    m.why = "no ray through the pixel";
    return m;
  }
  const int side = 2 * o.half_window + 1;
  const cv::Size size(side, side);
  cv::Mat tpl;
  cv::getRectSubPix(left, size, cv::Point2f(static_cast<float>(pixel.x()), static_cast<float>(pixel.y())),
                    tpl, CV_32F);
  cv::Scalar tm, ts;
  cv::meanStdDev(tpl, tm, ts);
  if (ts[0] < o.min_texture) {
    m.why = "no texture (grey std " + FormatNumber(ts[0]) + " < " + FormatNumber(o.min_texture) + ")";
    return m;
  }
  const cv::Mat tz = tpl - tm[0];
  std::vector<double> ts_v, scores;
  double t = o.t_min;
  bool left_image = false;
  while (t <= o.t_max && ts_v.size() < 4000) {
    const Eigen::Vector3d p = ray->origin + t * ray->direction;
    const auto pr = right_model.Project(p);
    if (!pr || pr->x() < o.half_window || pr->y() < o.half_window ||
        pr->x() > right.cols - 1 - o.half_window || pr->y() > right.rows - 1 - o.half_window) {
      if (!ts_v.empty()) {
        left_image = true;
        break;
      }
      t *= 1.02;
      continue;
    }
    cv::Mat win;
    cv::getRectSubPix(right, size, cv::Point2f(static_cast<float>(pr->x()), static_cast<float>(pr->y())),
                      win, CV_32F);
    cv::Scalar wm, wsd;
    cv::meanStdDev(win, wm, wsd);
    double score = -1.0;
    if (wsd[0] > 1e-3) {
      score = tz.dot(win - wm[0]) / (static_cast<double>(tpl.total()) * ts[0] * wsd[0]);
    }
    ts_v.push_back(t);
    scores.push_back(score);
    // The right patch moves by about |d pixel / d t|; step so it moves ~step_px.
    const auto pr2 = right_model.Project(ray->origin + (t * 1.001) * ray->direction);
    const double px_per_m = pr2 ? std::max(1e-6, (*pr2 - *pr).norm() / (0.001 * t)) : 1e-3;
    t += std::max(1e-4, o.step_px / px_per_m);
  }
  if (scores.size() < 3) {
    m.why = "the ray stays outside the right image";
    return m;
  }
  const std::size_t k = static_cast<std::size_t>(std::max_element(scores.begin(), scores.end()) - scores.begin());
  m.ncc = scores[k];
  if (scores[k] < o.min_ncc) {
    m.why = "best correlation " + FormatNumber(scores[k]) + " < " + FormatNumber(o.min_ncc);
    return m;
  }
  if (k == 0 || k + 1 == scores.size()) {
    m.why = left_image && k + 1 == scores.size() ? "best match where the ray leaves the right image"
                                                 : "best match at the end of the searched range";
    return m;
  }
  const double ym = scores[k - 1], y0 = scores[k], yp = scores[k + 1];
  const double den = ym - 2.0 * y0 + yp;
  const double off = std::abs(den) > 1e-12 ? std::clamp(0.5 * (ym - yp) / den, -0.5, 0.5) : 0.0;
  const double t_best = off >= 0.0 ? ts_v[k] + off * (ts_v[k + 1] - ts_v[k])
                                   : ts_v[k] + off * (ts_v[k] - ts_v[k - 1]);
  m.found = true;
  m.t = t_best;
  m.point = ray->origin + t_best * ray->direction;
  const double step = 0.5 * (ts_v[k + 1] - ts_v[k - 1]);
  m.sigma_t = step * (o.sigma_px / o.step_px);
  return m;
}

}  // namespace rover::apl::rendezvous
