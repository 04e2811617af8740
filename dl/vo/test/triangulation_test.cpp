#include "rover/dl/vo/triangulation.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>

#include "synthetic_scene.hpp"

namespace rover::dl::vo {
namespace {

TEST(RayMidpoint, IntersectingAndSkewRays) {
  double gap = -1.0;
  auto p = RayMidpoint({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {-1, 0, 1}, &gap);
  ASSERT_TRUE(p);
  EXPECT_NEAR((*p - Eigen::Vector3d(0, 0, 1)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(gap, 0.0, 1e-12);
  // Skew rays: x-axis ray at z = 5 ... a ray along z at (0,0,.) and one along x at y = 0.2.
  p = RayMidpoint({0, 0, 0}, {0, 0, 1}, {-3, 0.2, 4}, {1, 0, 0}, &gap);
  ASSERT_TRUE(p);
  EXPECT_NEAR((*p - Eigen::Vector3d(0, 0.1, 4)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(gap, 0.2, 1e-12);
  // Parallel and diverging rays have no midpoint in front.
  EXPECT_FALSE(RayMidpoint({0, 0, 0}, {0, 0, 1}, {1, 0, 0}, {0, 0, 1}));
  EXPECT_FALSE(RayMidpoint({0, 0, 0}, {0.1, 0, 1}, {1, 0, 0}, {0.3, 0, 1}));
}

TEST(TriangulateStereo, RoundTripIsExact) {
  const StereoCamera cam = testing::TestCamera();
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0.3, 1.2, 2.5), Eigen::Vector3d(-4, -1, 20), Eigen::Vector3d(2, 0.5, 60)}) {
    const auto x = TriangulateStereo(cam, cam.ProjectLeft(p), cam.ProjectRight(p), 0.3);
    ASSERT_TRUE(x);
    EXPECT_NEAR((x->position - p).norm(), 0.0, 1e-9 * p.norm());
    EXPECT_NEAR(x->ray_gap, 0.0, 1e-9);
  }
}

TEST(TriangulateStereo, RejectsNonPositiveDisparity) {
  const StereoCamera cam = testing::TestCamera();
  EXPECT_FALSE(TriangulateStereo(cam, {100, 100}, {100, 100}, 0.3));
  EXPECT_FALSE(TriangulateStereo(cam, {100, 100}, {103, 100}, 0.3));
}

TEST(TriangulateStereo, CovarianceMatchesMonteCarlo) {
  const StereoCamera cam = testing::TestCamera();
  const double sigma = 0.3;
  std::mt19937_64 rng(1234);
  std::normal_distribution<double> n(0.0, sigma);
  for (const Eigen::Vector3d& p : {Eigen::Vector3d(0.5, 1.0, 4.0), Eigen::Vector3d(-2, 0.3, 9)}) {
    const Eigen::Vector2d ul = cam.ProjectLeft(p), ur = cam.ProjectRight(p);
    const auto x = TriangulateStereo(cam, ul, ur, sigma);
    ASSERT_TRUE(x);
    const int kSamples = 20000;
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
    std::vector<Eigen::Vector3d> samples;
    for (int k = 0; k < kSamples; ++k) {
      const Eigen::Vector2d nl(ul.x() + n(rng), ul.y() + n(rng));
      const Eigen::Vector2d nr(ur.x() + n(rng), ur.y() + n(rng));
      const auto s = TriangulateStereo(cam, nl, nr, sigma);
      ASSERT_TRUE(s);
      samples.push_back(s->position);
      mean += s->position;
    }
    mean /= kSamples;
    for (const auto& s : samples) cov += (s - mean) * (s - mean).transpose();
    cov /= kSamples - 1;
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(std::sqrt(cov(i, i)), std::sqrt(x->covariance(i, i)),
                  0.05 * std::sqrt(x->covariance(i, i)))
          << "axis " << i << " at z=" << p.z();
    }
    // Depth sigma follows z^2 / (f b) * sqrt(2) sigma.
    const double sz = p.z() * p.z() / (cam.fx * cam.baseline) * std::sqrt(2.0) * sigma;
    EXPECT_NEAR(std::sqrt(x->covariance(2, 2)), sz, 0.05 * sz);
    // The long axis of the ellipsoid points along the viewing ray.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(x->covariance);
    EXPECT_GT(std::abs(es.eigenvectors().col(2).dot(p.normalized())), 0.99);
  }
}

}  // namespace
}  // namespace rover::dl::vo
