#include "rover/sim/terrain/lander.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <set>

#include "rover/sim/terrain/terrain.hpp"

namespace rover::sim::terrain {
namespace {

using ::testing::HasSubstr;

Terrain MakeLanderTerrain(RockPreset preset = RockPreset::kVl2) {
  TerrainParams p;
  p.size_x = 30;
  p.size_y = 30;
  p.seed = 12;
  p.rocks.preset = preset;
  auto t = GenerateTerrain(p);
  EXPECT_TRUE(t.ok()) << t.status().ToString();
  return std::move(t).value();
}

LanderParams At(double x, double y, double yaw_deg) {
  LanderParams l;
  l.x = x;
  l.y = y;
  l.yaw_deg = yaw_deg;
  return l;
}

TEST(Lander, StripeCodesIdentifyEveryStripeAndRamp) {
  // Widths unique within a ramp; ordered neighbour pairs unique over both ramps (and never the
  // reverse of another ramp's pair, so reading a ramp the wrong way round is detectable).
  std::set<std::pair<int, int>> pairs;
  for (const auto& codes : kRampStripeCodes) {
    EXPECT_EQ(std::set<int>(codes.begin(), codes.end()).size(), 6u);
    for (std::size_t i = 0; i + 1 < codes.size(); ++i) {
      EXPECT_TRUE(pairs.insert({codes[i], codes[i + 1]}).second);
    }
  }
  for (const auto& [a, b] : pairs) EXPECT_EQ(pairs.count({b, a}), 0u) << a << "," << b;
}

TEST(Lander, GeometryAndHeightfield) {
  Terrain t = MakeLanderTerrain();
  ASSERT_TRUE(PlaceLander(&t, At(6.0, -5.0, 30.0)).ok());
  ASSERT_TRUE(t.lander.has_value());
  const Lander& l = *t.lander;
  EXPECT_NEAR(l.deck_z - t.bare.Height(6.0, -5.0), 1.0, 1e-9);

  // Deck block in the physics heightfield; natural terrain untouched; hard soil.
  EXPECT_NEAR(t.ground.Height(6.0, -5.0), l.deck_z, 1e-5);
  EXPECT_NEAR(t.natural.Height(6.0, -5.0), t.bare.Height(6.0, -5.0), 0.5);
  EXPECT_EQ(t.ground.SoilAt(6.0, -5.0), Soil::kBedrock);

  // Ramps: ramp 0 descends along yaw; surface linear from the deck to the ground.
  const double yaw = 30.0 * std::numbers::pi / 180.0;
  EXPECT_NEAR(l.ramps[0].direction.x(), std::cos(yaw), 1e-12);
  EXPECT_NEAR(l.ramps[1].direction.x(), -std::cos(yaw), 1e-12);
  for (const LanderRamp& r : l.ramps) {
    EXPECT_NEAR(r.top_center.z(), l.deck_z, 1e-12);
    EXPECT_NEAR(r.SlopeDeg(), std::atan2(1.0, 3.0) * 180 / std::numbers::pi, 6.0);
    const Eigen::Vector3d mid = 0.5 * (r.top_center + r.bottom_center);
    EXPECT_NEAR(t.ground.Height(mid.x(), mid.y()), mid.z(), 0.01);
    // Stripes on the ramp surface, ordered bottom to top, widths from the code.
    for (std::size_t s = 0; s < 6; ++s) {
      const LanderStripe& st = r.stripes[s];
      double z = 0;
      EXPECT_EQ(l.RampAt(st.center.x(), st.center.y(), &z), st.ramp);
      EXPECT_NEAR(z, st.center.z(), 1e-9);
      EXPECT_DOUBLE_EQ(st.width, st.code * 0.03);
      if (s > 0) {
        EXPECT_GT(st.center.z(), r.stripes[s - 1].center.z());
      }
    }
  }

  // Renderer geometry: planar quads with unit normals; 12 stripes facing up.
  int stripes = 0;
  for (const LanderQuad& q : l.quads) {
    const Eigen::Vector3d n = q.Normal();
    EXPECT_NEAR(n.norm(), 1.0, 1e-9);
    EXPECT_NEAR((q.corners[3] - q.corners[0]).dot(n), 0.0, 1e-9);
    if (q.part == LanderPart::kStripe) {
      ++stripes;
      EXPECT_GT(n.z(), 0.9);
      EXPECT_NEAR(q.albedo.x(), 0.05, 1e-12);
    }
  }
  EXPECT_EQ(stripes, 12);

  // No generated rock left on or near the footprint.
  for (const Rock& r : t.rocks) {
    EXPECT_GE(l.DistanceToFootprint(r.position.x(), r.position.y()),
              RockBoundingRadius(r) + l.params.rock_clearance - 1e-9);
  }
}

TEST(Lander, OnlyTheRampsLeadOntoTheDeck) {
  Terrain t = MakeLanderTerrain(RockPreset::kNone);
  ASSERT_TRUE(PlaceLander(&t, At(-4.0, 3.0, -75.0)).ok());
  const Lander& l = *t.lander;
  // Around the deck, off the ramps, the edge is a wall of about the deck height.
  int wall = 0;
  for (int k = 0; k < 360; ++k) {
    const double a = k * std::numbers::pi / 180.0;
    const double r_out = l.params.deck_radius + 0.1;
    const double x = -4.0 + r_out * std::cos(a), y = 3.0 + r_out * std::sin(a);
    // Skip points whose bilinear cell touches a ramp (its sides are drop-offs, not walls).
    bool near_ramp = false;
    for (double dx : {-0.06, 0.0, 0.06}) {
      for (double dy : {-0.06, 0.0, 0.06}) near_ramp |= l.RampAt(x + dx, y + dy, nullptr) >= 0;
    }
    if (near_ramp || l.InDeck(x, y)) continue;
    EXPECT_GT(l.deck_z - t.ground.Height(x, y), 0.8) << k;
    ++wall;
  }
  EXPECT_GT(wall, 200);
  // Up a ramp's centre line the ground rises smoothly: no step above 1.5 cm per cm.
  for (const LanderRamp& r : l.ramps) {
    double prev = t.ground.Height(r.bottom_center.x() + 0.3 * r.direction.x(),
                                  r.bottom_center.y() + 0.3 * r.direction.y());
    const Eigen::Vector2d from = r.bottom_center.head<2>() + 0.3 * r.direction;
    const Eigen::Vector2d to = r.top_center.head<2>() - 0.5 * r.direction;
    const int steps = static_cast<int>((to - from).norm() / 0.01);
    double max_step = 0;
    for (int s = 1; s <= steps; ++s) {
      const Eigen::Vector2d q = from + (to - from) * s / steps;
      const double z = t.ground.Height(q.x(), q.y());
      max_step = std::max(max_step, std::abs(z - prev));
      prev = z;
    }
    EXPECT_LT(max_step, 0.015);
    EXPECT_NEAR(prev, l.deck_z, 0.01);
  }
}

TEST(Lander, ErrorsNameTheField) {
  Terrain t = MakeLanderTerrain(RockPreset::kVl1);
  Status s = PlaceLander(&t, At(14.0, 0.0, 0.0));  // ramps reach 5.8 m out; map is +-15 m
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_THAT(s.message(), HasSubstr("lander.x"));
  s = PlaceLander(&t, At(0.0, -40.0, 90.0));
  EXPECT_THAT(s.message(), HasSubstr("lander.y"));
  LanderParams wide = At(0, 0, 0);
  wide.ramp_width = 2.0;  // wider than the 1.5 m deck edge
  EXPECT_THAT(PlaceLander(&t, wide).message(), HasSubstr("lander.ramp_width"));
  EXPECT_FALSE(t.lander.has_value());
  ASSERT_TRUE(PlaceLander(&t, At(5.0, 5.0, 0.0)).ok());
  EXPECT_EQ(PlaceLander(&t, At(-5.0, -5.0, 0.0)).code(), StatusCode::kFailedPrecondition);
}

TEST(ScienceTarget, IsARockInTheHeightfield) {
  Terrain t = MakeLanderTerrain();
  auto id = AddScienceTarget(&t, {.x = -7.0, .y = 8.0, .diameter = 0.5, .texture_id = 3});
  ASSERT_TRUE(id.ok()) << id.status().ToString();
  const Rock* r = t.FindRock(*id);
  ASSERT_NE(r, nullptr);
  EXPECT_TRUE(r->science_target);
  EXPECT_EQ(r->texture_id, 3);
  EXPECT_DOUBLE_EQ(r->height, 0.25);  // height_ratio 0.5 * diameter
  EXPECT_NEAR(t.ground.Height(-7.0, 8.0) - r->position.z(), 0.25, 0.005);
  for (const Rock& o : t.rocks) {
    if (o.id == *id) continue;
    EXPECT_GE((o.position - r->position).head<2>().norm(),
              RockBoundingRadius(o) + RockBoundingRadius(*r));
  }
  // Errors name the field.
  auto off = AddScienceTarget(&t, {.x = 15.0, .y = 0.0, .diameter = 0.4});
  ASSERT_FALSE(off.ok());
  EXPECT_THAT(off.status().message(), HasSubstr("science_target.x"));
  off = AddScienceTarget(&t, {.x = 0.0, .y = -14.9, .diameter = 0.4});
  EXPECT_THAT(off.status().message(), HasSubstr("science_target.y"));
  EXPECT_THAT(AddScienceTarget(&t, {.x = 0, .y = 0, .diameter = -1}).status().message(),
              HasSubstr("science_target.diameter"));
  EXPECT_FALSE(AddScienceTarget(&t, {.x = -7.1, .y = 8.0, .diameter = 0.3}).ok());  // overlap
  // A lander on top of a target is refused; a target on the lander too.
  EXPECT_THAT(PlaceLander(&t, At(-7.0, 8.0, 0.0)).message(), HasSubstr("science target"));
  ASSERT_TRUE(PlaceLander(&t, At(5.0, 0.0, 0.0)).ok());
  EXPECT_THAT(AddScienceTarget(&t, {.x = 5.0, .y = 0.5, .diameter = 0.3}).status().message(),
              HasSubstr("lander"));
}

TEST(ScenarioObjects, FromYamlWithFileLineErrors) {
  ParamSet ps("sim");
  DeclareLanderParams(ps);
  DeclareScienceTargets(ps);
  ASSERT_TRUE(ps.LoadYamlString("lander:\n  enabled: true\n  x: 4\n  y: 2\n  yaw_deg: 10\n"
                                "science_targets: [-6, 6, 0.4, 1, -9, -9, 0.3, 2]\n",
                                "scn.yaml")
                  .ok());
  Terrain t = MakeLanderTerrain(RockPreset::kVl1);
  ASSERT_TRUE(PlaceScenarioObjects(&t, ps).ok());
  EXPECT_TRUE(t.lander.has_value());
  int targets = 0;
  for (const Rock& r : t.rocks) targets += r.science_target;
  EXPECT_EQ(targets, 2);

  ParamSet bad("sim");
  DeclareLanderParams(bad);
  DeclareScienceTargets(bad);
  ASSERT_TRUE(bad.LoadYamlString("lander:\n  enabled: true\n  x: 40\n", "bad.yaml").ok());
  Terrain t2 = MakeLanderTerrain(RockPreset::kNone);
  const Status s = PlaceScenarioObjects(&t2, bad);
  EXPECT_THAT(s.message(), HasSubstr("bad.yaml:3: key 'lander.x'"));

  ParamSet odd("sim");
  DeclareLanderParams(odd);
  DeclareScienceTargets(odd);
  ASSERT_TRUE(odd.LoadYamlString("science_targets: [1, 2, 0.3]\n", "odd.yaml").ok());
  EXPECT_THAT(PlaceScenarioObjects(&t2, odd).message(), HasSubstr("odd.yaml:1"));
}

}  // namespace
}  // namespace rover::sim::terrain
