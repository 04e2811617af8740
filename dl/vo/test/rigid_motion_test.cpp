#include "rover/dl/vo/rigid_motion.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <random>

#include "rover/base/units.hpp"
#include "rover/dl/vo/triangulation.hpp"
#include "synthetic_scene.hpp"

namespace rover::dl::vo {
namespace {

Eigen::Isometry3d Motion(const Eigen::Vector3d& t, const Eigen::Vector3d& w) {
  Eigen::Isometry3d m = Eigen::Isometry3d::Identity();
  m.linear() = ExpSo3(w);
  m.translation() = t;
  return m;
}

// Features seen by a stereo camera before and after `motion`, with pixel noise, triangulated
// with covariances. Points at ranges 2..12 m in front of both cameras. A share of them become
// outliers: their second observation is of a different point.
std::vector<Correspondence> MakeCorrespondences(const Eigen::Isometry3d& motion, int n,
                                                double pixel_noise, double outlier_share,
                                                std::uint64_t seed,
                                                std::vector<bool>* is_outlier = nullptr) {
  const StereoCamera cam = testing::TestCamera();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> ux(-4.0, 4.0), uy(-1.0, 1.5), uz(2.0, 12.0), u01(0, 1);
  std::normal_distribution<double> noise(0.0, pixel_noise);
  auto observe = [&](const Eigen::Vector3d& p) {
    const Eigen::Vector2d l = cam.ProjectLeft(p) + Eigen::Vector2d(noise(rng), noise(rng));
    const Eigen::Vector2d r = cam.ProjectRight(p) + Eigen::Vector2d(noise(rng), noise(rng));
    return TriangulateStereo(cam, l, r, pixel_noise);
  };
  std::vector<Correspondence> out;
  if (is_outlier) is_outlier->clear();
  while (static_cast<int>(out.size()) < n) {
    const Eigen::Vector3d p(ux(rng), uy(rng), uz(rng));
    Eigen::Vector3d q = motion.inverse() * p;
    const bool outlier = u01(rng) < outlier_share;
    if (outlier) q = Eigen::Vector3d(ux(rng), uy(rng), uz(rng));
    if (q.z() < 1.0) continue;
    const auto a = observe(p);
    const auto b = observe(q);
    if (!a || !b) continue;
    out.push_back(Correspondence{a->position, a->covariance, b->position, b->covariance});
    if (is_outlier) is_outlier->push_back(outlier);
  }
  return out;
}

std::vector<int> All(std::size_t n) {
  std::vector<int> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = static_cast<int>(i);
  return v;
}

TEST(So3, ExpLogRoundTripAndSkew) {
  for (const Eigen::Vector3d& w : {Eigen::Vector3d(0.1, -0.2, 0.3), Eigen::Vector3d(0, 0, 3.0),
                                   Eigen::Vector3d(1e-14, 0, 0)}) {
    EXPECT_NEAR((LogSo3(ExpSo3(w)) - w).norm(), 0.0, 1e-12);
    EXPECT_NEAR(RotationAngle(ExpSo3(w)), w.norm(), 1e-7);
  }
  const Eigen::Vector3d a(1, 2, 3), b(-0.5, 0.3, 2);
  EXPECT_NEAR((Skew(a) * b - a.cross(b)).norm(), 0.0, 1e-15);
}

TEST(ClosedForm, ExactOnNoiselessPointsAndRejectsCollinear) {
  const Eigen::Isometry3d truth = Motion({0.3, -0.1, 0.8}, {0.02, 0.2, -0.05});
  std::vector<Correspondence> pts;
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-5, 5);
  for (int i = 0; i < 10; ++i) {
    Correspondence c;
    c.to = Eigen::Vector3d(u(rng), u(rng), 10 + u(rng));
    c.from = truth * c.to;
    pts.push_back(c);
  }
  Eigen::Isometry3d m;
  ASSERT_TRUE(FitRigidClosedForm(pts, All(pts.size()), {}, &m));
  EXPECT_NEAR(MotionError(m, truth).norm(), 0.0, 1e-9);
  std::vector<Correspondence> line(3);
  for (int i = 0; i < 3; ++i) {
    line[static_cast<std::size_t>(i)].to = Eigen::Vector3d(i, 2 * i, 3 * i);
    line[static_cast<std::size_t>(i)].from = truth * line[static_cast<std::size_t>(i)].to;
  }
  EXPECT_FALSE(FitRigidClosedForm(line, {0, 1, 2}, {}, &m));
  EXPECT_FALSE(FitRigidClosedForm(pts, {0, 1}, {}, &m));
}

TEST(Ransac, SurvivesFortyPercentOutliers) {
  const Eigen::Isometry3d truth = Motion({0.05, 0.01, 0.5}, {0.01, 0.06, -0.01});
  for (std::uint64_t seed : {1u, 2u, 3u, 4u, 5u}) {
    std::vector<bool> outlier;
    const auto pts = MakeCorrespondences(truth, 150, 0.2, 0.4, seed, &outlier);
    const int n_out = static_cast<int>(std::count(outlier.begin(), outlier.end(), true));
    ASSERT_GT(n_out, 45) << "seed " << seed;
    RansacOptions ro;
    ro.seed = seed;
    const RansacResult rr = RansacRigidMotion(pts, ro);
    ASSERT_TRUE(rr.ok);
    const RefineResult ml = RefineMaximumLikelihood(pts, rr.inliers, rr.motion, RefineOptions{});
    ASSERT_TRUE(ml.converged);
    const Vector6d e = MotionError(ml.motion, truth);
    EXPECT_LT(e.head<3>().norm(), 0.005) << "seed " << seed;
    EXPECT_LT(e.tail<3>().norm(), 0.05 * kDegree) << "seed " << seed;
    int false_inliers = 0;
    for (int i : rr.inliers) false_inliers += outlier[static_cast<std::size_t>(i)];
    EXPECT_LE(false_inliers, 3) << "seed " << seed;
    EXPECT_GE(static_cast<int>(rr.inliers.size()), 150 - n_out - 5);
  }
}

TEST(Ransac, DeterministicForASeed) {
  const Eigen::Isometry3d truth = Motion({0.1, 0, 0.4}, {0, 0.05, 0});
  const auto pts = MakeCorrespondences(truth, 80, 0.2, 0.3, 9);
  RansacOptions ro;
  ro.seed = 77;
  const RansacResult a = RansacRigidMotion(pts, ro);
  const RansacResult b = RansacRigidMotion(pts, ro);
  EXPECT_EQ(a.inliers, b.inliers);
  EXPECT_EQ(a.iterations, b.iterations);
  EXPECT_TRUE(a.motion.isApprox(b.motion, 0.0));
}

TEST(Ransac, FailsOnTooFewPointsAndOptionsValidate) {
  EXPECT_FALSE(RansacRigidMotion({Correspondence{}, Correspondence{}}, RansacOptions{}).ok);
  RansacOptions ro;
  ro.confidence = 1.0;
  EXPECT_FALSE(ro.Validate().ok());
  ro = RansacOptions{};
  ro.inlier_chi2 = -1;
  EXPECT_FALSE(ro.Validate().ok());
  RefineOptions fo;
  fo.max_iterations = 0;
  EXPECT_FALSE(fo.Validate().ok());
}

TEST(Refine, MaximumLikelihoodBeatsUnweightedClosedForm) {
  // Averaged over seeds, the covariance-weighted estimate is more accurate in translation.
  const Eigen::Isometry3d truth = Motion({0.05, 0.0, 0.6}, {0.0, 0.04, 0.0});
  double err_ls = 0.0, err_ml = 0.0;
  for (std::uint64_t seed = 100; seed < 130; ++seed) {
    const auto pts = MakeCorrespondences(truth, 60, 0.3, 0.0, seed);
    Eigen::Isometry3d ls;
    ASSERT_TRUE(FitRigidClosedForm(pts, All(pts.size()), {}, &ls));
    const RefineResult ml = RefineMaximumLikelihood(pts, All(pts.size()), ls, RefineOptions{});
    ASSERT_TRUE(ml.converged);
    EXPECT_LE(ml.iterations, 10);
    err_ls += MotionError(ls, truth).head<3>().norm();
    err_ml += MotionError(ml.motion, truth).head<3>().norm();
  }
  EXPECT_LT(err_ml, 0.7 * err_ls);
}

TEST(Refine, CovarianceIsConsistentNees) {
  // NEES = e^T Cov^-1 e over seeded runs should average 6 (chi^2 with 6 dof) if the covariance
  // from the triangulation model and H^-1 is right.
  const Eigen::Isometry3d truth = Motion({0.08, -0.02, 0.5}, {0.01, 0.07, 0.005});
  const int kRuns = 300;
  double sum = 0.0;
  int above_99 = 0;
  for (int run = 0; run < kRuns; ++run) {
    const auto pts = MakeCorrespondences(truth, 50, 0.3, 0.0, 1000 + run);
    const RefineResult ml = RefineMaximumLikelihood(pts, All(pts.size()), truth, RefineOptions{});
    ASSERT_TRUE(ml.converged);
    const Vector6d e = MotionError(ml.motion, truth);
    const double nees = e.dot(ml.covariance.ldlt().solve(e));
    sum += nees;
    above_99 += nees > 16.81;  // chi^2_6 99th percentile
  }
  const double mean = sum / kRuns;
  // Mean of 300 chi^2_6 samples: 6 +- 0.2 (1 sigma); allow for triangulation non-linearity.
  EXPECT_GT(mean, 5.0);
  EXPECT_LT(mean, 7.2);
  EXPECT_LE(above_99, 10);  // expected 3
}

TEST(ChangeMotionFrame, MatchesNumericalPropagation) {
  const Eigen::Isometry3d dc = Motion({0.1, 0.02, 0.5}, {0.01, 0.1, -0.02});
  // Camera 1.2 m forward and 1 m up on the rover, looking forward (rover x fwd, y left, z up).
  Eigen::Isometry3d t_b_c = Eigen::Isometry3d::Identity();
  t_b_c.linear() << 0, 0, 1, -1, 0, 0, 0, -1, 0;
  t_b_c.translation() = Eigen::Vector3d(0.6, 0.1, 1.2);
  Matrix6d cov_c = Matrix6d::Zero();
  cov_c.diagonal() << 1e-4, 2e-4, 3e-4, 1e-5, 2e-5, 3e-5;
  cov_c(0, 4) = cov_c(4, 0) = 5e-6;
  Eigen::Isometry3d db;
  Matrix6d cov_b;
  ChangeMotionFrame(dc, cov_c, t_b_c, &db, &cov_b);
  EXPECT_TRUE(db.isApprox(t_b_c * dc * t_b_c.inverse(), 1e-12));
  // Numerical Jacobian of the body error with respect to the camera error.
  Matrix6d j;
  for (int k = 0; k < 6; ++k) {
    Vector6d d = Vector6d::Zero();
    d(k) = 1e-7;
    Eigen::Isometry3d pert = dc;
    pert.linear() = ExpSo3(d.tail<3>()) * dc.linear();
    pert.translation() += d.head<3>();
    j.col(k) = MotionError(db, t_b_c * pert * t_b_c.inverse()) / 1e-7;
  }
  const Matrix6d expect = j * cov_c * j.transpose();
  EXPECT_NEAR((cov_b - expect).norm(), 0.0, 1e-6 * expect.norm());
  // And back again.
  Eigen::Isometry3d dc2;
  Matrix6d cov_c2;
  ChangeMotionFrame(db, cov_b, t_b_c.inverse(), &dc2, &cov_c2);
  EXPECT_TRUE(dc2.isApprox(dc, 1e-12));
  EXPECT_NEAR((cov_c2 - cov_c).norm(), 0.0, 1e-12);
}

TEST(MahalanobisSq, ZeroForExactAndScalesWithCovariance) {
  Correspondence c;
  c.to = Eigen::Vector3d(1, 2, 3);
  const Eigen::Isometry3d m = Motion({0.1, 0, 0}, {0, 0, 0});
  c.from = m * c.to;
  EXPECT_NEAR(MahalanobisSq(c, m), 0.0, 1e-20);
  c.from.x() += 0.2;
  c.cov_from = Eigen::Matrix3d::Identity() * 0.01;
  c.cov_to = Eigen::Matrix3d::Identity() * 0.03;
  EXPECT_NEAR(MahalanobisSq(c, m), 0.04 / 0.04, 1e-12);
}

}  // namespace
}  // namespace rover::dl::vo
