// Step 4: regions of similar slope.
#include <gtest/gtest.h>

#include <cmath>

#include "rover/apl/roaman/traversability.hpp"
#include "scenes.hpp"

namespace rover::apl::roaman {
namespace {

// Flat for x < 1 m, then a 50° ramp up to x = 1.5 m, then flat again (a mesa).
double Mesa(double x, double) {
  const double t = std::tan(50.0 * kDegree);
  if (x < 1.0) return 0.0;
  if (x < 1.5) return t * (x - 1.0);
  return t * 0.5;
}

TEST(Regions, SplitTerrainAtSlopeChanges) {
  const sim::terrain::HeightField f = testing::HeightFieldOf(-0.5, -0.5, 3.0, 2.0, 0.01, Mesa);
  const ElevationMap m = testing::SampledElevation(f, testing::CellGeometry(50, 30));  // x 0..2.5 m
  const RoamanOptions o;
  const NormalMap n = FitNormals(m, o);
  const RegionMap r = GrowRegions(m, n, o);
  const int flat = r.id.at(5, 15), ramp = r.id.at(25, 15), top = r.id.at(45, 15);
  ASSERT_GE(flat, 0);
  ASSERT_GE(ramp, 0);
  ASSERT_GE(top, 0);
  EXPECT_NE(flat, ramp);
  EXPECT_NE(ramp, top);
  EXPECT_NE(flat, top);  // not connected through the ramp
  // (The flat regions take in the first fits that see the ramp, within region_tolerance.)
  EXPECT_NEAR(r.regions[static_cast<std::size_t>(flat)].slope, 0.0, 1.0 * kDegree);
  EXPECT_NEAR(r.regions[static_cast<std::size_t>(top)].slope, 0.0, 1.0 * kDegree);
  EXPECT_NEAR(r.regions[static_cast<std::size_t>(ramp)].slope, 50.0 * kDegree, 2.0 * kDegree);
  // The ramp's interior (fits that see only the ramp) is one region along its whole width.
  for (int j = 0; j < 30; ++j) EXPECT_EQ(r.id.at(25, j), ramp) << j;
  // Region sizes add up to the cells with a normal.
  int total = 0;
  for (const SlopeRegion& s : r.regions) total += s.cells;
  EXPECT_EQ(total, 50 * 30);
}

TEST(Regions, AHeightJumpEndsARegionEvenWhenTheSlopeIsTheSame) {
  // Two flat terraces 0.3 m apart with a sharp edge: the fits next to the edge tilt, but the
  // terraces' far parts have the same normal and must still be two regions.
  const sim::terrain::HeightField f = testing::HeightFieldOf(
      -0.5, -0.5, 3.0, 2.0, 0.01, [](double x, double) { return x < 1.0 ? 0.0 : 0.3; });
  const ElevationMap m = testing::SampledElevation(f, testing::CellGeometry(40, 20));
  RoamanOptions o;
  o.region_tolerance = 89.0 * kDegree;  // accept any normal: only the jump can split
  const RegionMap r = GrowRegions(m, FitNormals(m, o), o);
  EXPECT_NE(r.id.at(2, 10), r.id.at(37, 10));
  o.region_max_jump = 0.5;
  const RegionMap joined = GrowRegions(m, FitNormals(m, o), o);
  EXPECT_EQ(joined.id.at(2, 10), joined.id.at(37, 10));
}

TEST(Regions, CellsWithoutANormalBelongToNone) {
  const sim::terrain::HeightField f = testing::FlatGround(-0.5, -0.5, 2.0, 2.0);
  ElevationMap m = testing::SampledElevation(f, testing::CellGeometry(10, 10));
  for (int j = 0; j < 10; ++j) m.source.at(4, j) = m.source.at(5, j) = HeightSource::kNone;
  const RoamanOptions o;
  const RegionMap r = GrowRegions(m, FitNormals(m, o), o);
  EXPECT_EQ(r.id.at(4, 3), -1);
  EXPECT_NE(r.id.at(1, 3), r.id.at(8, 3));  // the missing band separates them
  EXPECT_EQ(r.regions.size(), 2u);
}

}  // namespace
}  // namespace rover::apl::roaman
