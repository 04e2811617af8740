#include "rover/apl/gestalt/moments.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace rover::apl::gestalt {

Moments& Moments::operator+=(const Moments& o) {
  n += o.n;
  sx += o.sx;
  sy += o.sy;
  sz += o.sz;
  sxx += o.sxx;
  syy += o.syy;
  szz += o.szz;
  sxy += o.sxy;
  sxz += o.sxz;
  syz += o.syz;
  snv += o.snv;
  return *this;
}

Moments& Moments::operator-=(const Moments& o) {
  n -= o.n;
  sx -= o.sx;
  sy -= o.sy;
  sz -= o.sz;
  sxx -= o.sxx;
  syy -= o.syy;
  szz -= o.szz;
  sxy -= o.sxy;
  sxz -= o.sxz;
  syz -= o.syz;
  snv -= o.snv;
  return *this;
}

Eigen::Matrix3d Moments::Covariance() const {
  const double inv = 1.0 / n;
  const double mx = sx * inv, my = sy * inv, mz = sz * inv;
  Eigen::Matrix3d c;
  c(0, 0) = sxx * inv - mx * mx;
  c(1, 1) = syy * inv - my * my;
  c(2, 2) = szz * inv - mz * mz;
  c(0, 1) = c(1, 0) = sxy * inv - mx * my;
  c(0, 2) = c(2, 0) = sxz * inv - mx * mz;
  c(1, 2) = c(2, 1) = syz * inv - my * mz;
  return c;
}

double Moments::StdDevZ() const {
  const double mz = sz / n;
  return std::sqrt(std::max(0.0, szz / n - mz * mz));
}

PlaneFit FitPlane(const Moments& m, double eigen_ratio) {
  PlaneFit f;
  if (m.n < 3.0) return f;
  f.centroid = m.Mean();
  // Centre the covariance on the mean (done inside Covariance) and scale it to O(1) before the
  // closed-form solver, which is accurate relative to the largest eigenvalue.
  const Eigen::Matrix3d c = m.Covariance();
  const double scale = c.cwiseAbs().maxCoeff();
  if (!(scale > 0.0) || !std::isfinite(scale)) return f;
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es;
  es.computeDirect(c / scale);
  if (es.info() != Eigen::Success) return f;
  Eigen::Vector3d ev = es.eigenvalues() * scale;
  for (int k = 0; k < 3; ++k) ev[k] = std::max(0.0, ev[k]);
  Eigen::Vector3d n = es.eigenvectors().col(0);
  if (!n.allFinite() || n.norm() < 0.5) return f;
  n.normalize();
  if (n.z() < 0.0) n = -n;
  f.ok = true;
  f.eigenvalues = ev;
  f.normal = n;
  f.residual = std::sqrt(ev[0]);
  f.tilt = std::acos(std::clamp(n.z(), -1.0, 1.0));
  f.planar = ev[1] >= eigen_ratio * ev[0];
  return f;
}

}  // namespace rover::apl::gestalt
