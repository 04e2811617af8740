#include "scenes.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::apl::roaman::testing {
namespace {

TEST(Scenes, HeightFieldsRocksAndWalls) {
  sim::terrain::HeightField g =
      HeightFieldOf(0, 0, 2, 1, 0.1, [](double x, double y) { return x + 2 * y; });
  EXPECT_EQ(g.nx(), 21);
  EXPECT_EQ(g.ny(), 11);
  EXPECT_NEAR(g.Height(1.0, 0.5), 2.0, 1e-6);
  sim::terrain::HeightField f = FlatGround(-1, -1, 1, 1, 0.02);
  AddRock(&f, 0.0, 0.0, 0.6, 0.3);
  EXPECT_NEAR(f.Height(0.0, 0.0), 0.3, 1e-6);
  EXPECT_NEAR(f.Height(0.31, 0.0), 0.0, 1e-6);
  AddWall(&f, {-0.5, 0.5}, {0.5, 0.5}, 0.1, 0.4);
  EXPECT_NEAR(f.Height(0.2, 0.5), 0.4, 1e-6);
  EXPECT_NEAR(f.Height(0.2, 0.7), 0.0, 1e-6);
}

TEST(Scenes, CulDeSacIsAUOpeningTowardItsMouth) {
  sim::terrain::HeightField g = FlatGround(-1, -4, 8, 4, 0.05);
  // Base at x = 6, mouth toward -x (the rover), inner width 3 m, arms 3 m deep.
  AddCulDeSac(&g, {6.0, 0.0}, {-1.0, 0.0}, 3.0, 3.0, 0.3, 0.8);
  EXPECT_NEAR(g.Height(6.0, 0.0), 0.8, 1e-6);   // base
  EXPECT_NEAR(g.Height(4.5, 1.65), 0.8, 1e-6);  // left arm
  EXPECT_NEAR(g.Height(4.5, -1.65), 0.8, 1e-6); // right arm
  EXPECT_NEAR(g.Height(4.5, 0.0), 0.0, 1e-6);   // inside
  EXPECT_NEAR(g.Height(2.5, 0.0), 0.0, 1e-6);   // in front of the mouth
  EXPECT_NEAR(g.Height(6.0, 2.5), 0.0, 1e-6);   // beside the base: open
  EXPECT_NEAR(g.Height(6.0, 1.65), 0.8, 1e-6);  // corner: raised once, not twice
}

TEST(Scenes, RockFieldsAreSeeded) {
  const sim::terrain::Terrain a = RockField(0.15, 3, 12.0);
  const sim::terrain::Terrain b = RockField(0.15, 3, 12.0);
  const sim::terrain::Terrain c = RockField(0.15, 4, 12.0);
  EXPECT_EQ(a.natural.heights(), b.natural.heights());
  EXPECT_NE(a.natural.heights(), c.natural.heights());
  EXPECT_GT(a.rocks.size(), 50u);
  for (const sim::terrain::Rock& r : a.rocks) {
    EXPECT_GT(r.position.head<2>().norm() - r.diameter / 2, 1.5 - 1e-9);  // keep-out disc
  }
}

TEST(Scenes, SampledElevationAndClassMaps) {
  const sim::terrain::HeightField g =
      HeightFieldOf(0, 0, 1, 1, 0.01, [](double x, double) { return x; });
  GridGeometry geo;
  geo.cell = 0.1;
  geo.width = 5;
  geo.height = 3;
  const ElevationMap m = SampledElevation(g, geo);
  EXPECT_NEAR(m.mean.at(2, 1), 0.25, 1e-6);
  EXPECT_EQ(m.measured, 15);
  TraversabilityMap t = ClassMap(-1.0, 0.0, 1.0, 1.0, 0.1, CellClass::kSafe);
  EXPECT_EQ(t.geometry.width, 20);
  EXPECT_EQ(t.geometry.height, 10);
  Paint(&t, {0.0, 0.0}, {0.0, 1.0}, 0.06, CellClass::kStep);
  EXPECT_EQ(t.ClassAt(0.04, 0.5), CellClass::kStep);
  EXPECT_EQ(t.ClassAt(-0.04, 0.5), CellClass::kStep);
  EXPECT_EQ(t.ClassAt(0.16, 0.5), CellClass::kSafe);
  EXPECT_EQ(t.ClassAt(5.0, 0.5), CellClass::kMissing);
  const std::vector<int> n = t.ClassCounts();
  EXPECT_EQ(n[static_cast<int>(CellClass::kStep)], 20);
}

}  // namespace
}  // namespace rover::apl::roaman::testing
