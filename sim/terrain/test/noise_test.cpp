#include "rover/sim/terrain/noise.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::sim::terrain {
namespace {

TEST(QuinticFade, EndpointsAndFlatEnds) {
  EXPECT_DOUBLE_EQ(QuinticFade(0.0), 0.0);
  EXPECT_DOUBLE_EQ(QuinticFade(1.0), 1.0);
  EXPECT_DOUBLE_EQ(QuinticFade(0.5), 0.5);
  const double h = 1e-6;
  EXPECT_NEAR((QuinticFade(h) - QuinticFade(0.0)) / h, 0.0, 1e-8);
  EXPECT_NEAR((QuinticFade(1.0) - QuinticFade(1.0 - h)) / h, 0.0, 1e-8);
}

TEST(ValueNoise, BoundedContinuousAndSeeded) {
  const Eigen::Vector2d lo(-10, -5), hi(10, 5);
  Rng r1(3), r2(3), r3(4);
  const ValueNoise a(&r1, lo, hi, 2.0), b(&r2, lo, hi, 2.0), c(&r3, lo, hi, 2.0);
  double sum = 0, sum2 = 0, max_step = 0;
  int n = 0, differ = 0;
  for (double x = -10; x <= 10; x += 0.05) {
    for (double y = -5; y <= 5; y += 0.05) {
      const double v = a(x, y);
      ASSERT_LE(std::abs(v), 1.0);
      ASSERT_EQ(v, b(x, y));
      differ += v != c(x, y);
      sum += v;
      sum2 += v * v;
      max_step = std::max(max_step, std::abs(a(x + 0.001, y) - v));
      ++n;
    }
  }
  EXPECT_GT(differ, n * 9 / 10);
  // Slope bound: |dv/dx| <= 2 * max fade slope (1.875) / wavelength = 1.875 per metre.
  EXPECT_LT(max_step, 0.001 * 1.9);
  // Not degenerate: lattice values uniform in [-1, 1] interpolated -> sd well above 0.2.
  const double mean = sum / n, sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_GT(sd, 0.2);
  EXPECT_LT(std::abs(mean), 0.2);
}

TEST(FractalNoise, OctavesWeightsAndBound) {
  Rng rng(11);
  const FractalNoise f(&rng, Eigen::Vector2d(0, 0), Eigen::Vector2d(30, 30), 8.0, 4, 0.5);
  EXPECT_EQ(f.octaves(), 4);
  EXPECT_DOUBLE_EQ(f.max_abs(), 1.0 + 0.5 + 0.25 + 0.125);
  for (double x = 0; x <= 30; x += 0.37) {
    for (double y = 0; y <= 30; y += 0.41) EXPECT_LE(std::abs(f(x, y)), f.max_abs());
  }
}

}  // namespace
}  // namespace rover::sim::terrain

namespace rover::sim::terrain {
namespace {

TEST(FractalNoise, GridFillMatchesPointEvaluation) {
  Rng rng(5);
  const FractalNoise f(&rng, Eigen::Vector2d(-3, -2), Eigen::Vector2d(4, 5), 3.0, 5, 0.5);
  const int nx = 71, ny = 58;
  std::vector<double> grid(static_cast<std::size_t>(nx * ny), 1.0);
  f.AddToGrid(-3.0, -2.0, 0.1, nx, ny, 2.0, grid.data());
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      EXPECT_NEAR(grid[static_cast<std::size_t>(j * nx + i)],
                  1.0 + 2.0 * f(-3.0 + i * 0.1, -2.0 + j * 0.1), 1e-12);
    }
  }
}

}  // namespace
}  // namespace rover::sim::terrain
