#include "rover/sim/heightfield.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::sim::terrain {
namespace {

TEST(HeightField, BilinearPlaneIsExact) {
  HeightField h(11, 21, 0.5, Eigen::Vector2d(-2.5, -5.0));
  for (int j = 0; j < h.ny(); ++j) {
    for (int i = 0; i < h.nx(); ++i) {
      const double x = h.min_x() + i * h.resolution(), y = h.min_y() + j * h.resolution();
      h.at(i, j) = static_cast<float>(0.2 * x - 0.1 * y + 1.0);
    }
  }
  Eigen::Vector2d g;
  EXPECT_NEAR(h.HeightAndGradient(0.3, 1.7, &g), 0.2 * 0.3 - 0.1 * 1.7 + 1.0, 1e-6);
  EXPECT_NEAR(g(0), 0.2, 1e-6);
  EXPECT_NEAR(g(1), -0.1, 1e-6);
  const Eigen::Vector3d n = h.Normal(0.3, 1.7);
  EXPECT_TRUE(n.isApprox(Eigen::Vector3d(-0.2, 0.1, 1.0).normalized(), 1e-6)) << n.transpose();
}

TEST(HeightField, ClampsOutsideAndReportsContainment) {
  HeightField h(3, 3, 1.0);
  h.at(2, 2) = 5.0f;
  EXPECT_TRUE(h.Contains(1.0, 1.0));
  EXPECT_FALSE(h.Contains(2.5, 1.0));
  EXPECT_NEAR(h.Height(10.0, 10.0), 5.0, 1e-9);
  h.soil(0, 0) = Soil::kLooseSand;
  EXPECT_EQ(h.SoilAt(-3.0, 0.2), Soil::kLooseSand);
  EXPECT_STREQ(SoilName(Soil::kBedrock), "bedrock");
}

}  // namespace
}  // namespace rover::sim::terrain
