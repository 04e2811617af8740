#include "rover/dl/vo/rigid_motion.hpp"

#include <Eigen/Dense>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "rover/base/check.hpp"

namespace rover::dl::vo {

double RotationAngle(const Eigen::Matrix3d& r) {
  const double c = std::clamp((r.trace() - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(c);
}

namespace {

Eigen::Matrix3d ResidualCovariance(const Correspondence& c, const Eigen::Matrix3d& r) {
  return c.cov_from + r * c.cov_to * r.transpose();
}

}  // namespace

double MahalanobisSq(const Correspondence& c, const Eigen::Isometry3d& t) {
  const Eigen::Vector3d e = c.from - t.linear() * c.to - t.translation();
  const Eigen::Matrix3d s = ResidualCovariance(c, t.linear());
  const Eigen::LDLT<Eigen::Matrix3d> ldlt(s);
  if (ldlt.info() != Eigen::Success) return std::numeric_limits<double>::infinity();
  return e.dot(ldlt.solve(e));
}

bool FitRigidClosedForm(const std::vector<Correspondence>& points, const std::vector<int>& indices,
                        const std::vector<double>& weights, Eigen::Isometry3d* motion) {
  ROVER_DEMAND(motion != nullptr);
  ROVER_DEMAND(weights.empty() || weights.size() == indices.size());
  if (indices.size() < 3) return false;
  double wsum = 0.0;
  Eigen::Vector3d mf = Eigen::Vector3d::Zero(), mt = Eigen::Vector3d::Zero();
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const double w = weights.empty() ? 1.0 : weights[k];
    const Correspondence& c = points[static_cast<std::size_t>(indices[k])];
    mf += w * c.from;
    mt += w * c.to;
    wsum += w;
  }
  if (!(wsum > 0.0)) return false;
  mf /= wsum;
  mt /= wsum;
  Eigen::Matrix3d h = Eigen::Matrix3d::Zero();
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const double w = weights.empty() ? 1.0 : weights[k];
    const Correspondence& c = points[static_cast<std::size_t>(indices[k])];
    h += w * (c.to - mt) * (c.from - mf).transpose();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d sv = svd.singularValues();
  // Collinear (or coincident) points leave a rotation about their line undetermined.
  if (!(sv(1) > 1e-9 * std::max(sv(0), 1e-300))) return false;
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  if ((svd.matrixV() * svd.matrixU().transpose()).determinant() < 0.0) d(2, 2) = -1.0;
  const Eigen::Matrix3d r = svd.matrixV() * d * svd.matrixU().transpose();
  motion->setIdentity();
  motion->linear() = r;
  motion->translation() = mf - r * mt;
  return motion->matrix().allFinite();
}

Status RansacOptions::Validate() const {
  if (max_iterations < 1) return InvalidArgument("ransac.max_iterations must be >= 1");
  if (max_sample_failures < 0) return InvalidArgument("ransac.max_sample_failures must be >= 0");
  if (!std::isfinite(inlier_chi2) || inlier_chi2 <= 0.0) {
    return InvalidArgument("ransac.inlier_chi2 must be finite and > 0");
  }
  if (!std::isfinite(rigidity_sigmas) || rigidity_sigmas <= 0.0) {
    return InvalidArgument("ransac.rigidity_sigmas must be finite and > 0");
  }
  if (!std::isfinite(confidence) || confidence <= 0.0 || confidence >= 1.0) {
    return InvalidArgument("ransac.confidence must be in (0, 1)");
  }
  return Status::Ok();
}

namespace {

// MER-style rigidity check on a sample: the distance between two features must be the same at
// both times, within k sigma of its uncertainty along the joining direction.
bool RigidPair(const Correspondence& a, const Correspondence& b, double k) {
  const Eigen::Vector3d df = a.from - b.from;
  const Eigen::Vector3d dt = a.to - b.to;
  const double lf = df.norm(), lt = dt.norm();
  if (lf < 1e-9 || lt < 1e-9) return false;
  const Eigen::Vector3d uf = df / lf, ut = dt / lt;
  const double var = uf.dot((a.cov_from + b.cov_from) * uf) + ut.dot((a.cov_to + b.cov_to) * ut);
  return std::abs(lf - lt) <= k * std::sqrt(var);
}

void ScoreHypothesis(const std::vector<Correspondence>& points, const Eigen::Isometry3d& m,
                     double gate, double* cost, std::vector<int>* inliers) {
  *cost = 0.0;
  inliers->clear();
  for (std::size_t i = 0; i < points.size(); ++i) {
    const double d2 = MahalanobisSq(points[i], m);
    if (d2 < gate) {
      *cost += d2;
      inliers->push_back(static_cast<int>(i));
    } else {
      *cost += gate;
    }
  }
}

std::vector<double> TraceWeights(const std::vector<Correspondence>& points,
                                 const std::vector<int>& idx) {
  std::vector<double> w;
  w.reserve(idx.size());
  for (int i : idx) {
    const Correspondence& c = points[static_cast<std::size_t>(i)];
    w.push_back(1.0 / std::max(1e-12, c.cov_from.trace() + c.cov_to.trace()));
  }
  return w;
}

}  // namespace

namespace {

// Local optimisation of a hypothesis (LO-RANSAC): Gauss-Newton maximum likelihood on its
// inliers, re-selection of the inliers, repeated while the truncated cost falls. Minimal 3-point
// fits of stereo points (whose errors are long ellipsoids along the viewing rays) explain only
// part of the true inliers; this recovers the rest.
void LocallyOptimise(const std::vector<Correspondence>& points, double gate,
                     Eigen::Isometry3d* motion, std::vector<int>* inliers, double* cost) {
  RefineOptions ro;
  ro.max_iterations = 6;
  for (int round = 0; round < 6 && inliers->size() >= 3; ++round) {
    const RefineResult r = RefineMaximumLikelihood(points, *inliers, *motion, ro);
    if (!r.motion.matrix().allFinite() || r.covariance.isZero()) break;
    double c = 0.0;
    std::vector<int> in;
    ScoreHypothesis(points, r.motion, gate, &c, &in);
    if (!(c < *cost - 1e-9) || in.size() < 3) break;
    *cost = c;
    *motion = r.motion;
    *inliers = std::move(in);
  }
}

}  // namespace

RansacResult RansacRigidMotion(const std::vector<Correspondence>& points,
                               const RansacOptions& options) {
  ROVER_DEMAND(options.Validate().ok());
  RansacResult result;
  const int n = static_cast<int>(points.size());
  if (n < 3) return result;
  std::mt19937_64 rng(options.seed);
  std::uniform_int_distribution<int> pick(0, n - 1);
  double best_cost = std::numeric_limits<double>::infinity();
  std::vector<int> inliers;
  long needed = options.max_iterations;
  while (result.iterations < std::min<long>(needed, options.max_iterations)) {
    const int a = pick(rng);
    int b = pick(rng);
    int c = pick(rng);
    const auto& pa = points[static_cast<std::size_t>(a)];
    const auto& pb = points[static_cast<std::size_t>(b)];
    const auto& pc = points[static_cast<std::size_t>(c)];
    Eigen::Isometry3d m;
    const bool usable = a != b && b != c && a != c && RigidPair(pa, pb, options.rigidity_sigmas) &&
                        RigidPair(pb, pc, options.rigidity_sigmas) &&
                        RigidPair(pa, pc, options.rigidity_sigmas) &&
                        FitRigidClosedForm(points, {a, b, c}, {}, &m);
    if (!usable) {
      if (++result.sample_failures > options.max_sample_failures) break;
      continue;
    }
    ++result.iterations;
    double cost = 0.0;
    ScoreHypothesis(points, m, options.inlier_chi2, &cost, &inliers);
    if (cost < best_cost && inliers.size() >= 3) {
      LocallyOptimise(points, options.inlier_chi2, &m, &inliers, &cost);
      best_cost = cost;
      result.motion = m;
      result.inliers = inliers;
      // Adaptive number of hypotheses for the requested confidence.
      const double w = static_cast<double>(inliers.size()) / n;
      const double p_good = w * w * w;
      if (p_good >= 1.0 - 1e-12) {
        needed = result.iterations;
      } else {
        needed = static_cast<long>(
            std::ceil(std::log(1.0 - options.confidence) / std::log(1.0 - p_good)));
      }
    }
  }
  if (result.inliers.size() < 3) return result;
  // Weighted closed-form re-fit on the consensus set, kept if it lowers the cost.
  Eigen::Isometry3d m;
  if (FitRigidClosedForm(points, result.inliers, TraceWeights(points, result.inliers), &m)) {
    double cost = 0.0;
    ScoreHypothesis(points, m, options.inlier_chi2, &cost, &inliers);
    if (cost < best_cost && inliers.size() >= 3) {
      LocallyOptimise(points, options.inlier_chi2, &m, &inliers, &cost);
      result.motion = m;
      result.inliers = inliers;
    }
  }
  result.ok = true;
  return result;
}

Status RefineOptions::Validate() const {
  if (max_iterations < 1) return InvalidArgument("refine.max_iterations must be >= 1");
  if (!std::isfinite(translation_tolerance) || translation_tolerance <= 0.0 ||
      !std::isfinite(rotation_tolerance) || rotation_tolerance <= 0.0) {
    return InvalidArgument("refine tolerances must be finite and > 0");
  }
  return Status::Ok();
}

RefineResult RefineMaximumLikelihood(const std::vector<Correspondence>& points,
                                     const std::vector<int>& indices,
                                     const Eigen::Isometry3d& initial,
                                     const RefineOptions& options) {
  ROVER_DEMAND(options.Validate().ok());
  RefineResult out;
  out.motion = initial;
  if (indices.size() < 3) return out;
  Eigen::Matrix3d r = initial.linear();
  Eigen::Vector3d t = initial.translation();
  Matrix6d h;
  auto build = [&](Matrix6d* hess, Vector6d* grad, double* cost) {
    hess->setZero();
    grad->setZero();
    *cost = 0.0;
    for (int i : indices) {
      const Correspondence& c = points[static_cast<std::size_t>(i)];
      const Eigen::Vector3d rx = r * c.to;
      const Eigen::Vector3d e = c.from - rx - t;
      const Eigen::Matrix3d w = ResidualCovariance(c, r).inverse();
      Eigen::Matrix<double, 3, 6> j;
      j.leftCols<3>() = -Eigen::Matrix3d::Identity();
      j.rightCols<3>() = Skew(rx);
      const Eigen::Matrix<double, 6, 3> jtw = j.transpose() * w;
      *hess += jtw * j;
      *grad += jtw * e;
      *cost += e.dot(w * e);
    }
  };
  Vector6d g;
  double cost = 0.0;
  for (out.iterations = 1; out.iterations <= options.max_iterations; ++out.iterations) {
    build(&h, &g, &cost);
    const Eigen::LDLT<Matrix6d> ldlt(h);
    if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) return out;
    const Vector6d step = -ldlt.solve(g);
    if (!step.allFinite()) return out;
    t += step.head<3>();
    r = ExpSo3(step.tail<3>()) * r;
    if (step.head<3>().norm() < options.translation_tolerance &&
        step.tail<3>().norm() < options.rotation_tolerance) {
      out.converged = true;
      break;
    }
  }
  if (!out.converged) out.iterations = options.max_iterations;
  // Re-orthonormalise and evaluate the Hessian at the final estimate.
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(r, Eigen::ComputeFullU | Eigen::ComputeFullV);
  r = svd.matrixU() * svd.matrixV().transpose();
  build(&h, &g, &cost);
  const Eigen::FullPivLU<Matrix6d> lu(h);
  if (!lu.isInvertible() || lu.rcond() < 1e-14) {
    out.converged = false;
    return out;
  }
  out.motion.setIdentity();
  out.motion.linear() = r;
  out.motion.translation() = t;
  Matrix6d cov = lu.inverse();
  out.covariance = 0.5 * (cov + cov.transpose());
  out.cost = cost;
  return out;
}

Vector6d MotionError(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth) {
  Vector6d d;
  d.head<3>() = truth.translation() - estimate.translation();
  d.tail<3>() = LogSo3(truth.linear() * estimate.linear().transpose());
  return d;
}

void ChangeMotionFrame(const Eigen::Isometry3d& delta_c, const Matrix6d& cov_c,
                       const Eigen::Isometry3d& t_b_c, Eigen::Isometry3d* delta_b,
                       Matrix6d* cov_b) {
  ROVER_DEMAND(delta_b != nullptr && cov_b != nullptr);
  const Eigen::Isometry3d d = t_b_c * delta_c * t_b_c.inverse();
  const Eigen::Matrix3d rbc = t_b_c.linear();
  Matrix6d j = Matrix6d::Zero();
  j.topLeftCorner<3, 3>() = rbc;
  j.topRightCorner<3, 3>() = Skew(d.linear() * t_b_c.translation()) * rbc;
  j.bottomRightCorner<3, 3>() = rbc;
  *delta_b = d;
  *cov_b = j * cov_c * j.transpose();
}

}  // namespace rover::dl::vo
