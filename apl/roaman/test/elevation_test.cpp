// Steps 1 and 2: binning, the height distribution, and interpolation of small holes only.
#include <gtest/gtest.h>

#include <cmath>

#include "rover/apl/roaman/traversability.hpp"
#include "scenes.hpp"

namespace rover::apl::roaman {
namespace {

// A measured map of a tilted plane z = 0.1 x + 0.05 y with `holes` (cells set to kNone).
ElevationMap PlaneWithHoles(int w, int h, const std::vector<Eigen::Vector2i>& holes) {
  const sim::terrain::HeightField plane = testing::HeightFieldOf(
      -1, -1, 5, 5, 0.01, [](double x, double y) { return 0.1 * x + 0.05 * y; });
  ElevationMap m = testing::SampledElevation(plane, testing::CellGeometry(w, h));
  for (const Eigen::Vector2i& c : holes) {
    m.source.at(c.x(), c.y()) = HeightSource::kNone;
    m.mean.at(c.x(), c.y()) = std::nanf("");
    --m.measured;
  }
  return m;
}

TEST(Elevation, BinsMeanSigmaAndClipsTopAndBottom) {
  Layer<CellStats> cells(3, 2);
  CellStats& c = cells.at(1, 1);
  for (const double z : {0.0, 0.0, 0.0, 0.0, 1.0}) {  // one outlier
    ++c.count;
    c.sum += z;
    c.sum_sq += z * z;
    c.min = std::min(c.min, static_cast<float>(z));
    c.max = std::max(c.max, static_cast<float>(z));
  }
  RoamanOptions o;
  const ElevationMap m = BinElevation(cells, testing::CellGeometry(3, 2), 0, 0, 3, 2, o);
  EXPECT_EQ(m.measured, 1);
  EXPECT_EQ(m.source.at(1, 1), HeightSource::kMeasured);
  EXPECT_EQ(m.source.at(0, 0), HeightSource::kNone);
  EXPECT_NEAR(m.mean.at(1, 1), 0.2, 1e-6);
  EXPECT_NEAR(m.sigma.at(1, 1), 0.4, 1e-6);
  EXPECT_NEAR(m.top.at(1, 1), 1.0, 1e-6);     // mean + 2 sigma = 1.0 = max
  EXPECT_NEAR(m.bottom.at(1, 1), 0.0, 1e-6);  // mean - 2 sigma = -0.6, clipped to min 0
  o.height_sigma_k = 1.0;
  const ElevationMap k1 = BinElevation(cells, testing::CellGeometry(3, 2), 0, 0, 3, 2, o);
  EXPECT_NEAR(k1.top.at(1, 1), 0.6, 1e-6);  // the outlier is clipped to mean + sigma
  // A window that reaches past the cells: those have no height.
  const ElevationMap shifted = BinElevation(cells, testing::CellGeometry(3, 2), 1, 1, 3, 2, o);
  EXPECT_EQ(shifted.source.at(0, 0), HeightSource::kMeasured);
  EXPECT_EQ(shifted.source.at(2, 1), HeightSource::kNone);
  EXPECT_NEAR(shifted.geometry.origin_x, 0.05, 1e-12);
  o.min_cell_points = 6;
  EXPECT_EQ(BinElevation(cells, testing::CellGeometry(3, 2), 0, 0, 3, 2, o).measured, 0);
}

TEST(Elevation, FillsSmallHolesByLinearInterpolation) {
  // A single missing cell and a 3-cell gap along i: both within max_fill_gap 0.2 m.
  ElevationMap m = PlaneWithHoles(20, 20, {{5, 5}, {10, 12}, {11, 12}, {12, 12}});
  const RoamanOptions o;
  EXPECT_EQ(FillHoles(&m, o), 4);
  EXPECT_EQ(m.filled, 4);
  for (const auto& c : std::vector<Eigen::Vector2i>{{5, 5}, {10, 12}, {11, 12}, {12, 12}}) {
    EXPECT_EQ(m.source.at(c.x(), c.y()), HeightSource::kFilled);
    const Eigen::Vector2d p = m.geometry.Center(c.x(), c.y());
    EXPECT_NEAR(m.mean.at(c.x(), c.y()), 0.1 * p.x() + 0.05 * p.y(), 1e-5);  // a plane: exact
    EXPECT_FLOAT_EQ(m.top.at(c.x(), c.y()), m.mean.at(c.x(), c.y()));
    EXPECT_FLOAT_EQ(m.sigma.at(c.x(), c.y()), 0.0f);
  }
}

TEST(Elevation, LeavesLargeHolesAndOcclusionEdgesMissing) {
  // A 6 x 6 hole (30 cm) is wider than max_fill_gap along every line through its centre.
  std::vector<Eigen::Vector2i> hole;
  for (int j = 7; j < 13; ++j) {
    for (int i = 7; i < 13; ++i) hole.emplace_back(i, j);
  }
  ElevationMap m = PlaneWithHoles(20, 20, hole);
  const RoamanOptions o;
  FillHoles(&m, o);
  EXPECT_EQ(m.source.at(9, 9), HeightSource::kNone);
  EXPECT_EQ(m.source.at(10, 10), HeightSource::kNone);
  // Its rim cells are bracketed only along lines that leave through the near side; the centre
  // rows stay missing.
  int missing = 0;
  for (const auto& c : hole) missing += m.source.at(c.x(), c.y()) == HeightSource::kNone;
  EXPECT_GE(missing, 16);

  // A one-cell gap between a rock top (0.5 m) and the ground is an occlusion edge: a 0.5 m rise
  // over 10 cm is steeper than max_slope, never bridged, whatever the direction count.
  ElevationMap edge = PlaneWithHoles(9, 9, {});
  for (int j = 0; j < 9; ++j) {
    for (int i = 0; i < 4; ++i) edge.mean.at(i, j) = 0.5f;
    edge.source.at(4, j) = HeightSource::kNone;
  }
  RoamanOptions one = o;
  one.min_fill_directions = 1;
  FillHoles(&edge, one);
  for (int j = 0; j < 9; ++j) EXPECT_EQ(edge.source.at(4, j), HeightSource::kNone) << j;
}

TEST(Elevation, DirectionCountAndGapWidthAreParameters) {
  // A missing column 1 cell wide is bracketed along i and both diagonals (3 lines), not along
  // j: filled with the default 2 directions, kept missing when all 4 are required.
  std::vector<Eigen::Vector2i> column;
  for (int j = 0; j < 10; ++j) column.emplace_back(5, j);
  ElevationMap a = PlaneWithHoles(10, 10, column);
  RoamanOptions o;
  FillHoles(&a, o);
  EXPECT_EQ(a.source.at(5, 5), HeightSource::kFilled);
  ElevationMap b = PlaneWithHoles(10, 10, column);
  o.min_fill_directions = 4;
  FillHoles(&b, o);
  EXPECT_EQ(b.source.at(5, 5), HeightSource::kNone);
  ElevationMap c = PlaneWithHoles(10, 10, {{5, 5}});
  o = {};
  o.max_fill_gap = 0.0;
  EXPECT_EQ(FillHoles(&c, o), 0);
}

}  // namespace
}  // namespace rover::apl::roaman
