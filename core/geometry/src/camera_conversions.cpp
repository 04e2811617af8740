// Conversions between camera models, resampling and change of frame (camera_model.hpp).

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "camera_internal.hpp"
#include "rover/base/check.hpp"
#include "rover/geometry/camera_model.hpp"

namespace rover::geometry {
namespace {

std::string PixelText(const Eigen::Vector2d& px) {
  return "(" + std::to_string(px.x()) + ", " + std::to_string(px.y()) + ")";
}

// Distance between each pixel of a grid and `dst`'s projection of `src`'s ray through it.
// Rays are compared as directions (points at infinity), which is exact when both models share
// the projection centre, as all conversions here do.
Result<std::pair<double, double>> FitError(const CameraModel& src, const CameraModel& dst,
                                           const FitOptions& options) {
  const auto grid = internal::PixelGrid(src.width(), src.height(), 2 * options.grid_cols - 1,
                                        2 * options.grid_rows - 1);
  double sum2 = 0.0;
  double max_err = 0.0;
  for (const Eigen::Vector2d& px : grid) {
    const auto ray = src.Unproject(px);
    if (!ray) {
      return InvalidArgument(std::string(KindName(src.kind())) + ": cannot unproject pixel " +
                             PixelText(px));
    }
    const auto back = dst.ProjectDirection(ray->direction);
    if (!back) {
      return InvalidArgument(std::string(KindName(dst.kind())) + ": the ray of pixel " +
                             PixelText(px) + " is outside the converted model's valid range");
    }
    const double err = (*back - px).norm();
    sum2 += err * err;
    max_err = std::max(max_err, err);
  }
  return std::make_pair(std::sqrt(sum2 / static_cast<double>(grid.size())), max_err);
}

// Brown model residuals and Jacobian for parameters q = (fx, fy, cx, cy, k1, k2, k3).
void PinholeResiduals(const Eigen::Matrix<double, 7, 1>& q,
                      const std::vector<Eigen::Vector2d>& normalised,
                      const std::vector<Eigen::Vector2d>& pixels, Eigen::VectorXd* res,
                      Eigen::MatrixXd* jac) {
  const auto n = static_cast<Eigen::Index>(pixels.size());
  res->resize(2 * n);
  jac->setZero(2 * n, 7);
  for (Eigen::Index i = 0; i < n; ++i) {
    const double xn = normalised[static_cast<std::size_t>(i)].x();
    const double yn = normalised[static_cast<std::size_t>(i)].y();
    const double r2 = xn * xn + yn * yn;
    const double r4 = r2 * r2;
    const double r6 = r4 * r2;
    const double s = 1.0 + q(4) * r2 + q(5) * r4 + q(6) * r6;
    const Eigen::Vector2d& px = pixels[static_cast<std::size_t>(i)];
    (*res)(2 * i) = q(0) * xn * s + q(2) - px.x();
    (*res)(2 * i + 1) = q(1) * yn * s + q(3) - px.y();
    jac->row(2 * i) << xn * s, 0.0, 1.0, 0.0, q(0) * xn * r2, q(0) * xn * r4, q(0) * xn * r6;
    jac->row(2 * i + 1) << 0.0, yn * s, 0.0, 1.0, q(1) * yn * r2, q(1) * yn * r4, q(1) * yn * r6;
  }
}

}  // namespace

Status FitOptions::Validate() const {
  if (grid_cols < 4 || grid_rows < 4) {
    return InvalidArgument("FitOptions: grid_cols = " + std::to_string(grid_cols) +
                           ", grid_rows = " + std::to_string(grid_rows) + " must be >= 4");
  }
  if (max_iterations < 1) {
    return InvalidArgument("FitOptions: max_iterations = " + std::to_string(max_iterations) +
                           " must be >= 1");
  }
  return Status::Ok();
}

// --- Scale and Transform -------------------------------------------------------------------

CameraModel Scale(const CameraModel& model, double sx, double sy) {
  ROVER_DEMAND(std::isfinite(sx) && std::isfinite(sy) && sx > 0.0 && sy > 0.0);
  const int width = std::max(1, static_cast<int>(std::lround(model.width() * sx)));
  const int height = std::max(1, static_cast<int>(std::lround(model.height() * sy)));
  CameraModel::Variant scaled = model.variant();
  std::visit(
      [&](auto& m) {
        if constexpr (std::is_same_v<std::decay_t<decltype(m)>, PinholeRadial>) {
          m.fx *= sx;
          m.fy *= sy;
          m.cx = sx * (m.cx + 0.5) - 0.5;
          m.cy = sy * (m.cy + 0.5) - 0.5;
          m.width = width;
          m.height = height;
        } else {
          // x' = sx x + (sx - 1)/2 with x = p.H / p.A.
          m.h = sx * m.h + 0.5 * (sx - 1.0) * m.a;
          m.v = sy * m.v + 0.5 * (sy - 1.0) * m.a;
        }
      },
      scaled);
  return CameraModel(std::move(scaled), width, height);
}

CameraModel Transform(const CameraModel& model, const Eigen::Isometry3d& new_from_old) {
  const Eigen::Matrix3d r = new_from_old.linear();
  CameraModel::Variant moved = model.variant();
  std::visit(
      [&](auto& m) {
        using T = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<T, PinholeRadial>) {
          m.pose = new_from_old * m.pose;
        } else {
          m.c = new_from_old * m.c;
          m.a = r * m.a;
          m.h = r * m.h;
          m.v = r * m.v;
          if constexpr (!std::is_same_v<T, Cahv>) m.o = r * m.o;
        }
      },
      moved);
  return CameraModel(std::move(moved), model.width(), model.height());
}

