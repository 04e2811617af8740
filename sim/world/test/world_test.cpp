#include "rover/sim/world/world.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::sim::world {
namespace {

TEST(World, SameParametersSameWorld) {
  const std::string text =
      "task: ignored\nterrain: {size_x: 20, size_y: 16, resolution: 0.05, seed: 11, "
      "rocks: {preset: vl2}}\nrover: {start: {x: 2, y: -1, yaw_deg: 90}}\n";
  ParamSet a("sim"), b("sim");
  DeclareWorldParams(a);
  DeclareWorldParams(b);
  ASSERT_TRUE(a.LoadYamlSections(text, "s.yaml", WorldSections()).ok());
  ASSERT_TRUE(b.LoadYamlSections(text, "s.yaml", WorldSections()).ok());
  auto wa = BuildWorld(a);
  auto wb = BuildWorld(b);
  ASSERT_TRUE(wa.ok()) << wa.status().message();
  ASSERT_TRUE(wb.ok());
  EXPECT_EQ(wa->start_x, 2);
  EXPECT_EQ(wa->start_y, -1);
  EXPECT_NEAR(wa->start_yaw, M_PI / 2, 1e-12);
  ASSERT_FALSE(wa->terrain.rocks.empty());
  ASSERT_EQ(wa->terrain.rocks.size(), wb->terrain.rocks.size());
  EXPECT_EQ(wa->terrain.rocks[0].position, wb->terrain.rocks[0].position);
  EXPECT_EQ(wa->terrain.ground.heights(), wb->terrain.ground.heights());
}

TEST(World, TheStartBelongsToTheRoverSection) {
  ParamSet p("sim");
  DeclareWorldParams(p);
  ASSERT_TRUE(p.LoadYamlSections("terrain:\n  start: {x: 3}\n", "s.yaml", WorldSections()).ok());
  auto w = BuildWorld(p);
  ASSERT_FALSE(w.ok());
  EXPECT_EQ(w.status().message(), "s.yaml:2: key 'terrain.start.x': set the start with rover.start.x instead");
}

TEST(World, ErrorsNameTheKeyAndLine) {
  ParamSet p("sim");
  DeclareWorldParams(p);
  ASSERT_TRUE(p.LoadYamlSections("lander:\n  enabled: true\n  x: 500\n", "s.yaml", WorldSections()).ok());
  auto w = BuildWorld(p);
  ASSERT_FALSE(w.ok());
  EXPECT_NE(w.status().message().find("s.yaml:3"), std::string::npos) << w.status().message();
  EXPECT_NE(w.status().message().find("lander.x"), std::string::npos) << w.status().message();
}

}  // namespace
}  // namespace rover::sim::world
