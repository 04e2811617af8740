#include "rover/sim/terrain/top_down_map.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "rover/sim/terrain/terrain.hpp"

namespace rover::sim::terrain {
namespace {

using ::testing::HasSubstr;

Terrain Make(RockPreset preset) {
  TerrainParams p;
  p.size_x = 20;
  p.size_y = 24;
  p.seed = 31;
  p.rocks.preset = preset;
  auto t = GenerateTerrain(p);
  EXPECT_TRUE(t.ok());
  return std::move(t).value();
}

bool IsRed(MapColor c) { return c.r > 200 && c.g < 60 && c.b < 60; }

TEST(TopDownMap, SizeOrientationAndLayers) {
  Terrain t = Make(RockPreset::kVl2);
  ASSERT_TRUE(PlaceLander(&t, {.x = 4, .y = 5, .yaw_deg = 0}).ok());
  MapOptions o;
  o.draw_legend = false;
  o.polylines.push_back({.points = {{-8, -10}, {-8, 10}}, .color = {0, 255, 0}, .label = "path"});
  auto img = RenderTopDownMap(t, o);
  ASSERT_TRUE(img.ok()) << img.status().ToString();
  EXPECT_EQ(img->width, 601);   // 24 m at 25 px/m
  EXPECT_EQ(img->height, 501);  // 20 m
  // North up, west left: (max_x, max_y) is the top-left pixel.
  EXPECT_NEAR(img->ToPixel(10, 12).norm(), 0.0, 1e-9);
  // The polyline is drawn in its colour.
  const Eigen::Vector2d mid = img->ToPixel(-8, 3);
  const MapColor c = img->At(static_cast<int>(mid.x()), static_cast<int>(mid.y()));
  EXPECT_EQ(c.g, 255);
  EXPECT_EQ(c.r, 0);
  // Stripes are dark on the light ramp.
  const LanderStripe& st = t.lander->ramps[0].stripes[5];  // the widest (7 units)
  const Eigen::Vector2d sp = img->ToPixel(st.center.x(), st.center.y());
  EXPECT_LT(img->At(static_cast<int>(std::lround(sp.x())), static_cast<int>(std::lround(sp.y()))).r,
            40);
  // A VL-2 field has rocks above 0.2 m: outlined in red. Without rocks there is no red.
  std::size_t red = 0;
  for (int r = 0; r < img->height; ++r) {
    for (int col = 0; col < img->width; ++col) red += IsRed(img->At(col, r));
  }
  EXPECT_GT(red, 100u);
  auto none = RenderTopDownMap(Make(RockPreset::kNone), o);
  ASSERT_TRUE(none.ok());
  red = 0;
  for (int r = 0; r < none->height; ++r) {
    for (int col = 0; col < none->width; ++col) red += IsRed(none->At(col, r));
  }
  EXPECT_EQ(red, 0u);
}

TEST(TopDownMap, LimitsSizeAndWritesPng) {
  Terrain t = Make(RockPreset::kVl1);
  MapOptions o;
  o.max_pixels = 300;
  o.title = "VL-1 test";
  auto img = RenderTopDownMap(t, o);
  ASSERT_TRUE(img.ok());
  EXPECT_LE(std::max(img->map_width, img->map_height), 300);  // the map; title and legend beside
  const std::string path =
      (std::filesystem::temp_directory_path() / "sim_terrain_map_test.png").string();
  ASSERT_TRUE(WriteTopDownMap(t, path, o).ok());
  EXPECT_GT(std::filesystem::file_size(path), 1000u);
  std::filesystem::remove(path);
  const Status s = WriteTopDownMap(t, "/nonexistent-dir/x.png", o);
  EXPECT_EQ(s.code(), StatusCode::kUnavailable);
  EXPECT_THAT(s.message(), HasSubstr("/nonexistent-dir/x.png"));
  o.max_pixels = 2;
  EXPECT_THAT(RenderTopDownMap(t, o).status().message(), HasSubstr("max_pixels"));
}

// The title sits in a band above the map and the legend in a panel to its right: neither covers
// the map, and a title longer than the image is wrapped, not cut ("FAIL autor").
TEST(TopDownMap, TitleAndLegendAreBesideTheMapAndTheTitleWraps) {
  Terrain t = Make(RockPreset::kVl1);
  MapOptions o;
  o.max_pixels = 240;
  o.draw_legend = false;
  auto bare = RenderTopDownMap(t, o);
  ASSERT_TRUE(bare.ok());
  EXPECT_EQ(bare->width, bare->map_width);
  EXPECT_EQ(bare->height, bare->map_height);
  o.draw_legend = true;
  o.title = "short-autonav-q20 seed 1  FAIL  autonav: NOPATH (goal error) after a long wander";
  auto img = RenderTopDownMap(t, o);
  ASSERT_TRUE(img.ok());
  EXPECT_EQ(img->map_width, bare->map_width);
  EXPECT_EQ(img->map_col0, 0);
  o.title = "short";
  auto one_line = RenderTopDownMap(t, o);
  ASSERT_TRUE(one_line.ok());
  EXPECT_GT(one_line->map_row0, 0);
  EXPECT_GT(img->map_row0, one_line->map_row0 + 10);  // the long title took two lines or more
  EXPECT_GT(img->width, img->map_width + 100);    // the legend panel
  // The map's pixels are the bare map's, shifted below the band: nothing drawn over them.
  int differ = 0;
  for (int r = 0; r < bare->height; r += 3) {
    for (int c = 0; c < bare->width; c += 3) {
      const MapColor a = bare->At(c, r), b = img->At(c, r + img->map_row0);
      differ += a.r != b.r || a.g != b.g || a.b != b.b;
    }
  }
  EXPECT_EQ(differ, 0);
  // Site-frame points map into the map region.
  const Eigen::Vector2d px = img->ToPixel(img->max_x, img->max_y);
  EXPECT_DOUBLE_EQ(px.y(), img->map_row0);
}

}  // namespace
}  // namespace rover::sim::terrain