// --- to pinhole ----------------------------------------------------------------------------

Result<ModelFit<PinholeRadial>> ToPinholeRadial(const CameraModel& model,
                                                const FitOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  if (const auto* p = model.As<PinholeRadial>()) return ModelFit<PinholeRadial>{*p, 0.0, 0.0};

  const internal::LinearPart lin = internal::LinearPartOf(model);
  if (!(lin.theta > 0.0)) {
    return InvalidArgument(std::string(KindName(model.kind())) +
                           ": the model is mirrored (H' x V' points against A); a pinhole "
                           "camera frame cannot represent it");
  }
  PinholeRadial out;
  out.pose.linear() = lin.axes;
  out.pose.translation() = lin.center;
  out.width = model.width();
  out.height = model.height();

  // Initial guess: exact for CAHV with theta = pi/2 and for CAHVOR with O = A.
  Eigen::Matrix<double, 7, 1> q;
  q << lin.fx, lin.fy, lin.cx, lin.cy, 0.0, 0.0, 0.0;
  const Eigen::Vector3d* r = nullptr;
  if (const auto* m = model.As<Cahvor>()) r = &m->r;
  if (const auto* m = model.As<Cahvore>()) r = &m->r;
  if (r != nullptr) {
    const double g = 1.0 + r->x();
    q(0) *= g;
    q(1) *= g;
    q(4) = r->y() / g;
    q(5) = r->z() / g;
  }

  // Samples: normalised camera coordinates of each grid pixel's ray.
  const auto grid =
      internal::PixelGrid(model.width(), model.height(), options.grid_cols, options.grid_rows);
  std::vector<Eigen::Vector2d> normalised;
  normalised.reserve(grid.size());
  for (const Eigen::Vector2d& px : grid) {
    const auto ray = model.Unproject(px);
    if (!ray) {
      return InvalidArgument(std::string(KindName(model.kind())) + ": cannot unproject pixel " +
                             PixelText(px));
    }
    const Eigen::Vector3d dc = lin.axes.transpose() * ray->direction;
    if (!(dc.z() > 1e-6)) {
      return InvalidArgument(std::string(KindName(model.kind())) + ": the ray of pixel " +
                             PixelText(px) +
                             " is 90 deg or more off the axis; a pinhole cannot represent it");
    }
    normalised.emplace_back(dc.x() / dc.z(), dc.y() / dc.z());
  }

  // Gauss-Newton (the problem is nearly linear; it converges in a few steps). A CAHV model has
  // no distortion: only fx, fy, cx, cy are fitted and k stays exactly 0.
  const Eigen::Index n_params = model.kind() == CameraModel::Kind::kCahv ? 4 : 7;
  Eigen::VectorXd res;
  Eigen::MatrixXd jac;
  for (int it = 0; it < options.max_iterations; ++it) {
    PinholeResiduals(q, normalised, grid, &res, &jac);
    const Eigen::VectorXd step = jac.leftCols(n_params).colPivHouseholderQr().solve(-res);
    if (!step.allFinite()) break;
    q.head(n_params) += step;
    if (step.head<4>().cwiseAbs().maxCoeff() < 1e-12 * q.head<2>().cwiseAbs().maxCoeff() &&
        (n_params == 4 || step.tail<3>().cwiseAbs().maxCoeff() < 1e-14)) {
      break;
    }
  }
  out.fx = q(0);
  out.fy = q(1);
  out.cx = q(2);
  out.cy = q(3);
  out.k1 = q(4);
  out.k2 = q(5);
  out.k3 = q(6);

  auto pinhole = CameraModel::Create(out);
  if (!pinhole.ok()) return pinhole.status().WithPrefix("ToPinholeRadial: fit failed");
  auto err = FitError(model, *pinhole, options);
  if (!err.ok()) return err.status().WithPrefix("ToPinholeRadial");
  return ModelFit<PinholeRadial>{out, err->first, err->second};
}

