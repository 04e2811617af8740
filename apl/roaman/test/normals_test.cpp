// Step 3: plane fits over each cell and its neighbours.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rover/apl/roaman/traversability.hpp"
#include "scenes.hpp"

namespace rover::apl::roaman {
namespace {

GridGeometry OffsetGeometry(int w, int h) { return testing::CellGeometry(w, h, 1.0, -2.0); }

ElevationMap Plane(double a, double b, int w = 20, int h = 20) {
  const sim::terrain::HeightField f = testing::HeightFieldOf(
      0.0, -3.0, 3.0, 0.0, 0.01, [a, b](double x, double y) { return a * x + b * y + 1.0; });
  return testing::SampledElevation(f, OffsetGeometry(w, h));
}

TEST(Normals, RecoverThePlaneOfATiltedSurface) {
  const double a = std::tan(20.0 * kDegree) * std::cos(30.0 * kDegree);
  const double b = std::tan(20.0 * kDegree) * std::sin(30.0 * kDegree);
  const ElevationMap m = Plane(a, b);
  const NormalMap n = FitNormals(m, RoamanOptions{});
  for (const auto& [i, j] : {std::pair{10, 10}, std::pair{0, 0}, std::pair{19, 7}}) {
    ASSERT_TRUE(n.has(i, j)) << i << ", " << j;
    EXPECT_NEAR(n.slope.at(i, j), 20.0 * kDegree, 1e-4);
    const Eigen::Vector3f expect = Eigen::Vector3f(-a, -b, 1.0).normalized();
    EXPECT_NEAR(n.normal.at(i, j).dot(expect), 1.0f, 1e-5);
    EXPECT_NEAR(n.residual.at(i, j), 0.0, 2e-4);  // float heights
  }
}

TEST(Normals, ResidualMeasuresRoughness) {
  ElevationMap m = Plane(0.0, 0.0);
  std::mt19937 rng(3);
  std::normal_distribution<float> noise(0.0f, 0.02f);
  for (float& z : m.mean.values()) z += noise(rng);
  const NormalMap n = FitNormals(m, RoamanOptions{});
  double sum = 0.0;
  int count = 0;
  for (int j = 2; j < 18; ++j) {
    for (int i = 2; i < 18; ++i) {
      sum += n.residual.at(i, j);
      ++count;
      EXPECT_LT(n.slope.at(i, j), 20.0 * kDegree);
    }
  }
  // RMS of 25 residuals of a 3-parameter fit: sigma sqrt(22 / 25) ~ 0.019 on average.
  EXPECT_NEAR(sum / count, 0.02 * std::sqrt(22.0 / 25.0), 0.003);
}

TEST(Normals, NeedEnoughNonCollinearHeights) {
  ElevationMap m = Plane(0.1, 0.0);
  // Keep a single row of heights (collinear) plus an isolated cell.
  for (int j = 0; j < 20; ++j) {
    for (int i = 0; i < 20; ++i) {
      if (j != 5 && !(i == 15 && j == 15)) m.source.at(i, j) = HeightSource::kNone;
    }
  }
  const NormalMap n = FitNormals(m, RoamanOptions{});
  EXPECT_FALSE(n.has(10, 5));   // 5 collinear cells in its window: the cross slope is unknown
  EXPECT_FALSE(n.has(15, 15));  // 1 cell < min_fit_cells
  EXPECT_FALSE(n.has(10, 10));  // no height at all
  // Two rows are enough.
  for (int i = 0; i < 20; ++i) m.source.at(i, 6) = HeightSource::kMeasured;
  const NormalMap two = FitNormals(m, RoamanOptions{});
  ASSERT_TRUE(two.has(10, 5));
  EXPECT_NEAR(two.slope.at(10, 5), std::atan(0.1), 1e-4);
}

TEST(Normals, WindowSizeIsTheParameter) {
  // A step of 0.2 m between i < 10 and i >= 10: the fit at i = 7 sees it with a 35 cm window
  // (half-width 3) but not with the default 25 cm (half-width 2).
  ElevationMap m = Plane(0.0, 0.0);
  for (int j = 0; j < 20; ++j) {
    for (int i = 10; i < 20; ++i) m.mean.at(i, j) += 0.2f;
  }
  RoamanOptions o;
  EXPECT_NEAR(FitNormals(m, o).slope.at(7, 10), 0.0, 1e-4);
  o.normal_window = 0.35;
  EXPECT_GT(FitNormals(m, o).slope.at(7, 10), 5.0 * kDegree);
}

}  // namespace
}  // namespace rover::apl::roaman
