#include "rover/sim/terrain/terrain_params.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace rover::sim::terrain {
namespace {

using ::testing::HasSubstr;

TEST(TerrainParams, DefaultsAreValidAndPresetsHaveTheirK) {
  EXPECT_TRUE(TerrainParams{}.Validate().ok()) << TerrainParams{}.Validate().ToString();
  EXPECT_DOUBLE_EQ(RockPresetK(RockPreset::kNone), 0.0);
  EXPECT_NEAR(RockPresetK(RockPreset::kVl1), 0.07, 0.005);
  EXPECT_GE(RockPresetK(RockPreset::kVl2), 0.14);
  EXPECT_LE(RockPresetK(RockPreset::kVl2), 0.18);
  EXPECT_GT(RockPresetK(RockPreset::kImpassable), RockPresetK(RockPreset::kVl2));
  RockParams r;
  r.preset = RockPreset::kCustom;
  r.k = 0.123;
  EXPECT_DOUBLE_EQ(r.EffectiveK(), 0.123);
  EXPECT_EQ(*ParseRockPreset("vl2"), RockPreset::kVl2);
  EXPECT_THAT(ParseRockPreset("vl3").status().message(), HasSubstr("rocks.preset"));
}

TEST(TerrainParams, BadValuesNameTheField) {
  TerrainParams p;
  p.size_x = -5;
  EXPECT_THAT(p.Validate().message(), HasSubstr("size_x"));
  p = {};
  p.resolution = 0.0;
  EXPECT_THAT(p.Validate().message(), HasSubstr("resolution"));
  p = {};
  p.resolution = 0.001;  // 50001^2 cells
  EXPECT_THAT(p.Validate().message(), HasSubstr("coarser resolution"));
  p = {};
  p.slope.angle_deg = 70;
  EXPECT_THAT(p.Validate().message(), HasSubstr("slope.angle_deg"));
  p = {};
  p.craters.diameter_max = 1.0;
  EXPECT_THAT(p.Validate().message(), HasSubstr("craters.diameter_max"));
  p = {};
  p.rocks.diameter_min = 0.05;  // below 2 cells of 4 cm
  EXPECT_THAT(p.Validate().message(), HasSubstr("rocks.diameter_min"));
  p = {};
  p.soil.sand_fraction = 0.7;
  p.soil.bedrock_fraction = 0.5;
  EXPECT_THAT(p.Validate().message(), HasSubstr("soil.bedrock_fraction"));
  p = {};
  p.start.x = 30;  // map is [-25, 25]
  EXPECT_THAT(p.Validate().message(), HasSubstr("start.x"));
}

TEST(TerrainParams, ImpossibleRockDensityIsRejected) {
  TerrainParams p;
  p.rocks.preset = RockPreset::kCustom;
  p.rocks.k = 1.5;  // more than the whole surface
  Status s = p.Validate();
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(s.message(), HasSubstr("rocks.k"));
  EXPECT_THAT(s.message(), HasSubstr("cannot exceed"));
  p.rocks.k = 0.9;  // <= 1, but 74 % cover with D >= 0.1 m cannot be placed without overlap
  s = p.Validate();
  EXPECT_THAT(s.message(), HasSubstr("rocks.k"));
  EXPECT_THAT(s.message(), HasSubstr("cannot be placed"));
  p.rocks.diameter_min = 1.0;  // the same k restricted to big rocks is only 10 % cover
  EXPECT_TRUE(p.Validate().ok()) << p.Validate().ToString();
  p.rocks.k = -0.1;
  EXPECT_THAT(p.Validate().message(), HasSubstr("rocks.k"));
}

TEST(TerrainParams, ParamSetRoundTripsTheDefaults) {
  ParamSet ps("sim");
  DeclareTerrainParams(ps);
  auto p = TerrainParamsFromParamSet(ps);
  ASSERT_TRUE(p.ok()) << p.status().ToString();
  const TerrainParams d;
  EXPECT_EQ(p->size_x, d.size_x);
  EXPECT_EQ(p->resolution, d.resolution);
  EXPECT_EQ(p->seed, d.seed);
  EXPECT_EQ(p->rocks.preset, d.rocks.preset);
  EXPECT_EQ(p->hills.octaves, d.hills.octaves);
  EXPECT_EQ(p->start.keep_out_radius, d.start.keep_out_radius);
}

TEST(TerrainParams, YamlErrorsCarryFileLineAndKey) {
  ParamSet ps("sim");
  DeclareTerrainParams(ps);
  ASSERT_TRUE(ps.LoadYamlString("terrain:\n  size_y: 30\n  size_x: -5\n", "scn.yaml").ok());
  auto p = TerrainParamsFromParamSet(ps);
  ASSERT_FALSE(p.ok());
  EXPECT_THAT(p.status().message(), HasSubstr("scn.yaml:3: key 'terrain.size_x'"));

  ParamSet dense("sim");
  DeclareTerrainParams(dense);
  ASSERT_TRUE(dense.LoadYamlString("terrain:\n  rocks:\n    k: 0.95\n", "dense.yaml").ok());
  p = TerrainParamsFromParamSet(dense);
  ASSERT_FALSE(p.ok());
  EXPECT_THAT(p.status().message(), HasSubstr("dense.yaml:3: key 'terrain.rocks.k'"));
  EXPECT_THAT(p.status().message(), HasSubstr("cannot be placed"));
}

TEST(TerrainParams, KSelectsCustomAndConflictsWithAPreset) {
  ParamSet ps("sim");
  DeclareTerrainParams(ps, "");
  ASSERT_TRUE(ps.LoadYamlString("rocks: {k: 0.12}\nseed: 77\n", "a.yaml").ok());
  auto p = TerrainParamsFromParamSet(ps, "");
  ASSERT_TRUE(p.ok()) << p.status().ToString();
  EXPECT_EQ(p->rocks.preset, RockPreset::kCustom);
  EXPECT_DOUBLE_EQ(p->rocks.EffectiveK(), 0.12);
  EXPECT_EQ(p->seed, 77u);

  ParamSet both("sim");
  DeclareTerrainParams(both, "");
  ASSERT_TRUE(both.LoadYamlString("rocks:\n  preset: vl2\n  k: 0.12\n", "b.yaml").ok());
  p = TerrainParamsFromParamSet(both, "");
  ASSERT_FALSE(p.ok());
  EXPECT_THAT(p.status().message(), HasSubstr("b.yaml:3: key 'rocks.k'"));
  EXPECT_THAT(p.status().message(), HasSubstr("custom"));

  ParamSet bad_preset("sim");
  DeclareTerrainParams(bad_preset, "");
  ASSERT_TRUE(bad_preset.LoadYamlString("rocks:\n  preset: vl9\n", "c.yaml").ok());
  p = TerrainParamsFromParamSet(bad_preset, "");
  ASSERT_FALSE(p.ok());
  EXPECT_THAT(p.status().message(), HasSubstr("c.yaml:2: key 'rocks.preset'"));
}

}  // namespace
}  // namespace rover::sim::terrain