// --- from pinhole --------------------------------------------------------------------------

namespace {

Cahv LinearCahv(const PinholeRadial& p) {
  const Eigen::Matrix3d r = p.pose.linear();
  Cahv m;
  m.c = p.pose.translation();
  m.a = r.col(2);
  m.h = p.fx * r.col(0) + p.cx * m.a;
  m.v = p.fy * r.col(1) + p.cy * m.a;
  return m;
}

}  // namespace

Result<Cahv> ToCahv(const PinholeRadial& pinhole) {
  if (pinhole.k1 != 0.0 || pinhole.k2 != 0.0 || pinhole.k3 != 0.0) {
    return InvalidArgument(
        "ToCahv: the pinhole has radial distortion (k1 = " + std::to_string(pinhole.k1) +
        ", k2 = " + std::to_string(pinhole.k2) + ", k3 = " + std::to_string(pinhole.k3) +
        "); a CAHV model has none (use ToCahvor)");
  }
  return LinearCahv(pinhole);
}

Result<ModelFit<Cahvor>> ToCahvor(const PinholeRadial& pinhole, const FitOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  auto source = CameraModel::Create(pinhole);
  if (!source.ok()) return source.status().WithPrefix("ToCahvor");
  const Cahv lin = LinearCahv(pinhole);
  Cahvor out{lin.c, lin.a, lin.h, lin.v, lin.a, Eigen::Vector3d(0.0, pinhole.k1, pinhole.k2)};
  if (pinhole.k3 != 0.0) {
    // CAHVOR with O = A: u = cx + fx xn (1 + r0 + r1 r^2 + r2 r^4), linear in R.
    const auto grid =
        internal::PixelGrid(pinhole.width, pinhole.height, options.grid_cols, options.grid_rows);
    Eigen::MatrixXd a(2 * grid.size(), 3);
    Eigen::VectorXd b(2 * grid.size());
    Eigen::Index row = 0;
    for (const Eigen::Vector2d& px : grid) {
      const auto ray = source->Unproject(px);
      if (!ray) {
        return InvalidArgument("ToCahvor: cannot unproject pixel " + PixelText(px) +
                               " of the pinhole model");
      }
      const Eigen::Vector3d dc = pinhole.pose.linear().transpose() * ray->direction;
      const double xn = dc.x() / dc.z();
      const double yn = dc.y() / dc.z();
      const double r2 = xn * xn + yn * yn;
      a.row(row) << pinhole.fx * xn, pinhole.fx * xn * r2, pinhole.fx * xn * r2 * r2;
      b(row++) = px.x() - pinhole.cx - pinhole.fx * xn;
      a.row(row) << pinhole.fy * yn, pinhole.fy * yn * r2, pinhole.fy * yn * r2 * r2;
      b(row++) = px.y() - pinhole.cy - pinhole.fy * yn;
    }
    out.r = a.colPivHouseholderQr().solve(b);
  }
  auto cahvor = CameraModel::Create(out, pinhole.width, pinhole.height);
  if (!cahvor.ok()) return cahvor.status().WithPrefix("ToCahvor: fit failed");
  auto err = FitError(*source, *cahvor, options);
  if (!err.ok()) return err.status().WithPrefix("ToCahvor");
  return ModelFit<Cahvor>{out, err->first, err->second};
}

}  // namespace rover::geometry
