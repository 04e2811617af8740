#include "terrain_mesh.hpp"

#include <algorithm>
#include <cmath>

#include "rover/base/check.hpp"

namespace rover::sim::render::internal {

using terrain::HeightField;

std::vector<int> LodSamples(int lo, int hi, int step) {
  std::vector<int> s;
  for (int i = lo; i < hi; i += step) s.push_back(i);
  s.push_back(hi);
  return s;
}

TerrainMesh BuildTerrainMesh(const HeightField& hf, int tile_cells, const Eigen::Vector3d& origin) {
  ROVER_DEMAND(hf.nx() >= 2 && hf.ny() >= 2);
  ROVER_DEMAND(tile_cells >= 2 && (tile_cells & (tile_cells - 1)) == 0);
  const int nx = hf.nx(), ny = hf.ny();
  const double res = hf.resolution();
  TerrainMesh mesh;
  mesh.origin = origin;
  mesh.tiles_x = (nx - 1 + tile_cells - 1) / tile_cells;
  mesh.tiles_y = (ny - 1 + tile_cells - 1) / tile_cells;

  auto x_of = [&](int i) { return static_cast<float>(hf.min_x() + i * res - origin.x()); };
  auto y_of = [&](int j) { return static_cast<float>(hf.min_y() + j * res - origin.y()); };
  auto z_of = [&](int i, int j) { return static_cast<float>(hf.at(i, j) - origin.z()); };
  int levels = 1;
  while ((1 << levels) <= tile_cells) ++levels;

  mesh.tiles.resize(static_cast<std::size_t>(mesh.tiles_x) * mesh.tiles_y);
  for (int ty = 0; ty < mesh.tiles_y; ++ty) {
    for (int tx = 0; tx < mesh.tiles_x; ++tx) {
      TerrainTile& t = mesh.tiles[static_cast<std::size_t>(ty) * mesh.tiles_x + tx];
      t.i0 = tx * tile_cells;
      t.i1 = std::min(nx - 1, t.i0 + tile_cells);
      t.j0 = ty * tile_cells;
      t.j1 = std::min(ny - 1, t.j0 + tile_cells);
      // Vertex block: samples row by row, then skirt copies of the edges j0, j1, i0, i1.
      const int w = t.i1 - t.i0 + 1, h = t.j1 - t.j0 + 1;
      t.first_vertex = static_cast<std::uint32_t>(mesh.vertex_count());
      for (int j = t.j0; j <= t.j1; ++j)
        for (int i = t.i0; i <= t.i1; ++i)
          mesh.vertices.insert(mesh.vertices.end(), {x_of(i), y_of(j), z_of(i, j), 0.0F});
      for (int j : {t.j0, t.j1})
        for (int i = t.i0; i <= t.i1; ++i)
          mesh.vertices.insert(mesh.vertices.end(), {x_of(i), y_of(j), z_of(i, j), 1.0F});
      for (int i : {t.i0, t.i1})
        for (int j = t.j0; j <= t.j1; ++j)
          mesh.vertices.insert(mesh.vertices.end(), {x_of(i), y_of(j), z_of(i, j), 1.0F});
      t.vertex_count = static_cast<std::uint32_t>(mesh.vertex_count()) - t.first_vertex;
      auto grid_index = [&t, w](int i, int j) {
        return static_cast<std::uint32_t>((j - t.j0) * w + (i - t.i0));
      };
      const std::uint32_t skirt0 = static_cast<std::uint32_t>(w * h);
      // Horizontal edges: j == j0 -> block 0, j == j1 -> block 1; vertical: i0 -> 2, i1 -> 3.
      auto hskirt = [&](int i, int j) {
        return skirt0 + static_cast<std::uint32_t>((j == t.j0 ? 0 : w) + (i - t.i0));
      };
      auto vskirt = [&](int i, int j) {
        return skirt0 + static_cast<std::uint32_t>(2 * w + (i == t.i0 ? 0 : h) + (j - t.j0));
      };
      float zmin = 1e30F, zmax = -1e30F;
      for (int j = t.j0; j <= t.j1; ++j)
        for (int i = t.i0; i <= t.i1; ++i) {
          zmin = std::min(zmin, z_of(i, j));
          zmax = std::max(zmax, z_of(i, j));
        }
      t.box_min = Eigen::Vector3f(x_of(t.i0), y_of(t.j0), zmin);
      t.box_max = Eigen::Vector3f(x_of(t.i1), y_of(t.j1), zmax);
      for (int l = 0; l < levels; ++l) {
        TerrainTileLod lod;
        lod.step = 1 << l;
        lod.first_index = static_cast<std::uint32_t>(mesh.indices.size());
        const std::vector<int> xs = LodSamples(t.i0, t.i1, lod.step);
        const std::vector<int> ys = LodSamples(t.j0, t.j1, lod.step);
        double err = 0.0;
        for (std::size_t b = 0; b + 1 < ys.size(); ++b) {
          for (std::size_t a = 0; a + 1 < xs.size(); ++a) {
            const int ia = xs[a], ib = xs[a + 1], ja = ys[b], jb = ys[b + 1];
            const std::uint32_t v00 = grid_index(ia, ja), v10 = grid_index(ib, ja);
            const std::uint32_t v01 = grid_index(ia, jb), v11 = grid_index(ib, jb);
            mesh.indices.insert(mesh.indices.end(), {v00, v10, v11, v00, v11, v01});
            if (lod.step > 1) {
              const double z00 = hf.at(ia, ja), z10 = hf.at(ib, ja), z01 = hf.at(ia, jb),
                           z11 = hf.at(ib, jb);
              for (int j = ja; j <= jb; ++j) {
                const double v = static_cast<double>(j - ja) / (jb - ja);
                for (int i = ia; i <= ib; ++i) {
                  const double u = static_cast<double>(i - ia) / (ib - ia);
                  const double z = u >= v ? z00 + u * (z10 - z00) + v * (z11 - z10)
                                          : z00 + v * (z01 - z00) + u * (z11 - z01);
                  err = std::max(err, std::abs(z - hf.at(i, j)));
                }
              }
            }
          }
        }
        lod.surface_count = static_cast<std::uint32_t>(mesh.indices.size()) - lod.first_index;
        lod.max_error = static_cast<float>(err);
        // Skirts along the four edges.
        auto strip = [&](const std::vector<int>& along, bool vertical, int fixed) {
          for (std::size_t k = 0; k + 1 < along.size(); ++k) {
            std::uint32_t ta, tb, sa, sb;
            if (vertical) {
              ta = grid_index(fixed, along[k]);
              tb = grid_index(fixed, along[k + 1]);
              sa = vskirt(fixed, along[k]);
              sb = vskirt(fixed, along[k + 1]);
            } else {
              ta = grid_index(along[k], fixed);
              tb = grid_index(along[k + 1], fixed);
              sa = hskirt(along[k], fixed);
              sb = hskirt(along[k + 1], fixed);
            }
            mesh.indices.insert(mesh.indices.end(), {ta, tb, sb, ta, sb, sa});
          }
        };
        strip(xs, false, t.j0);
        strip(xs, false, t.j1);
        strip(ys, true, t.i0);
        strip(ys, true, t.i1);
        lod.index_count = static_cast<std::uint32_t>(mesh.indices.size()) - lod.first_index;
        t.lods.push_back(lod);
      }
    }
  }
  // Skirt depths: own error + the largest error any neighbour may have + 2 cm.
  std::vector<float> worst(mesh.tiles.size(), 0.0F);
  for (std::size_t k = 0; k < mesh.tiles.size(); ++k) {
    for (const auto& l : mesh.tiles[k].lods) worst[k] = std::max(worst[k], l.max_error);
  }
  for (int ty = 0; ty < mesh.tiles_y; ++ty) {
    for (int tx = 0; tx < mesh.tiles_x; ++tx) {
      float neighbour = 0.0F;
      const int dxs[4] = {-1, 1, 0, 0}, dys[4] = {0, 0, -1, 1};
      for (int d = 0; d < 4; ++d) {
        const int x = tx + dxs[d], y = ty + dys[d];
        if (x < 0 || y < 0 || x >= mesh.tiles_x || y >= mesh.tiles_y) continue;
        neighbour = std::max(neighbour, worst[static_cast<std::size_t>(y) * mesh.tiles_x + x]);
      }
      TerrainTile& t = mesh.tiles[static_cast<std::size_t>(ty) * mesh.tiles_x + tx];
      float deepest = 0.0F;
      for (auto& l : t.lods) {
        l.skirt_depth = l.max_error + neighbour + 0.02F;
        deepest = std::max(deepest, l.skirt_depth);
      }
      t.box_min.z() -= deepest;
    }
  }
  return mesh;
}

int SelectLod(const TerrainTile& tile, const Eigen::Vector3f& camera, double focal_px,
              double resolution, double error_px, double max_cell_px) {
  const Eigen::Vector3f closest = camera.cwiseMax(tile.box_min).cwiseMin(tile.box_max);
  const double d = (closest - camera).norm();
  if (d < 1e-6) return 0;
  for (int l = static_cast<int>(tile.lods.size()) - 1; l > 0; --l) {
    const TerrainTileLod& lod = tile.lods[static_cast<std::size_t>(l)];
    if (lod.max_error * focal_px / d <= error_px &&
        lod.step * resolution * focal_px / d <= max_cell_px) {
      return l;
    }
  }
  return 0;
}

}  // namespace rover::sim::render::internal
