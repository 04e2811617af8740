#include "rover/apl/rendezvous/target_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <utility>

#include <Eigen/Cholesky>
#include <Eigen/SVD>
#include <opencv2/imgproc.hpp>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/base/range_check.hpp"

namespace rover::apl::rendezvous {
namespace {

using Eigen::Isometry3d;
using Eigen::Vector2d;
using Eigen::Vector3d;

bool Inside(const cv::Mat& im, const Vector2d& p, double margin) {
  return p.x() >= margin && p.y() >= margin && p.x() <= im.cols - 1 - margin &&
         p.y() <= im.rows - 1 - margin;
}

// Distance of c from the segment a-b.
double SegmentDistance(const Vector2d& c, const Vector2d& a, const Vector2d& b) {
  const Vector2d ab = b - a;
  const double len2 = ab.squaredNorm();
  const double s = len2 > 1e-12 ? std::clamp((c - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (a + s * ab - c).norm();
}

// Parabola vertex offset in [-0.5, 0.5] through (-1, ym), (0, y0), (1, yp).
double Vertex(double ym, double y0, double yp) {
  const double den = ym - 2.0 * y0 + yp;
  return std::abs(den) > 1e-12 ? std::clamp(0.5 * (ym - yp) / den, -0.5, 0.5) : 0.0;
}

// Information (inverse covariance) of a feature's residual m * ref - cur: its two ranges along
// the ref ray moved by `rotation`, the pixel precision across it.
Eigen::Matrix3d RayInformation(const RangedFeature& f, const Eigen::Matrix3d& rotation) {
  const Vector3d d = rotation * f.ref_ray;
  const double along2 = f.ref_sigma * f.ref_sigma + f.cur_sigma * f.cur_sigma + 1e-8;
  const double across = std::max(5e-4, f.across_sigma);
  const Eigen::Matrix3d dd = d * d.transpose();
  return dd / along2 + (Eigen::Matrix3d::Identity() - dd) / (across * across);
}

// The motion minimising the sum of the features' residuals weighted by RayInformation (Gauss-
// Newton from `start`, the rotation perturbed on the left).
Isometry3d WeightedRigidFit(const std::vector<RangedFeature>& f,
                            const std::vector<std::size_t>& set, const Isometry3d& start) {
  Isometry3d t = start;
  std::vector<Eigen::Matrix3d> w;
  for (std::size_t q : set) w.push_back(RayInformation(f[q], start.linear()));
  for (int iteration = 0; iteration < 10; ++iteration) {
    Eigen::Matrix<double, 6, 6> h = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> g = Eigen::Matrix<double, 6, 1>::Zero();
    for (std::size_t k = 0; k < set.size(); ++k) {
      const RangedFeature& p = f[set[k]];
      const Vector3d rx = t.linear() * p.ref;
      const Vector3d r = rx + t.translation() - p.cur;
      Eigen::Matrix<double, 3, 6> j;
      j.leftCols<3>() << 0.0, rx.z(), -rx.y(), -rx.z(), 0.0, rx.x(), rx.y(), -rx.x(), 0.0;
      j.rightCols<3>().setIdentity();
      h += j.transpose() * w[k] * j;
      g += j.transpose() * w[k] * r;
    }
    const Eigen::LDLT<Eigen::Matrix<double, 6, 6>> ldlt(h);
    if (ldlt.info() != Eigen::Success) break;
    const Eigen::Matrix<double, 6, 1> dx = -ldlt.solve(g);
    if (!dx.allFinite()) break;
    const double angle = dx.head<3>().norm();
    if (angle > 1e-12) {
      t.linear() = Eigen::AngleAxisd(angle, dx.head<3>() / angle).toRotationMatrix() * t.linear();
    }
    t.translation() += dx.tail<3>();
    if (dx.norm() < 1e-9) break;
  }
  return t;
}

// Step 6's RANSAC and fit, with the sphere (along_rays false: a 3-point rigid fit each, Kabsch)
// or the ellipsoids about the rays (also one feature each with the predicted rotation, the
// weighted fit).
MotionEstimate RansacMotion(const std::vector<RangedFeature>& f, const Isometry3d& predicted,
                            const TrackerOptions& o, unsigned seed, bool along_rays) {
  MotionEstimate e;
  e.inlier.assign(f.size(), false);
  if (f.size() < 3) return e;
  auto consistent = [&](const Isometry3d& t, const RangedFeature& p) {
    const Vector3d r = t * p.ref - p.cur;
    const double b = std::max(o.inlier_m, o.inlier_range_ratio * p.ref_t);
    if (!along_rays) return r.norm() <= b;
    const double a = std::max(b, o.inlier_range_sigma * std::hypot(p.ref_sigma, p.cur_sigma));
    const double along = r.dot(t.linear() * p.ref_ray);
    const double across2 = std::max(0.0, r.squaredNorm() - along * along);
    return along * along / (a * a) + across2 / (b * b) <= 1.0;
  };
  auto agreeing = [&](const Isometry3d& t) {
    std::vector<std::size_t> set;
    for (std::size_t q = 0; q < f.size(); ++q) {
      if (consistent(t, f[q])) set.push_back(q);
    }
    return set;
  };
  std::vector<std::size_t> best_set;
  Isometry3d best = predicted;
  if (along_rays) {
    // The rotation of dl/pose is good (IMU attitude, a heading drift of a fraction of a degree a
    // leg), its translation is what slips: one feature each with the predicted rotation.
    for (const RangedFeature& p : f) {
      Isometry3d t = predicted;
      t.translation() = p.cur - predicted.linear() * p.ref;
      std::vector<std::size_t> set = agreeing(t);
      if (set.size() > best_set.size()) {
        best_set = std::move(set);
        best = t;
      }
    }
  }
  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, f.size() - 1);
  for (int it = 0; it < o.ransac_iterations; ++it) {
    const std::size_t i = pick(rng), j = pick(rng), k = pick(rng);
    if (i == j || j == k || i == k) continue;
    const Vector3d& a = f[i].ref;
    if ((f[j].ref - a).cross(f[k].ref - a).norm() < 1e-3) continue;
    const Isometry3d t = FitRigid({f[i].ref, f[j].ref, f[k].ref}, {f[i].cur, f[j].cur, f[k].cur});
    std::vector<std::size_t> set = agreeing(t);
    if (set.size() > best_set.size()) {
      best_set = std::move(set);
      best = t;
    }
  }
  if (best_set.size() < 3) return e;
  for (int round = 0; round < 2; ++round) {
    if (along_rays) {
      best = WeightedRigidFit(f, best_set, best);
    } else {
      std::vector<Vector3d> a, b;
      for (std::size_t q : best_set) {
        a.push_back(f[q].ref);
        b.push_back(f[q].cur);
      }
      best = FitRigid(a, b);
    }
    best_set = agreeing(best);
    if (best_set.size() < 3) return e;
  }
  double ss = 0.0;
  for (std::size_t q : best_set) {
    e.inlier[q] = true;
    ss += (best * f[q].ref - f[q].cur).squaredNorm();
  }
  e.motion = best;
  e.inliers = static_cast<int>(best_set.size());
  e.rms = std::sqrt(ss / static_cast<double>(best_set.size()));
  return e;
}

}  // namespace

Status TrackerOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.window_m", window_m, Bounds::OpenLow(0.0, 10.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.min_window_px", min_window_px, 16, 2000, "px"));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.max_window_px", max_window_px, min_window_px, 4000, "px"));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.max_features", max_features, 3, 1000));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.min_roundness", min_roundness, 0.0, 1.0));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.min_weight_ratio", min_weight_ratio, 0.0, 100.0));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.max_feature_offset_m", max_feature_offset_m,
                                   Bounds::OpenLow(0.0, 50.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.template_half", template_half, 3, 40, "px"));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.range_slack", range_slack, Bounds::OpenLow(0.0, 4.0)));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.band_px", band_px, 0, 200, "px"));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.refine_px", refine_px, 1, 20, "px"));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.min_ncc", min_ncc, -1.0, 1.0));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.min_inliers", min_inliers, 3, 1000));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.min_inlier_ratio", min_inlier_ratio, 0.0, 1.0));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.inlier_m", inlier_m, Bounds::OpenLow(0.0, 1.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.inlier_range_ratio", inlier_range_ratio, 0.0, 0.5));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.inlier_range_sigma", inlier_range_sigma, 0.0, 10.0));
  ROVER_RETURN_IF_ERROR(
      CheckRange("tracker.across_sigma_px", across_sigma_px, Bounds::OpenLow(0.0, 10.0), "px"));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.min_target_alone_ncc", min_target_alone_ncc, -1.0, 1.0));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.max_target_alone_jump_m", max_target_alone_jump_m,
                                   Bounds::OpenLow(0.0, 10.0), "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.gate_sigma", gate_sigma, Bounds::OpenLow(0.0, 100.0)));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.gate_floor_m", gate_floor_m, 0.0, 1.0, "m"));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.ransac_iterations", ransac_iterations, 1, 100000));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.stereo_half_window", stereo_half_window, 2, 40, "px"));
  ROVER_RETURN_IF_ERROR(CheckRange("tracker.min_stereo_ncc", min_stereo_ncc, -1.0, 1.0));
  return Status::Ok();
}

