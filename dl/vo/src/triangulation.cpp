#include "rover/dl/vo/triangulation.hpp"

#include <cmath>

namespace rover::dl::vo {

std::optional<Eigen::Vector3d> RayMidpoint(const Eigen::Vector3d& c1, const Eigen::Vector3d& r1,
                                           const Eigen::Vector3d& c2, const Eigen::Vector3d& r2,
                                           double* gap) {
  const Eigen::Vector3d w = c1 - c2;
  const double a = r1.dot(r1), b = r1.dot(r2), c = r2.dot(r2), d = r1.dot(w), e = r2.dot(w);
  const double denom = a * c - b * b;
  if (!(denom > 1e-12 * a * c)) return std::nullopt;  // parallel rays
  const double s = (b * e - c * d) / denom;
  const double t = (a * e - b * d) / denom;
  if (!(s > 0.0 && t > 0.0)) return std::nullopt;  // diverging or behind a camera
  const Eigen::Vector3d p1 = c1 + s * r1;
  const Eigen::Vector3d p2 = c2 + t * r2;
  if (gap != nullptr) *gap = (p1 - p2).norm();
  return 0.5 * (p1 + p2);
}

std::optional<StereoPoint> TriangulateStereo(const StereoCamera& camera,
                                             const Eigen::Vector2d& left_px,
                                             const Eigen::Vector2d& right_px, double pixel_sigma) {
  if (!(left_px.x() - right_px.x() > 0.0)) return std::nullopt;
  const Eigen::Vector3d cl = Eigen::Vector3d::Zero();
  const Eigen::Vector3d cr = camera.RightCentre();
  auto solve = [&](const Eigen::Vector4d& m, double* gap) {
    return RayMidpoint(cl, camera.Ray(m.head<2>()), cr, camera.Ray(m.tail<2>()), gap);
  };
  Eigen::Vector4d m;
  m << left_px, right_px;
  StereoPoint out;
  const auto x = solve(m, &out.ray_gap);
  if (!x) return std::nullopt;
  out.position = *x;
  // Central differences; the map is smooth (a rational function of the pixels), so a step of
  // 1e-3 px leaves a relative error of ~1e-6 in J.
  constexpr double kStep = 1e-3;
  Eigen::Matrix<double, 3, 4> jac;
  for (int k = 0; k < 4; ++k) {
    Eigen::Vector4d mp = m, mm = m;
    mp(k) += kStep;
    mm(k) -= kStep;
    const auto xp = solve(mp, nullptr);
    const auto xm = solve(mm, nullptr);
    if (!xp || !xm) return std::nullopt;
    jac.col(k) = (*xp - *xm) / (2.0 * kStep);
  }
  out.covariance = pixel_sigma * pixel_sigma * jac * jac.transpose();
  if (!out.position.allFinite() || !out.covariance.allFinite()) return std::nullopt;
  return out;
}

}  // namespace rover::dl::vo
