#include "rover/apl/roaman/site_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace rover::apl::roaman {
namespace {

RoamanOptions SmallMap() {
  RoamanOptions o;
  o.map_size = 4.0;  // 80 x 80 cells
  o.recenter_distance = 1.0;
  o.max_range = 2.0;
  o.plan_width = 3.0;
  o.plan_length = 3.0;
  o.plan_back = 0.5;
  return o;
}

// A one-row scan of rover-frame points (all marked valid) taken at site (x, y), heading 0.
nav_core::RangeScan ScanOf(const std::vector<Eigen::Vector3d>& points, double x, double y) {
  nav_core::RangeScan s;
  s.width = static_cast<int>(points.size());
  s.height = 1;
  for (const Eigen::Vector3d& p : points) {
    s.xyz.push_back(static_cast<float>(p.x()));
    s.xyz.push_back(static_cast<float>(p.y()));
    s.xyz.push_back(static_cast<float>(p.z()));
    s.valid.push_back(1);
  }
  s.site_from_rover.translation() = Eigen::Vector3d(x, y, 0.0);
  s.camera = "navcam";
  return s;
}

TEST(SiteMap, BinsHeightsIntoCellStatistics) {
  SiteMap map(SmallMap());
  ASSERT_TRUE(
      map.AddScan(ScanOf({{0.51, 0.51, 0.1}, {0.52, 0.53, 0.3}, {0.99, 0.0, 0.0}}, 0, 0)).ok());
  // The first scan centres the map on the rover: cell corners at multiples of 5 cm.
  EXPECT_NEAR(map.center().x(), 0.0, 1e-12);
  EXPECT_NEAR(map.geometry().origin_x, -2.0, 1e-12);
  int i = 0, j = 0;
  map.geometry().CellOf(0.51, 0.51, &i, &j);
  const CellStats& c = map.cells().at(i, j);
  EXPECT_EQ(c.count, 2u);
  EXPECT_NEAR(c.mean(), 0.2, 1e-6);
  EXPECT_NEAR(c.variance(), 0.01, 1e-6);
  EXPECT_FLOAT_EQ(c.min, 0.1f);
  EXPECT_FLOAT_EQ(c.max, 0.3f);
  EXPECT_EQ(map.data_cells(), 2u);
  int i0 = 0, j0 = 0, i1 = 0, j1 = 0;
  ASSERT_TRUE(map.DataBounds(&i0, &j0, &i1, &j1));
  EXPECT_EQ(i1 - i0, 9);  // x = 0.51 m and 0.99 m: cells 50 and 59 from the origin at -2 m
}

TEST(SiteMap, SkipsNonFiniteAndFarPointsAndCountsThem) {
  SiteMap map(SmallMap());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto r = map.AddScan(
      ScanOf({{0.5, 0.0, 0.0}, {nan, 0.0, 0.0}, {0.5, 0.0, nan}, {3.0, 0.0, 0.0}}, 0, 0));
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(r->pixels, 4u);
  EXPECT_EQ(r->valid, 4u);
  EXPECT_EQ(r->non_finite, 2u);
  EXPECT_EQ(r->out_of_range, 1u);  // 3 m > max_range 2 m
  EXPECT_EQ(r->used, 1u);
}

TEST(SiteMap, RejectsAScanWithNothingUsableAndNamesWhy) {
  SiteMap map(SmallMap());
  nav_core::RangeScan none = ScanOf({{0.5, 0.0, 0.0}, {0.6, 0.0, 0.0}}, 0, 0);
  none.valid.assign(2, 0);
  auto r = map.AddScan(none);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(r.status().message(),
            "RangeScan 'navcam' has no usable point: 0 of 2 pixels valid, 0 of them non-finite "
            "(NaN/inf), 0 beyond max_range 2 m, 0 off the map");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  r = map.AddScan(ScanOf({{nan, nan, nan}}, 0, 0));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("1 of them non-finite"), std::string::npos);
  EXPECT_EQ(map.data_cells(), 0u);
  EXPECT_EQ(map.revision(), 0u);  // nothing changed

  nav_core::RangeScan bad = ScanOf({{0.5, 0.0, 0.0}}, 0, 0);
  bad.xyz.pop_back();
  r = map.AddScan(bad);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(),
            "RangeScan 'navcam': RangeScan.xyz: 2 floats for 1 x 1 pixels (need 3 = 3 per pixel)");
  nav_core::RangeScan pose = ScanOf({{0.5, 0.0, 0.0}}, nan, 0);
  EXPECT_FALSE(map.AddScan(pose).ok());
}