void TrackerOptions::BindParams(ParamBinder<TrackerOptions>& b) {
  using O = TrackerOptions;
  b.Bind("window_m", &O::window_m, "m", "side of the square about the target where features are taken");
  b.Bind("min_window_px", &O::min_window_px, "px", "least side of that window in the image");
  b.Bind("max_window_px", &O::max_window_px, "px", "largest side of that window");
  b.Bind("max_features", &O::max_features, "", "Förstner points kept, strongest first");
  b.Bind("min_roundness", &O::min_roundness, "", "Förstner roundness threshold");
  b.Bind("min_weight_ratio", &O::min_weight_ratio, "", "Förstner weight threshold, times the window's mean");
  b.Bind("max_feature_offset_m", &O::max_feature_offset_m, "m", "features farther from the target dropped");
  b.Bind("template_half", &O::template_half, "px", "half side of the projected patch");
  b.Bind("range_slack", &O::range_slack, "", "epipolar segment: t / (1 + s) .. t (1 + s)");
  b.Bind("band_px", &O::band_px, "px", "searched across the epipolar segment");
  b.Bind("refine_px", &O::refine_px, "px", "search of the refinement with the measured motion");
  b.Bind("min_ncc", &O::min_ncc, "", "lowest patch correlation of a match");
  b.Bind("min_inliers", &O::min_inliers, "", "fewer features consistent with one motion: TARGET_LOST");
  b.Bind("min_inlier_ratio", &O::min_inlier_ratio, "",
         "fewer inliers than this share of the features found again: TARGET_LOST");
  b.Bind("inlier_m", &O::inlier_m, "m", "RANSAC threshold floor");
  b.Bind("inlier_range_ratio", &O::inlier_range_ratio, "", "RANSAC threshold as a fraction of range");
  b.Bind("inlier_range_sigma", &O::inlier_range_sigma, "",
         "inliers within ellipsoids this many range sigma long along the rays (0: the sphere)");
  b.Bind("across_sigma_px", &O::across_sigma_px, "px",
         "a feature's 1-sigma across its ray, its weight in the motion fit");
  b.Bind("min_target_alone_ncc", &O::min_target_alone_ncc, "",
         "too few features agree: the target's own match goes on alone when this good");
  b.Bind("max_target_alone_jump_m", &O::max_target_alone_jump_m, "m",
         "... and within this of where the pose puts it");
  b.Bind("gate_floor_m", &O::gate_floor_m, "m", "... plus this (a repeating texture's next cell is not the target)");
  b.Bind("gate_sigma", &O::gate_sigma, "", "target measurement gate against the motion, in sigma");
  b.Bind("ransac_iterations", &O::ransac_iterations, "", "3-point rigid fits tried");
  b.Bind("stereo_half_window", &O::stereo_half_window, "px", "half side of the range correlation patch");
  b.Bind("min_stereo_ncc", &O::min_stereo_ncc, "", "lowest correlation of a range");
}

