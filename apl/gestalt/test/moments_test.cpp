#include "rover/apl/gestalt/moments.hpp"

#include <gtest/gtest.h>

#include <Eigen/SVD>
#include <cmath>
#include <vector>

#include "rover/sim/terrain/random.hpp"

namespace rover::apl::gestalt {
namespace {

// Points on z = a x + b y + c with N(0, sigma) noise along z, over a square of side `size`
// centred at (cx, cy).
std::vector<Eigen::Vector3d> NoisyPlane(double a, double b, double c, double sigma, double cx,
                                        double cy, double size, int n, std::uint64_t seed) {
  sim::terrain::Rng rng(seed);
  std::vector<Eigen::Vector3d> pts;
  for (int k = 0; k < n; ++k) {
    const double x = cx + rng.Uniform(-0.5, 0.5) * size, y = cy + rng.Uniform(-0.5, 0.5) * size;
    pts.emplace_back(x, y, a * x + b * y + c + sigma * rng.Normal());
  }
  return pts;
}

Moments Sum(const std::vector<Eigen::Vector3d>& pts) {
  Moments m;
  for (const auto& p : pts) m.Add(p);
  return m;
}

// Total least squares straight from the points: SVD of the centred point matrix.
struct DirectFit {
  Eigen::Vector3d normal;
  double residual;
};
DirectFit FitDirect(const std::vector<Eigen::Vector3d>& pts) {
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (const auto& p : pts) m += p;
  m /= static_cast<double>(pts.size());
  Eigen::MatrixXd a(pts.size(), 3);
  for (std::size_t k = 0; k < pts.size(); ++k)
    a.row(static_cast<Eigen::Index>(k)) = (pts[k] - m).transpose();
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(a, Eigen::ComputeThinV);
  Eigen::Vector3d n = svd.matrixV().col(2);
  if (n.z() < 0) n = -n;
  const double res = svd.singularValues()[2] / std::sqrt(static_cast<double>(pts.size()));
  return {n, res};
}

TEST(Moments, AddAndMerge) {
  Moments a, b;
  a.Add(1, 2, 3);
  a.Add(-1, 0, 1);
  b.Add(2, 2, 2);
  const Moments c = a + b;
  EXPECT_EQ(c.n, 3.0);
  EXPECT_EQ(c.sx, 2.0);
  EXPECT_EQ(c.sxz, 3.0 - 1.0 + 4.0);
  EXPECT_EQ(c.syz, 6.0 + 0.0 + 4.0);
  EXPECT_EQ((c - b).sxx, a.sxx);
  EXPECT_DOUBLE_EQ(a.Mean().z(), 2.0);
  EXPECT_DOUBLE_EQ(a.StdDevZ(), 1.0);
  EXPECT_TRUE(Moments{}.empty());
}

TEST(Moments, CovarianceMatchesTheSampleCovariance) {
  const auto pts = NoisyPlane(0.3, -0.2, 1.0, 0.05, 2.0, -1.0, 2.6, 500, 7);
  Eigen::Vector3d m = Eigen::Vector3d::Zero();
  for (const auto& p : pts) m += p;
  m /= 500.0;
  Eigen::Matrix3d c = Eigen::Matrix3d::Zero();
  for (const auto& p : pts) c += (p - m) * (p - m).transpose();
  c /= 500.0;
  EXPECT_LT((Sum(pts).Covariance() - c).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(PlaneFit, MatchesADirectFitOfTheRawPoints) {
  // A tilted, noisy patch far from the origin, as a 2.6 m rover disc 40 m out would be.
  for (std::uint64_t seed : {1u, 2u, 3u}) {
    const auto pts = NoisyPlane(0.25, 0.1, -3.0, 0.02, 40.0, -25.0, 2.6, 2000, seed);
    const PlaneFit f = FitPlane(Sum(pts), 2.0);
    const DirectFit d = FitDirect(pts);
    ASSERT_TRUE(f.ok);
    EXPECT_TRUE(f.planar);
    EXPECT_LT((f.normal - d.normal).norm(), 1e-9) << seed;
    EXPECT_NEAR(f.residual, d.residual, 1e-9) << seed;
    // The fitted normal is the plane's: (-a, -b, 1) normalised.
    const Eigen::Vector3d truth = Eigen::Vector3d(-0.25, -0.1, 1.0).normalized();
    EXPECT_LT((f.normal - truth).norm(), 5e-3);
    EXPECT_NEAR(f.tilt, std::acos(truth.z()), 5e-3);
    EXPECT_NEAR(f.HeightAt(40.0, -25.0), 0.25 * 40.0 + 0.1 * -25.0 - 3.0, 5e-3);
  }
}

TEST(PlaneFit, ResidualIsTheRmsDistanceAlongTheNormal) {
  // A checkerboard of points 0.1 m above and below a flat plane: residual 0.1.
  Moments m;
  for (int a = 0; a < 10; ++a) {
    for (int b = 0; b < 10; ++b) m.Add(0.1 * a, 0.1 * b, (a + b) % 2 == 0 ? 0.1 : -0.1);
  }
  EXPECT_NEAR(FitPlane(m, 1.0).residual, 0.1, 2e-3);
}

TEST(PlaneFit, EigenRatioRejectsPointsThatAreNotAPlane) {
  // A thin rod of points: the second eigenvalue is as small as the first.
  sim::terrain::Rng rod_rng(4);
  Moments line;
  for (int k = 0; k < 200; ++k)
    line.Add(0.01 * k, 0.002 * rod_rng.Normal(), 0.002 * rod_rng.Normal());
  EXPECT_FALSE(FitPlane(line, 2.0).planar);
  // A cube of points: all three eigenvalues equal.
  sim::terrain::Rng rng(5);
  Moments cube;
  for (int k = 0; k < 500; ++k) cube.Add(rng.Uniform(), rng.Uniform(), rng.Uniform());
  const PlaneFit f = FitPlane(cube, 2.0);
  EXPECT_TRUE(f.ok);
  EXPECT_FALSE(f.planar);
  EXPECT_NEAR(f.residual, std::sqrt(1.0 / 12.0), 0.03);
}

TEST(PlaneFit, TooFewPointsIsNoFit) {
  Moments m;
  m.Add(0, 0, 0);
  m.Add(1, 0, 0);
  EXPECT_FALSE(FitPlane(m, 2.0).ok);
  m.Add(0, 1, 0);
  const PlaneFit f = FitPlane(m, 2.0);
  EXPECT_TRUE(f.ok);
  EXPECT_NEAR(f.tilt, 0.0, 1e-9);
  EXPECT_NEAR(f.residual, 0.0, 1e-7);
}

}  // namespace
}  // namespace rover::apl::gestalt