TEST(SiteMap, RecentresByWholeCellsKeepingDataInPlace) {
  SiteMap map(SmallMap());
  ASSERT_TRUE(map.AddScan(ScanOf({{0.5, 0.5, 0.25}}, 0, 0)).ok());
  // 1.2 m away: beyond recenter_distance 1 m. The point seen first is 1.7 m west of the rover
  // now, still on the 4 m map.
  auto r = map.AddScan(ScanOf({{0.0, 0.0, 0.1}}, -1.2, 0.0));
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r->recentred);
  EXPECT_NEAR(map.center().x(), -1.2, 1e-9);
  int i = 0, j = 0;
  map.geometry().CellOf(0.5, 0.5, &i, &j);
  ASSERT_TRUE(map.geometry().Contains(i, j));
  EXPECT_NEAR(map.cells().at(i, j).mean(), 0.25, 1e-6);
  // Moving 3 m on drops it: it is off the grid.
  ASSERT_TRUE(map.AddScan(ScanOf({{0.0, 0.0, 0.0}}, -4.2, 0.0)).ok());
  map.geometry().CellOf(0.5, 0.5, &i, &j);
  EXPECT_FALSE(map.geometry().Contains(i, j));
  EXPECT_EQ(map.data_cells(), 1u);  // only (-4.2, 0): (-1.2, 0) is off the grid too
}

TEST(SiteMap, ANewPanoramaReplacesOlderDataCellByCell) {
  SiteMap map(SmallMap());
  ASSERT_TRUE(map.AddScan(ScanOf({{0.52, 0.02, 0.4}, {0.52, 0.52, 0.4}}, 0, 0)).ok());
  // Same stand: the same panorama, heights accumulate.
  auto r = map.AddScan(ScanOf({{0.42, 0.02, 0.2}}, 0.1, 0.0));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->panorama, 1);
  int i = 0, j = 0;
  map.geometry().CellOf(0.52, 0.02, &i, &j);
  EXPECT_EQ(map.cells().at(i, j).count, 2u);
  // The rover drove 0.6 m: a new panorama; the cell it sees again is replaced, the other kept.
  r = map.AddScan(ScanOf({{-0.18, 0.02, 0.0}}, 0.7, 0.0));
  ASSERT_TRUE(r.ok());
  EXPECT_EQ(r->panorama, 2);
  map.geometry().CellOf(0.52, 0.02, &i, &j);
  EXPECT_EQ(map.cells().at(i, j).count, 1u);
  EXPECT_NEAR(map.cells().at(i, j).mean(), 0.0, 1e-6);
  map.geometry().CellOf(0.52, 0.52, &i, &j);
  EXPECT_NEAR(map.cells().at(i, j).mean(), 0.4, 1e-6);
  // A replaced cell is still one cell with data.
  EXPECT_EQ(map.data_cells(), 2u);
}

TEST(SiteMap, BlockedCorridorsAreMarkedKeptAcrossRecentringAndChecked) {
  SiteMap map(SmallMap());
  ASSERT_TRUE(map.AddScan(ScanOf({{0.5, 0.0, 0.0}}, 0, 0)).ok());
  auto n = map.MarkBlocked({0.0, -0.5}, {0.0, 0.5}, 0.1);
  ASSERT_TRUE(n.ok());
  // Cells whose centres lie within 0.1 m of the 1 m segment: 4 columns x 20 rows, plus the
  // rounded ends.
  EXPECT_GE(*n, 80);
  EXPECT_LE(*n, 100);
  int i = 0, j = 0;
  map.geometry().CellOf(0.02, 0.3, &i, &j);
  EXPECT_EQ(map.blocked().at(i, j), 1);
  map.geometry().CellOf(0.2, 0.3, &i, &j);
  EXPECT_EQ(map.blocked().at(i, j), 0);
  map.Recenter({-0.73, 0.4});
  map.geometry().CellOf(0.02, 0.3, &i, &j);
  EXPECT_EQ(map.blocked().at(i, j), 1);

  EXPECT_EQ(map.MarkBlocked({std::nan(""), 0.0}, {1.0, 0.0}, 0.1).status().message(),
            "blocked corridor: from = (nan, 0) (must be finite)");
  EXPECT_EQ(map.MarkBlocked({0.0, 0.0}, {1.0, 0.0}, 0.0).status().message(),
            "blocked corridor: half_width = 0 m is outside (0, 4]");
  map.ClearBlocked();
  EXPECT_TRUE(map.corridors().empty());
  map.geometry().CellOf(0.02, 0.3, &i, &j);
  EXPECT_EQ(map.blocked().at(i, j), 0);
  map.Clear();
  EXPECT_EQ(map.data_cells(), 0u);
  EXPECT_FALSE(map.DataBounds(&i, &j, &i, &j));
}

}  // namespace
}  // namespace rover::apl::roaman