Isometry3d FitRigid(const std::vector<Vector3d>& a, const std::vector<Vector3d>& b) {
  ROVER_DEMAND(a.size() == b.size() && a.size() >= 3);
  Vector3d ca = Vector3d::Zero(), cb = Vector3d::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) {
    ca += a[i];
    cb += b[i];
  }
  ca /= static_cast<double>(a.size());
  cb /= static_cast<double>(b.size());
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (std::size_t i = 0; i < a.size(); ++i) h += (a[i] - ca) * (b[i] - cb).transpose();
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0) d(2, 2) = -1.0;
  Isometry3d t = Isometry3d::Identity();
  t.linear() = svd.matrixV() * d * svd.matrixU().transpose();
  t.translation() = cb - t.linear() * ca;
  return t;
}

MotionEstimate EstimateMotion(const std::vector<RangedFeature>& features,
                              const Isometry3d& predicted, const TrackerOptions& options,
                              unsigned seed) {
  return RansacMotion(features, predicted, options, seed, options.inlier_range_sigma > 0.0);
}

TargetTracker::TargetTracker(const TrackerOptions& options) : options_(options) {
  ROVER_DEMAND(options_.Validate().ok());
}

Result<TargetTracker::Frame> TargetTracker::CopyFrame(const NavcamPair& pair,
                                                       const Isometry3d& site_from_rover) {
  if (pair.left == nullptr || pair.right == nullptr || pair.left_model == nullptr ||
      pair.right_model == nullptr) {
    return InvalidArgument("target tracking needs a full NAVCAM pair with both camera models");
  }
  if (pair.left->type() != CV_8UC1 || pair.right->type() != CV_8UC1 || pair.left->empty() ||
      pair.right->empty()) {
    return InvalidArgument("target tracking: both images must be non-empty 8-bit grey");
  }
  if (pair.left->cols != pair.left_model->width() || pair.left->rows != pair.left_model->height() ||
      pair.right->cols != pair.right_model->width() || pair.right->rows != pair.right_model->height()) {
    return InvalidArgument("target tracking: image sizes differ from the camera models'");
  }
  return Frame{pair.left->clone(), pair.right->clone(), *pair.left_model, *pair.right_model,
               site_from_rover};
}

