#include "src/terrain_mesh.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::sim::render::internal {

using terrain::HeightField;

namespace {

HeightField Plane(int n, double res, double a, double b) {
  HeightField hf(n, n, res, Eigen::Vector2d(-1, -2));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) hf.at(i, j) = static_cast<float>(a * i * res + b * j * res);
  return hf;
}

TEST(TerrainMeshTest, LodSamplesIncludeEnds) {
  EXPECT_EQ(LodSamples(0, 8, 4), (std::vector<int>{0, 4, 8}));
  EXPECT_EQ(LodSamples(64, 98, 16), (std::vector<int>{64, 80, 96, 98}));
}

TEST(TerrainMeshTest, TilesCoverGridAndIndicesStayInTheirBlock) {
  const HeightField hf = Plane(101, 0.04, 0.1, -0.2);
  const TerrainMesh m = BuildTerrainMesh(hf, 32, Eigen::Vector3d(1, 2, 0));
  EXPECT_EQ(m.tiles_x, 4);  // 100 cells / 32 -> 4 tiles (the last 4 cells wide)
  EXPECT_EQ(m.tiles.size(), 16u);
  EXPECT_EQ(m.tiles.back().i1, 100);
  EXPECT_EQ(m.tiles[0].lods.size(), 6u);  // steps 1..32
  for (const auto& t : m.tiles) {
    for (const auto& l : t.lods) {
      for (std::uint32_t k = 0; k < l.index_count; ++k) {
        ASSERT_LT(m.indices[l.first_index + k], t.vertex_count);
      }
    }
  }
  // Render coordinates = site - origin.
  EXPECT_FLOAT_EQ(m.vertices[0], -1.0F - 1.0F);
  EXPECT_FLOAT_EQ(m.vertices[1], -2.0F - 2.0F);
}

TEST(TerrainMeshTest, PlaneIsExactAtEveryLod) {
  const TerrainMesh m = BuildTerrainMesh(Plane(65, 0.04, 0.3, 0.1), 64, Eigen::Vector3d::Zero());
  for (const auto& l : m.tiles[0].lods) EXPECT_LT(l.max_error, 1e-5F);
}

TEST(TerrainMeshTest, BumpErrorGrowsWithLodAndSkirtsCoverIt) {
  HeightField hf(129, 129, 0.04);
  for (int j = 0; j < 129; ++j)
    for (int i = 0; i < 129; ++i)
      hf.at(i, j) = static_cast<float>(0.2 * std::sin(i * 0.3) * std::cos(j * 0.2));
  const TerrainMesh m = BuildTerrainMesh(hf, 64, Eigen::Vector3d::Zero());
  const auto& lods = m.tiles[0].lods;
  EXPECT_EQ(lods[0].max_error, 0.0F);
  for (std::size_t l = 1; l < lods.size(); ++l) {
    EXPECT_GE(lods[l].max_error + 1e-6F, lods[l - 1].max_error * 0.5F);
    EXPECT_GE(lods[l].skirt_depth, lods[l].max_error + 0.02F - 1e-6F);
  }
  EXPECT_GT(lods.back().max_error, 0.1F);
  // Near camera: full resolution; far camera: coarser.
  const Eigen::Vector3f near(1.0F, 1.0F, 1.0F), far(300.0F, 0.0F, 10.0F);
  EXPECT_EQ(SelectLod(m.tiles[0], near, 500.0, 0.04, 1.0, 12.0), 0);
  EXPECT_GT(SelectLod(m.tiles[0], far, 500.0, 0.04, 1.0, 12.0), 0);
}

}  // namespace
}  // namespace rover::sim::render::internal
