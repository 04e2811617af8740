#pragma once
/// @file
/// Rigid motion from 3D-3D correspondences: closed-form least squares (Arun 1987 / Umeyama
/// 1991), RANSAC around it, and maximum-likelihood refinement weighted by each point's 3D
/// covariance (Matthies 1989, as in MER visual odometry).
///
/// Convention. A motion is T = (R, t) = T_from_to: the pose of the frame at t_to expressed in the
/// frame at t_from, so a point seen at both times satisfies
///   x_from = R x_to + t.
/// Uncertainty is expressed by a 6-vector delta = [dt (3, m); dtheta (3, rad)] perturbing the
/// estimate in the t_from frame ("left" perturbation, translation and rotation separate):
///   R_true = Exp(dtheta) R,   t_true = t + dt,
/// and a 6x6 covariance of delta in that order. For small angles dtheta = (droll, dpitch,
/// dyaw) about the from-frame axes, the layout of dl/relative_pose.covariance. (The same error
/// in the t_to frame is blockdiag(R^T, R^T) delta.)
///
/// Maximum likelihood. With residuals e_i = x_from_i - R x_to_i - t and their covariances
/// S_i = Sigma_from_i + R Sigma_to_i R^T, minimise sum e_i^T S_i^-1 e_i by Gauss-Newton on delta:
///   J_i = de_i/d(delta) = [-I, [R x_to_i]_x],  H = sum J^T S^-1 J,  delta = -H^-1 sum J^T S^-1 e.
/// At convergence Cov(delta) = H^-1.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::dl::vo {

using Matrix6d = Eigen::Matrix<double, 6, 6>;
using Vector6d = Eigen::Matrix<double, 6, 1>;

// SO(3) helpers of core/geometry (rover/geometry/transforms.hpp).
using geometry::ExpSo3;
using geometry::LogSo3;
using geometry::Skew;
/// Rotation angle of a rotation matrix [rad].
double RotationAngle(const Eigen::Matrix3d& r);

/// One feature seen at both times, with its triangulation covariances.
struct Correspondence {
  Eigen::Vector3d from = Eigen::Vector3d::Zero();  ///< [m] in the frame at t_from
  Eigen::Matrix3d cov_from = Eigen::Matrix3d::Identity();
  Eigen::Vector3d to = Eigen::Vector3d::Zero();  ///< [m] in the frame at t_to
  Eigen::Matrix3d cov_to = Eigen::Matrix3d::Identity();
};

/// Squared Mahalanobis distance e^T S^-1 e of one correspondence under motion `t`.
double MahalanobisSq(const Correspondence& c, const Eigen::Isometry3d& t);

/// Closed-form weighted least-squares rigid motion minimising sum w_i |from_i - R to_i - t|^2
/// (SVD of the cross-covariance, reflection corrected). `weights` may be empty (all 1).
/// Returns false for fewer than 3 points or a degenerate (collinear) configuration.
bool FitRigidClosedForm(const std::vector<Correspondence>& points, const std::vector<int>& indices,
                        const std::vector<double>& weights, Eigen::Isometry3d* motion);

struct RansacOptions {
  int max_iterations = 300;        ///< hypotheses scored at most
  int max_sample_failures = 1000;  ///< degenerate or non-rigid samples tolerated
  double inlier_chi2 = 16.27;      ///< Mahalanobis^2 gate (chi^2, 3 dof, 0.999)
  double rigidity_sigmas = 4.0;    ///< sample check: pairwise distances kept within k sigma
  double confidence = 0.999;       ///< adaptive stop once this sure of an all-inlier sample
  std::uint64_t seed = 42;

  Status Validate() const;
};

struct RansacResult {
  bool ok = false;
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  std::vector<int> inliers;  ///< indices into the correspondences
  int iterations = 0;        ///< hypotheses scored
  int sample_failures = 0;   ///< samples rejected before scoring
};

/// RANSAC over minimal 3-point closed-form fits, scored by truncated Mahalanobis cost (MSAC).
/// Each new best hypothesis is locally optimised (LO-RANSAC: a few Gauss-Newton ML steps on its
/// inliers and inlier re-selection while the cost falls), since a minimal fit of stereo points
/// with long depth uncertainties explains only part of the true inliers. Samples whose pairwise
/// distances differ beyond rigidity_sigmas are skipped before fitting (MER's rigidity check).
/// Deterministic for a given seed.
RansacResult RansacRigidMotion(const std::vector<Correspondence>& points,
                               const RansacOptions& options);

struct RefineOptions {
  int max_iterations = 20;
  double translation_tolerance = 1e-7;  ///< [m] converged when the step is below both
  double rotation_tolerance = 1e-9;     ///< [rad]

  Status Validate() const;
};

struct RefineResult {
  bool converged = false;
  Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
  Matrix6d covariance = Matrix6d::Zero();  ///< H^-1 over [dt; dtheta]
  int iterations = 0;
  double cost = 0.0;  ///< sum of squared Mahalanobis residuals
};

/// Gauss-Newton maximum-likelihood refinement over the correspondences `indices`.
RefineResult RefineMaximumLikelihood(const std::vector<Correspondence>& points,
                                     const std::vector<int>& indices,
                                     const Eigen::Isometry3d& initial,
                                     const RefineOptions& options);

/// The error delta (same convention as above) that takes `estimate` to `truth`:
/// dt = t_truth - t_est, dtheta = Log(R_truth R_est^T).
Vector6d MotionError(const Eigen::Isometry3d& estimate, const Eigen::Isometry3d& truth);

/// Re-expresses a relative motion of frame c and its covariance for a frame b rigidly attached
/// to c (e.g. camera -> rover body), given the fixed extrinsic T_b_c (pose of c in b):
///   delta_b = T_b_c delta_c T_b_c^-1,   Cov_b = J Cov_c J^T,
///   J = [R_bc, [R_b t_bc]_x R_bc; 0, R_bc]   (R_b = rotation of delta_b).
/// Pass T_b_c^-1 to go the other way (e.g. a wheel-odometry prior from body to camera).
void ChangeMotionFrame(const Eigen::Isometry3d& delta_c, const Matrix6d& cov_c,
                       const Eigen::Isometry3d& t_b_c, Eigen::Isometry3d* delta_b, Matrix6d* cov_b);

}  // namespace rover::dl::vo