bool TargetTracker::TakeFeatures(const Frame& f, const Vector3d& target, const Vector2d& target_px,
                                 std::vector<Point>* points, std::string* why) const {
  const auto ray = f.left_model.Unproject(target_px);
  points->clear();
  if (!ray) {
    *why = "no ray through the target pixel";
    return false;
  }
  const double t_target = (target - ray->origin).norm();
  // The angle of one pixel there (the features' precision across their rays).
  const auto ray1 = f.left_model.Unproject(target_px + Vector2d(1.0, 0.0));
  const double rad_per_px =
      ray1 ? std::acos(std::clamp(ray->direction.dot(ray1->direction), -1.0, 1.0)) : 0.0;
  points->push_back({target_px, target, t_target, 0.0, ray->direction, rad_per_px});
  // Window side: window_m across the line of sight at the target, in pixels.
  const Vector3d across = ray->direction.cross(Vector3d::UnitZ()).normalized();
  const auto p1 = f.left_model.Project(target + 0.1 * across);
  const double px_per_m = p1 ? (*p1 - target_px).norm() / 0.1 : 100.0;
  const int side = std::clamp(static_cast<int>(std::lround(px_per_m * options_.window_m)),
                              options_.min_window_px, options_.max_window_px);
  const cv::Rect roi(static_cast<int>(std::lround(target_px.x())) - side / 2,
                     static_cast<int>(std::lround(target_px.y())) - side / 2, side, side);
  ForstnerOptions fo;
  fo.max_points = options_.max_features;
  fo.min_roundness = options_.min_roundness;
  fo.min_weight_ratio = options_.min_weight_ratio;
  fo.suppression_radius = std::max(4, side / 20);
  auto ips = ForstnerPoints(f.left, roi, fo);
  if (!ips.ok()) {
    *why = "interest points: " + ips.status().message();
    return false;
  }
  RayMatchOptions ro;
  ro.half_window = options_.stereo_half_window;
  ro.min_ncc = options_.min_stereo_ncc;
  ro.t_min = std::max(0.3, t_target - 1.5 * options_.max_feature_offset_m);
  ro.t_max = t_target + 1.5 * options_.max_feature_offset_m;
  int unranged = 0;
  for (const InterestPoint& ip : *ips) {
    if ((ip.pixel - target_px).norm() < options_.template_half) continue;
    auto m = MatchAlongRay(f.left, f.left_model, f.right, f.right_model, ip.pixel, ro);
    if (!m.ok() || !m->found || (m->point - target).norm() > options_.max_feature_offset_m) {
      ++unranged;
      continue;
    }
    const auto r = f.left_model.Unproject(ip.pixel);
    points->push_back(
        {ip.pixel, m->point, m->t, m->sigma_t, r ? r->direction : ray->direction, rad_per_px});
  }
  const int n = static_cast<int>(points->size()) - 1;
  if (n < options_.min_inliers) {
    *why = std::to_string(ips->size()) + " interest points in a " + std::to_string(side) +
           " px window about the target, " + std::to_string(n) + " with a range (need " +
           std::to_string(options_.min_inliers) + ")";
    return false;
  }
  return true;
}

