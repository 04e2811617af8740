#include "rover/sim/terrain/features.hpp"

#include <cmath>
#include <numbers>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "rover/sim/terrain/terrain.hpp"

namespace rover::sim::terrain {
namespace {

using ::testing::HasSubstr;

Terrain MakeTerrain(RockPreset preset, std::uint64_t seed = 5) {
  TerrainParams p;
  p.size_x = 30;
  p.size_y = 30;
  p.resolution = 0.05;
  p.seed = seed;
  p.rocks.preset = preset;
  auto t = GenerateTerrain(p);
  EXPECT_TRUE(t.ok()) << t.status().ToString();
  return std::move(t).value();
}

std::vector<const Rock*> Placed(const Terrain& t) {
  std::vector<const Rock*> out;
  for (const Rock& r : t.rocks) {
    if (r.placed) out.push_back(&r);
  }
  return out;
}

TEST(TerrainFeatures, APlacedRockStandsWhereItIsToldAndClearsItsFootprint) {
  Terrain t = MakeTerrain(RockPreset::kVl2);
  const int before_id = t.next_rock_id;
  ASSERT_TRUE(PlaceFeatures(&t, {{{8.0, 1.0, 1.2, 0.6}}, {}, {}}).ok());
  const auto placed = Placed(t);
  ASSERT_EQ(placed.size(), 1u);
  EXPECT_EQ(placed[0]->id, before_id);
  EXPECT_DOUBLE_EQ(placed[0]->height, 0.6);
  // The heightfield has the rock: ~0.6 m above the bare ground at its centre.
  EXPECT_NEAR(t.natural.Height(8.0, 1.0) - t.bare.Height(8.0, 1.0), 0.6, 0.05);
  // No generated rock overlaps it.
  for (const Rock& r : t.rocks) {
    if (r.placed) continue;
    EXPECT_GE((r.position.head<2>() - Eigen::Vector2d(8, 1)).norm(),
              RockBoundingRadius(*placed[0]) + RockBoundingRadius(r) - 1e-9);
  }
}

TEST(TerrainFeatures, AWallHasNoGapAndIsTheSameForTheSameSeed) {
  const TerrainFeatures f{{}, {{{10, -5}, {10, 5}, 0.5, 0.4}}, {}};
  Terrain a = MakeTerrain(RockPreset::kNone, 3), b = MakeTerrain(RockPreset::kNone, 3);
  ASSERT_TRUE(PlaceFeatures(&a, f).ok());
  ASSERT_TRUE(PlaceFeatures(&b, f).ok());
  const auto wa = Placed(a), wb = Placed(b);
  ASSERT_GE(wa.size(), 30u);  // 10 m at 0.3 m spacing
  ASSERT_EQ(wa.size(), wb.size());
  for (std::size_t i = 0; i < wa.size(); ++i) {
    EXPECT_EQ(wa[i]->position, wb[i]->position);
    EXPECT_EQ(wa[i]->diameter, wb[i]->diameter);
    EXPECT_EQ(wa[i]->height, wb[i]->height);
  }
  // Along the wall the ground stands well above the bare surface everywhere: no gap for a
  // 1 m wide rover (and for nothing 10 cm wide).
  for (double y = -4.9; y <= 4.9; y += 0.1) {
    EXPECT_GT(a.natural.Height(10.0, y) - a.bare.Height(10.0, y), 0.2) << "gap at y = " << y;
  }
  // Another seed jitters the rocks differently.
  Terrain c = MakeTerrain(RockPreset::kNone, 4);
  ASSERT_TRUE(PlaceFeatures(&c, f).ok());
  EXPECT_NE(Placed(c)[0]->diameter, wa[0]->diameter);
}

TEST(TerrainFeatures, BadFeaturesAreErrorsNamingTheFieldAndValue) {
  Terrain t = MakeTerrain(RockPreset::kNone);
  EXPECT_EQ(PlaceFeatures(&t, {{{8, 1, 40, 0}}, {}, {}}).message(),
            "rocks[0].diameter: 40 is out of range [0.1, 10]");
  EXPECT_EQ(PlaceFeatures(&t, {{}, {{{5, 0}, {6, 0}, 0.5, -1}}, {}}).message(),
            "walls[0].height: -1 is out of range [0, 5]");
  EXPECT_THAT(PlaceFeatures(&t, {{{40, 1, 1, 0}}, {}, {}}).message(),
              HasSubstr("rocks[0]: the rock at (40, 1) (radius 0.5) is off the map"));
  // The rover's start disc (2 m about the origin by default) stays free.
  EXPECT_THAT(PlaceFeatures(&t, {{{1, 0, 0.5, 0}}, {}, {}}).message(),
              HasSubstr("rocks[0]: the rock at (1, 0) is on the rover's rock-free start disc"));
  EXPECT_THAT(PlaceFeatures(&t, {{}, {{{5, 0}, {5.2, 0}, 0.5, 0}}, {}}).message(),
              HasSubstr("walls[0]: the wall is 0.2 m long"));
}

TEST(TerrainFeatures, FromAScenarioWithFileLineErrors) {
  ParamSet ps("sim");
  DeclareTerrainFeatures(ps);
  ASSERT_TRUE(ps.LoadYamlString("terrain_features:\n  rocks: [8, 1, 1.2, 0.6]\n"
                                "  walls: [12, -3, 12, 3, 0.5, 0]\n",
                                "scn.yaml")
                  .ok());
  Terrain t = MakeTerrain(RockPreset::kVl1);
  ASSERT_TRUE(PlaceScenarioFeatures(&t, ps).ok());
  EXPECT_GT(Placed(t).size(), 10u);

  ParamSet odd("sim");
  DeclareTerrainFeatures(odd);
  ASSERT_TRUE(odd.LoadYamlString("terrain_features:\n  walls: [1, 2, 3]\n", "odd.yaml").ok());
  EXPECT_THAT(PlaceScenarioFeatures(&t, odd).message(),
              HasSubstr("odd.yaml:2: key 'terrain_features.walls': 3 numbers is not a multiple "
                        "of 6"));
  ParamSet big("sim");
  DeclareTerrainFeatures(big);
  ASSERT_TRUE(big.LoadYamlString("terrain_features:\n\n  walls: [5, 0, 8, 0, 9, 0]\n", "big.yaml")
                  .ok());
  EXPECT_THAT(PlaceScenarioFeatures(&t, big).message(),
              HasSubstr("big.yaml:3: key 'terrain_features.walls': walls[0].diameter: 9"));
}

TEST(TerrainFeatures, AnOutcropIsSteppedBedsWithLevelTopsAndAnOutlineOnItsFootprint) {
  TerrainFeatures f;
  f.outcrops.push_back({10.0, 2.0, 4.0, 1.5, 0.9, 30.0});
  Terrain t = MakeTerrain(RockPreset::kVl1, 3);
  ASSERT_TRUE(PlaceFeatures(&t, f).ok());
  const auto placed = Placed(t);
  ASSERT_EQ(placed.size(), 1u);
  const Rock& o = *placed[0];
  EXPECT_EQ(o.layers, 3);  // 0.9 m of ~0.3 m beds
  // Top bed at the centre, nothing just outside the long side, one bed just inside it.
  EXPECT_DOUBLE_EQ(RockRelief(o, 10.0, 2.0), 0.9);
  const Eigen::Vector2d along(std::cos(30.0 * std::numbers::pi / 180), std::sin(30.0 * std::numbers::pi / 180));
  const Eigen::Vector2d across(-along.y(), along.x());
  const Eigen::Vector2d c(10.0, 2.0);
  const Eigen::Vector2d in = c + 0.74 * across, out = c + 0.76 * across;
  EXPECT_DOUBLE_EQ(RockRelief(o, in.x(), in.y()), 0.3);
  EXPECT_EQ(RockRelief(o, out.x(), out.y()), 0.0);
  EXPECT_EQ(RockRelief(o, (c + 2.01 * along).x(), (c + 2.01 * along).y()), 0.0);
  // Level tops: the relief is constant along the long side within a bed.
  const Eigen::Vector2d p1 = c + 0.7 * across + 1.0 * along, p2 = c + 0.7 * across - 1.0 * along;
  EXPECT_EQ(RockRelief(o, p1.x(), p1.y()), RockRelief(o, p2.x(), p2.y()));
  // The outline lies on the rectangle and within the bounding radius.
  for (const Eigen::Vector2d& p : RockOutline(o, 24)) {
    const Eigen::Vector2d d = p - c;
    const double u = std::abs(d.dot(along)), v = std::abs(d.dot(across));
    EXPECT_NEAR(std::max(u / 2.0, v / 0.75), 1.0, 1e-9);
    EXPECT_LE(d.norm(), RockBoundingRadius(o) + 1e-9);
  }
  // The heightfield carries it.
  EXPECT_NEAR(t.natural.Height(10.0, 2.0) - t.bare.Height(10.0, 2.0), 0.9, 0.02);
}

TEST(TerrainFeatures, AnOutcropOutOfRangeIsNamedByItsField) {
  Terrain t = MakeTerrain(RockPreset::kNone, 3);
  TerrainFeatures f;
  f.outcrops.push_back({10.0, 2.0, 4.0, 5.0, 0.9, 0.0});
  const Status s = PlaceFeatures(&t, f);
  EXPECT_THAT(s.message(), HasSubstr("outcrops[0].depth: 5 is out of range"));
  f.outcrops[0] = {10.0, 2.0, 4.0, 1.0, 9.0, 0.0};
  EXPECT_THAT(PlaceFeatures(&t, f).message(), HasSubstr("outcrops[0].height: 9"));
}

}  // namespace
}  // namespace rover::sim::terrain
