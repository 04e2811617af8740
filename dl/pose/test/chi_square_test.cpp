#include "rover/dl/pose/chi_square.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::dl::pose {
namespace {

TEST(ChiSquare, QuantilesMatchTables) {
  // Reference values from standard chi-square tables.
  EXPECT_NEAR(ChiSquareQuantile(0.95, 1), 3.841459, 1e-5);
  EXPECT_NEAR(ChiSquareQuantile(0.95, 2), 5.991465, 1e-5);
  EXPECT_NEAR(ChiSquareQuantile(0.95, 3), 7.814728, 1e-5);
  EXPECT_NEAR(ChiSquareQuantile(0.95, 6), 12.591587, 1e-5);
  EXPECT_NEAR(ChiSquareQuantile(0.99, 6), 16.811894, 1e-5);
  EXPECT_NEAR(ChiSquareQuantile(0.999, 6), 22.457744, 1e-5);
  EXPECT_NEAR(ChiSquareQuantile(0.9999, 2), 18.420681, 1e-5);
  EXPECT_NEAR(ChiSquareQuantile(0.025, 100), 74.221927, 1e-4);
  EXPECT_NEAR(ChiSquareQuantile(0.975, 100), 129.561197, 1e-4);
}

TEST(ChiSquare, CdfBasics) {
  // 2 dof: F(x) = 1 - exp(-x/2).
  for (double x : {0.1, 1.0, 4.0, 20.0, 80.0}) {
    EXPECT_NEAR(ChiSquareCdf(x, 2), 1.0 - std::exp(-x / 2), 1e-13) << x;
  }
  EXPECT_EQ(ChiSquareCdf(0.0, 3), 0.0);
  EXPECT_EQ(ChiSquareCdf(-1.0, 3), 0.0);
  EXPECT_EQ(ChiSquareCdf(INFINITY, 3), 1.0);
  // 1 dof: F(x) = erf(sqrt(x / 2)).
  for (double x : {0.01, 0.5, 3.0, 9.0, 30.0}) {
    EXPECT_NEAR(ChiSquareCdf(x, 1), std::erf(std::sqrt(x / 2)), 1e-13) << x;
  }
  for (int k : {1, 2, 3, 6, 9, 50, 500}) {
    for (double p : {0.001, 0.05, 0.5, 0.95, 0.9999}) {
      EXPECT_NEAR(ChiSquareCdf(ChiSquareQuantile(p, k), k), p, 1e-10) << k << " " << p;
    }
  }
  EXPECT_NEAR(RegularizedGammaP(1.0, 2.0), 1.0 - std::exp(-2.0), 1e-14);
}

}  // namespace
}  // namespace rover::dl::pose