bool TargetTracker::MatchPoint(const Frame& ref, const Point& p, const Frame& cur,
                               const Isometry3d& m, const Vector2d* near, int band,
                               Vector2d* pixel, double* ncc) const {
  const auto ray = ref.left_model.Unproject(p.pixel);
  if (!ray) return false;
  // The template is centred where p itself lands under m (so its centre is p's patch whatever
  // p's range error), and searched along the epipolar segment, or about `near`.
  const auto at = cur.left_model.Project(m * p.xyz);
  if (!at) return false;
  const Vector2d centre = *at;
  Vector2d a, b;
  if (near != nullptr) {
    a = b = *near;
  } else {
    const double s = 1.0 + options_.range_slack;
    std::vector<Vector2d> seg;
    for (int k = 0; k <= 24; ++k) {
      const double t = p.t / s * std::pow(s * s, k / 24.0);
      if (auto q = cur.left_model.Project(m * (ray->origin + t * ray->direction))) {
        if (Inside(cur.left, *q, -band)) seg.push_back(*q);
      }
    }
    if (seg.size() < 2) return false;
    a = seg.front();
    b = seg.back();
  }
  // The ref patch projected into cur about `centre` through the local ground plane at p.
  const int h = options_.template_half, side = 2 * h + 1;
  cv::Mat mapx(side, side, CV_32F), mapy(side, side, CV_32F);
  const Isometry3d minv = m.inverse();
  const Vector3d n_ground = Vector3d::UnitZ();
  int outside = 0;
  for (int dy = -h; dy <= h; ++dy) {
    for (int dx = -h; dx <= h; ++dx) {
      float& mx = mapx.at<float>(dy + h, dx + h);
      float& my = mapy.at<float>(dy + h, dx + h);
      mx = my = -100.0f;
      const auto rc = cur.left_model.Unproject(centre + Vector2d(dx, dy));
      if (!rc) {
        ++outside;
        continue;
      }
      const Vector3d o = minv * rc->origin;
      const Vector3d d = minv.linear() * rc->direction;
      // The ground plane through p; where the ray grazes it, the plane facing the ref camera.
      Vector3d n = n_ground;
      if (std::abs(n.dot(d)) < 0.05) n = ray->direction;
      const double den = n.dot(d);
      const double s = std::abs(den) > 1e-9 ? n.dot(p.xyz - o) / den : -1.0;
      const auto q = s > 0.0 ? ref.left_model.Project(o + s * d) : std::nullopt;
      if (!q || !Inside(ref.left, *q, 0.0)) {
        ++outside;
        continue;
      }
      mx = static_cast<float>(q->x());
      my = static_cast<float>(q->y());
    }
  }
  if (outside > side * side / 10) return false;
  cv::Mat tpl;
  cv::remap(ref.left, tpl, mapx, mapy, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  tpl.convertTo(tpl, CV_32F);
  // Search region: the segment grown by the band and the template.
  const int grow = band + h + 2;
  const int x0 = static_cast<int>(std::floor(std::min(a.x(), b.x()))) - grow;
  const int y0 = static_cast<int>(std::floor(std::min(a.y(), b.y()))) - grow;
  const int x1 = static_cast<int>(std::ceil(std::max(a.x(), b.x()))) + grow;
  const int y1 = static_cast<int>(std::ceil(std::max(a.y(), b.y()))) + grow;
  const cv::Rect region = cv::Rect(x0, y0, x1 - x0 + 1, y1 - y0 + 1) & cv::Rect(0, 0, cur.left.cols, cur.left.rows);
  if (region.width < side + 2 || region.height < side + 2) return false;
  cv::Mat search, response;
  cur.left(region).convertTo(search, CV_32F);
  cv::matchTemplate(search, tpl, response, cv::TM_CCOEFF_NORMED);
  double best = -2.0;
  int bx = -1, by = -1;
  for (int y = 0; y < response.rows; ++y) {
    for (int x = 0; x < response.cols; ++x) {
      const float r = response.at<float>(y, x);
      if (!(r > best)) continue;
      const Vector2d c(region.x + x + h, region.y + y + h);
      if (SegmentDistance(c, a, b) > band + 0.5) continue;
      best = r;
      bx = x;
      by = y;
    }
  }
  if (bx < 0 || best < options_.min_ncc) {
    *ncc = best;
    return false;
  }
  double ox = 0.0, oy = 0.0;
  if (bx > 0 && bx + 1 < response.cols) {
    ox = Vertex(response.at<float>(by, bx - 1), best, response.at<float>(by, bx + 1));
  }
  if (by > 0 && by + 1 < response.rows) {
    oy = Vertex(response.at<float>(by - 1, bx), best, response.at<float>(by + 1, bx));
  }
  // The template's centre pixel maps to `centre`; the match moves it by the offset found.
  *pixel = Vector2d(region.x + bx + h + ox, region.y + by + h + oy);
  *ncc = best;
  return true;
}

Result<TargetFix> TargetTracker::Designate(const NavcamPair& pair, const Isometry3d& site_from_rover,
                                           const Vector2d& pixel) {
  ROVER_ASSIGN_OR_RETURN(Frame f, CopyFrame(pair, site_from_rover));
  RayMatchOptions ro;
  ro.half_window = options_.stereo_half_window;
  ro.min_ncc = options_.min_stereo_ncc;
  ro.t_min = 0.5;
  ro.t_max = 60.0;
  const std::string where = "pixel (" + FormatNumber(pixel.x()) + ", " + FormatNumber(pixel.y()) + ")";
  ROVER_ASSIGN_OR_RETURN(RayMatch m, MatchAlongRay(f.left, f.left_model, f.right, f.right_model, pixel, ro));
  if (!m.found) return InvalidArgument(where + " has no stereo range: " + m.why);
  std::vector<Point> points;
  std::string why;
  if (!TakeFeatures(f, m.point, pixel, &points, &why)) {
    return InvalidArgument(where + " cannot be tracked: " + why);
  }
  ref_ = std::move(f);
  points_ = std::move(points);
  target_pixel_ = pixel;
  ref_sigma_ = m.sigma_t;
  started_ = true;
  steps_ = 0;
  tracks_.clear();
  TargetFix fix;
  fix.tracked = true;
  fix.target_measured = true;
  fix.target_rover = m.point;
  fix.sigma = m.sigma_t;
  fix.features = static_cast<int>(points_.size()) - 1;
  Draw(*ref_, "target_00", fix);
  return fix;
}

Result<TargetFix> TargetTracker::Track(const NavcamPair& pair, const Isometry3d& site_from_rover) {
  if (!started_) return FailedPrecondition("target tracking: no target designated");
  ROVER_ASSIGN_OR_RETURN(Frame cur, CopyFrame(pair, site_from_rover));
  ++steps_;
  TargetFix fix;
  fix.features = static_cast<int>(points_.size()) - 1;
  const Frame& ref = *ref_;
  const Isometry3d predicted = cur.site_from_rover.inverse() * ref.site_from_rover;
  fix.predicted_motion = predicted;
  const Vector3d target_ref = points_[0].xyz;
  const auto tp = cur.left_model.Project(predicted * target_ref);
  if (!tp || !Inside(cur.left, *tp, options_.template_half)) {
    fix.loss = TargetLoss::kOutOfView;
    fix.why = tp ? "the target is expected at (" + FormatNumber(tp->x()) + ", " +
                       FormatNumber(tp->y()) + "), outside the left image"
                 : "the target is behind the camera";
    Draw(cur, "target_" + std::string(steps_ < 10 ? "0" : "") + std::to_string(steps_), fix);
    return fix;
  }
  const std::size_t n = points_.size();
  std::vector<Vector2d> px(n);
  std::vector<Vector3d> xyz(n);
  std::vector<double> sig(n, 0.0), ncc(n, -1.0);
  std::vector<char> ok(n, 0), inl(n, 0);
  RayMatchOptions ro;
  ro.half_window = options_.stereo_half_window;
  ro.min_ncc = options_.min_stereo_ncc;
  auto range = [&](std::size_t i, const Isometry3d& m) {
    const double t_pred = (m * points_[i].xyz - cur.left_model.Unproject(px[i])->origin).norm();
    const double s = 1.0 + options_.range_slack;
    ro.t_min = std::max(0.2, t_pred / s);
    ro.t_max = std::max(ro.t_min + 0.05, t_pred * s);
    auto r = MatchAlongRay(cur.left, cur.left_model, cur.right, cur.right_model, px[i], ro);
    if (!r.ok() || !r->found) return false;
    xyz[i] = r->point;
    sig[i] = r->sigma_t;
    return true;
  };
  // Step 6 over the features found again (not the target) for R_cur from R_ref.
  auto fit = [&](Isometry3d* motion, double* rms) {
    std::vector<std::size_t> idx;
    std::vector<RangedFeature> features;
    for (std::size_t i = 1; i < n; ++i) {
      if (!ok[i]) continue;
      idx.push_back(i);
      const Point& p = points_[i];
      features.push_back({p.xyz, xyz[i], p.ray, p.t, p.sigma, sig[i],
                          options_.across_sigma_px * p.rad_per_px * p.t});
    }
    std::fill(inl.begin(), inl.end(), 0);
    if (static_cast<int>(idx.size()) < options_.min_inliers) return 0;
    const MotionEstimate e =
        EstimateMotion(features, predicted, options_, 0x5c1e7a26u + static_cast<unsigned>(steps_));
    if (e.inliers == 0) return 0;
    for (std::size_t k = 0; k < idx.size(); ++k) inl[idx[k]] = e.inlier[k] ? 1 : 0;
    *motion = e.motion;
    *rms = e.rms;
    return e.inliers;
  };
  // Pass 1: along the epipolar segments of the predicted motion.
  for (std::size_t i = 0; i < n; ++i) {
    ok[i] = MatchPoint(ref, points_[i], cur, predicted, nullptr, options_.band_px, &px[i], &ncc[i]) &&
            range(i, predicted);
  }
  Isometry3d motion = predicted;
  double rms = 0.0;
  int inliers = fit(&motion, &rms);
  // Pass 2: the patches projected with the measured motion, matched again near pass 1.
  if (inliers >= options_.min_inliers) {
    for (std::size_t i = 0; i < n; ++i) {
      const auto guess = cur.left_model.Project(motion * points_[i].xyz);
      if (!guess) {
        ok[i] = 0;
        continue;
      }
      const Vector2d near = ok[i] ? px[i] : *guess;
      ok[i] = MatchPoint(ref, points_[i], cur, motion, &near,
                         ok[i] ? options_.refine_px : options_.band_px, &px[i], &ncc[i]) &&
              range(i, motion);
    }
    inliers = fit(&motion, &rms);
  }
  int matched = 0;
  for (std::size_t i = 1; i < n; ++i) matched += ok[i] ? 1 : 0;
  fix.matched = matched;
  fix.inliers = inliers;
  fix.rms = rms;
  tracks_.clear();
  for (std::size_t i = 0; i < n; ++i) {
    tracks_.push_back({points_[i].pixel, px[i], ncc[i], ok[i] != 0, inl[i] != 0, points_[i].xyz,
                       ok[i] ? xyz[i] : Vector3d::Zero(), i == 0 ? ref_sigma_ : points_[i].sigma,
                       ok[i] ? sig[i] : 0.0});
  }
  const std::string name = "target_" + std::string(steps_ < 10 ? "0" : "") + std::to_string(steps_);
  const int need = std::max(options_.min_inliers,
                            static_cast<int>(std::ceil(options_.min_inlier_ratio * matched)));
  if (inliers < need) {
    // Too few features agree on a motion. The target's own patch, matched and ranged with a
    // high correlation, still says where it is (on bare sand at 9 m the rock carries nearly all
    // the texture): keep tracking on it alone, the motion being the prediction moved so that it
    // carries the target there.
    const bool alone = ok[0] && ncc[0] >= options_.min_target_alone_ncc &&
                       (xyz[0] - predicted * target_ref).norm() <=
                           options_.max_target_alone_jump_m;
    if (!alone) {
      fix.loss = TargetLoss::kTooFewFeatures;
      fix.why = std::to_string(matched) + " of " + std::to_string(n - 1) +
                " features found again, " + std::to_string(inliers) +
                " consistent with one motion (need " + std::to_string(need) + ")";
      Draw(cur, name, fix);
      return fix;
    }
    motion = predicted;
    motion.translation() += xyz[0] - predicted * target_ref;
    fix.why = "the target alone: " + std::to_string(inliers) + " of " + std::to_string(matched) +
              " features consistent with one motion";
    fix.tracked = true;
    fix.target_measured = true;
    fix.motion = motion;
    fix.target_rover = xyz[0];
    fix.sigma = std::max(sig[0], 1e-3);
    Draw(cur, name, fix);
    Rereference(std::move(cur), xyz[0], px[0], &fix);
    return fix;
  }
  fix.motion = motion;
  // The target: carried by the motion, and measured where its own patch matched.
  const Vector3d carried = motion * target_ref;
  const double sigma_ref = std::max(ref_sigma_, 1e-3);
  const double var_c = sigma_ref * sigma_ref + rms * rms / std::max(1, inliers) + 1e-6;
  Vector3d target = carried;
  double var = var_c;
  if (ok[0]) {
    const double var_m = std::max(sig[0] * sig[0], 1e-6);
    const double gate = options_.gate_sigma * std::sqrt(var_m + var_c) + options_.gate_floor_m;
    if ((xyz[0] - carried).norm() <= gate) {
      target = (xyz[0] / var_m + carried / var_c) / (1.0 / var_m + 1.0 / var_c);
      var = 1.0 / (1.0 / var_m + 1.0 / var_c);
      fix.target_measured = true;
    }
  }
  fix.tracked = true;
  fix.target_rover = target;
  fix.sigma = std::sqrt(var);
  const auto carried_px = cur.left_model.Project(target);
  const Vector2d target_px = fix.target_measured ? px[0] : carried_px ? *carried_px : *tp;
  Draw(cur, name, fix);
  Rereference(std::move(cur), target, target_px, &fix);
  return fix;
}

void TargetTracker::Rereference(Frame cur, const Vector3d& target, const Vector2d& target_px,
                                TargetFix* fix) {
  // The new pair becomes the reference, its features about the target.
  std::vector<Point> points;
  std::string why;
  const bool enough = TakeFeatures(cur, target, target_px, &points, &why);
  ref_ = std::move(cur);
  points_ = std::move(points);
  if (points_.empty())
    points_.push_back({target_px, target, 0.0, fix->sigma, Vector3d::UnitX(), 0.0});
  target_pixel_ = target_px;
  ref_sigma_ = fix->sigma;
  if (!enough) fix->why += std::string(fix->why.empty() ? "" : "; ") + "next step: " + why;
}

void TargetTracker::Draw(const Frame& cur, const std::string& name, const TargetFix& fix) {
  auto bgr = std::make_shared<cv::Mat>();
  cv::cvtColor(cur.left, *bgr, cv::COLOR_GRAY2BGR);
  auto pt = [](const Vector2d& p) { return cv::Point(static_cast<int>(std::lround(p.x())),
                                                     static_cast<int>(std::lround(p.y()))); };
  for (std::size_t i = 1; i < tracks_.size(); ++i) {
    const FeatureTrack& t = tracks_[i];
    if (!t.matched) continue;
    const cv::Scalar colour = t.inlier ? cv::Scalar(0, 220, 0) : cv::Scalar(0, 0, 230);
    cv::drawMarker(*bgr, pt(t.pixel), colour, cv::MARKER_CROSS, 9, 1);
  }
  if (tracks_.empty()) {
    for (std::size_t i = 1; i < points_.size(); ++i) {
      cv::drawMarker(*bgr, pt(points_[i].pixel), cv::Scalar(0, 220, 0), cv::MARKER_CROSS, 9, 1);
    }
  }
  if (fix.tracked) {
    if (auto p = cur.left_model.Project(fix.target_rover)) {
      cv::circle(*bgr, pt(*p), 12, cv::Scalar(0, 230, 230), 2);
    }
  }
  char text[160];
  std::snprintf(text, sizeof text, "%s: %d/%d features, %d inliers, rms %.1f cm%s", name.c_str(),
                fix.matched, fix.features, fix.inliers, 100.0 * fix.rms,
                fix.tracked ? "" : (std::string(" LOST ") + TargetLossName(fix.loss)).c_str());
  cv::putText(*bgr, text, cv::Point(10, 24), cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 230, 230), 1);
  drawing_ = {name, bgr};
}

}  // namespace rover::apl::rendezvous
