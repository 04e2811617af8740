#include "view_planner.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "rover/base/check.hpp"

namespace rover::sim::render::internal {
namespace {

using geometry::CameraModel;

void AppendVec(std::string* s, const Eigen::Vector3d& v) {
  // Components below 1e-9 of the vector's size are rounding noise of Transform (print 0).
  const double eps = 1e-9 * std::max(1.0, v.norm());
  auto clean = [eps](double c) { return std::abs(c) < eps ? 0.0 : c + 0.0; };
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.7g,%.7g,%.7g;", clean(v.x()), clean(v.y()), clean(v.z()));
  *s += buf;
}
void AppendNum(std::string* s, double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.7g;", v + 0.0);
  *s += buf;
}

// Cube faces: view axes (columns x, y, z) in the camera frame, each right-handed.
std::array<Eigen::Matrix3d, 6> CubeFaces() {
  std::array<Eigen::Matrix3d, 6> f;
  auto m = [](Eigen::Vector3d x, Eigen::Vector3d y, Eigen::Vector3d z) {
    Eigen::Matrix3d r;
    r.col(0) = x;
    r.col(1) = y;
    r.col(2) = z;
    return r;
  };
  using V = Eigen::Vector3d;
  f[0] = m(V(1, 0, 0), V(0, 1, 0), V(0, 0, 1));    // +z
  f[1] = m(V(0, 0, -1), V(0, 1, 0), V(1, 0, 0));   // +x
  f[2] = m(V(0, 0, 1), V(0, 1, 0), V(-1, 0, 0));   // -x
  f[3] = m(V(1, 0, 0), V(0, 0, -1), V(0, 1, 0));   // +y
  f[4] = m(V(1, 0, 0), V(0, 0, 1), V(0, -1, 0));   // -y
  f[5] = m(V(-1, 0, 0), V(0, 1, 0), V(0, 0, -1));  // -z
  return f;
}

int FaceOf(const Eigen::Vector3d& d) {
  const double ax = std::abs(d.x()), ay = std::abs(d.y()), az = std::abs(d.z());
  if (az >= ax && az >= ay) return d.z() >= 0 ? 0 : 5;
  if (ax >= ay) return d.x() >= 0 ? 1 : 2;
  return d.y() >= 0 ? 3 : 4;
}

}  // namespace

CameraFrame CanonicalFrame(const CameraModel& model) {
  CameraFrame f;
  f.center = model.Center();
  auto from_jpl = [&](const Eigen::Vector3d& a, const Eigen::Vector3d& h) {
    const Eigen::Vector3d z = a.normalized();
    const Eigen::Vector3d x = (h - z.dot(h) * z).normalized();
    f.ref_from_cam.col(0) = x;
    f.ref_from_cam.col(1) = z.cross(x);
    f.ref_from_cam.col(2) = z;
  };
  if (const auto* m = model.As<geometry::Cahv>()) {
    from_jpl(m->a, m->h);
  } else if (const auto* m1 = model.As<geometry::Cahvor>()) {
    from_jpl(m1->a, m1->h);
  } else if (const auto* m2 = model.As<geometry::Cahvore>()) {
    from_jpl(m2->a, m2->h);
  } else if (const auto* p = model.As<geometry::PinholeRadial>()) {
    f.ref_from_cam = p->pose.linear();
  }
  return f;
}

CameraModel CanonicalModel(const CameraModel& model) {
  const CameraFrame f = CanonicalFrame(model);
  Eigen::Isometry3d cam_from_ref = Eigen::Isometry3d::Identity();
  cam_from_ref.linear() = f.ref_from_cam.transpose();
  cam_from_ref.translation() = -(f.ref_from_cam.transpose() * f.center);
  return geometry::Transform(model, cam_from_ref);
}

std::string WarpKey(const CameraModel& model) {
  const CameraModel c = CanonicalModel(model);
  std::string key(geometry::KindName(c.kind()));
  key += ":" + std::to_string(c.width()) + "x" + std::to_string(c.height()) + ":";
  if (const auto* m = c.As<geometry::Cahv>()) {
    AppendVec(&key, m->a); AppendVec(&key, m->h); AppendVec(&key, m->v);
  } else if (const auto* m1 = c.As<geometry::Cahvor>()) {
    AppendVec(&key, m1->a); AppendVec(&key, m1->h); AppendVec(&key, m1->v);
    AppendVec(&key, m1->o); AppendVec(&key, m1->r);
  } else if (const auto* m2 = c.As<geometry::Cahvore>()) {
    AppendVec(&key, m2->a); AppendVec(&key, m2->h); AppendVec(&key, m2->v);
    AppendVec(&key, m2->o); AppendVec(&key, m2->r); AppendVec(&key, m2->e);
    AppendNum(&key, static_cast<double>(m2->type)); AppendNum(&key, m2->parameter);
  } else if (const auto* p = c.As<geometry::PinholeRadial>()) {
    for (double v : {p->fx, p->fy, p->cx, p->cy, p->k1, p->k2, p->k3}) AppendNum(&key, v);
  }
  return key;
}

bool VirtualView::Project(const Eigen::Vector3d& d_cam, double* u, double* v) const {
  const Eigen::Vector3d d = cam_from_view.transpose() * d_cam;
  if (d.z() <= 1e-12) return false;
  *u = f * d.x() / d.z() + cx;
  *v = f * d.y() / d.z() + cy;
  return true;
}

Result<WarpPlan> PlanWarp(const CameraModel& model, const PlanOptions& options) {
  ROVER_DEMAND(options.oversample > 0.0 && options.margin >= 1 && options.max_view_size >= 16);
  const CameraModel canon = CanonicalModel(model);
  const int w = canon.width(), h = canon.height();
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  std::vector<Eigen::Vector3d> dirs(n, Eigen::Vector3d::Zero());
  std::vector<std::uint8_t> valid(n, 0);
  double min_cos = 1.0;
  std::size_t valid_count = 0;
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const auto ray = canon.Unproject(Eigen::Vector2d(x, y));
      if (!ray) continue;
      const std::size_t k = static_cast<std::size_t>(y) * w + x;
      dirs[k] = ray->direction.normalized();
      valid[k] = 1;
      ++valid_count;
      min_cos = std::min(min_cos, ray->direction.normalized().z());
    }
  }
  if (valid_count == 0) {
    return InvalidArgument("camera model (" + std::string(geometry::KindName(model.kind())) +
                           ") has no valid ray over its image");
  }
  const bool single =
      min_cos > std::cos(options.single_view_max_angle_deg * std::numbers::pi / 180.0);
  const auto faces = CubeFaces();
  std::vector<std::int8_t> face(n, -1);
  for (std::size_t k = 0; k < n; ++k) {
    if (valid[k]) face[k] = single ? 0 : static_cast<std::int8_t>(FaceOf(dirs[k]));
  }

  WarpPlan plan;
  plan.key = WarpKey(model);
  plan.out_width = w;
  plan.out_height = h;
  std::array<int, 6> view_of_face;
  view_of_face.fill(-1);
  for (int fi = 0; fi < 6; ++fi) {
    const Eigen::Matrix3d axes = single ? Eigen::Matrix3d::Identity() : faces[static_cast<std::size_t>(fi)];
    const Eigen::Matrix3d axes_t = axes.transpose();
    double umin = 1e30, umax = -1e30, vmin = 1e30, vmax = -1e30, density = 0.0;
    bool any = false;
    auto tan_of = [&](std::size_t k, double* tu, double* tv) {
      const Eigen::Vector3d d = axes_t * dirs[k];
      *tu = d.x() / d.z();
      *tv = d.y() / d.z();
    };
    for (int y = 0; y < h; ++y) {
      for (int x = 0; x < w; ++x) {
        const std::size_t k = static_cast<std::size_t>(y) * w + x;
        if (face[k] != fi) continue;
        any = true;
        double tu, tv;
        tan_of(k, &tu, &tv);
        umin = std::min(umin, tu);
        umax = std::max(umax, tu);
        vmin = std::min(vmin, tv);
        vmax = std::max(vmax, tv);
        for (int dir = 0; dir < 2; ++dir) {
          const int x2 = x + (dir == 0), y2 = y + (dir == 1);
          if (x2 >= w || y2 >= h) continue;
          const std::size_t k2 = static_cast<std::size_t>(y2) * w + x2;
          if (face[k2] != fi) continue;
          double tu2, tv2;
          tan_of(k2, &tu2, &tv2);
          const double step = std::hypot(tu2 - tu, tv2 - tv);
          if (step > 1e-9) density = std::max(density, 1.0 / step);
        }
      }
    }
    if (!any) continue;
    if (density <= 0.0) density = 1.0;
    VirtualView view;
    view.cam_from_view = axes;
    view.f = options.oversample * density;
    const double span = std::max(umax - umin, vmax - vmin);
    const double usable = options.max_view_size - 1 - 2.0 * options.margin;
    if (view.f * span > usable) {
      view.f = usable / span;
      plan.min_density_ratio = std::min(plan.min_density_ratio, view.f / density);
    }
    view.cx = options.margin - view.f * umin;
    view.cy = options.margin - view.f * vmin;
    view.width = static_cast<int>(std::ceil(view.f * (umax - umin))) + 1 + 2 * options.margin;
    view.height = static_cast<int>(std::ceil(view.f * (vmax - vmin))) + 1 + 2 * options.margin;
    view.atlas_y = plan.atlas_height;
    plan.atlas_height += view.height;
    plan.atlas_width = std::max(plan.atlas_width, view.width);
    view_of_face[static_cast<std::size_t>(fi)] = static_cast<int>(plan.views.size());
    plan.views.push_back(view);
    if (single) break;
  }
  if (plan.atlas_width > options.max_atlas_size || plan.atlas_height > options.max_atlas_size) {
    return InvalidArgument("camera model needs a " + std::to_string(plan.atlas_width) + " x " +
                           std::to_string(plan.atlas_height) +
                           " px render atlas, more than the GL limit " +
                           std::to_string(options.max_atlas_size) + " (lower oversample)");
  }
  plan.map_x = cv::Mat(h, w, CV_32FC1, cv::Scalar(-1.0F));
  plan.map_y = cv::Mat(h, w, CV_32FC1, cv::Scalar(-1.0F));
  for (int y = 0; y < h; ++y) {
    float* mx = plan.map_x.ptr<float>(y);
    float* my = plan.map_y.ptr<float>(y);
    for (int x = 0; x < w; ++x) {
      const std::size_t k = static_cast<std::size_t>(y) * w + x;
      if (face[k] < 0) continue;
      const VirtualView& v = plan.views[static_cast<std::size_t>(view_of_face[static_cast<std::size_t>(face[k])])];
      double u, vv;
      if (!v.Project(dirs[k], &u, &vv)) continue;
      mx[x] = static_cast<float>(u);
      my[x] = static_cast<float>(vv + v.atlas_y);
    }
  }
  cv::convertMaps(plan.map_x, plan.map_y, plan.map1, plan.map2, CV_16SC2, false);
  return plan;
}

}  // namespace rover::sim::render::internal
