#pragma once
// Terrain mesh with tiles and levels of detail (geomipmapping with skirts), CPU side.
//
// The heightfield grid (nx x ny samples) is cut into tiles of `tile_cells` cells. Each tile has
// LODs l = 0, 1, ... with sample step 2^l cells (the tile's last row/column is always
// included), triangulated as two triangles per LOD cell (diagonal (i0, j0)-(i1, j1)). For each
// LOD we store the largest vertical distance between a full-resolution sample in the tile and
// the LOD surface (max_error, metres), which a renderer turns into a screen-space error
// max_error * f / distance to pick the coarsest acceptable LOD per tile (SelectLod).
// Neighbouring tiles at different LODs leave cracks; every tile therefore carries vertical
// skirts along its four edges, hanging `skirt_depth` below the edge (its own error plus the
// largest error of its neighbours plus 2 cm), which fill any crack from below.
//
// Vertices are in "render coordinates": site frame minus `origin` (metres, float), 4 floats
// each: x, y, z, skirt flag (1 = this vertex is a skirt copy, drawn skirt_depth lower). Every
// tile owns a contiguous block of vertices (its samples, then its four edges' skirt copies) and
// its indices are relative to that block (draw with base vertex = first_vertex), so a draw call
// touches only the tile's own vertices.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "rover/sim/heightfield.hpp"

namespace rover::sim::render::internal {

struct TerrainTileLod {
  std::uint32_t first_index = 0;  // into TerrainMesh::indices (values relative to first_vertex)
  std::uint32_t index_count = 0;  // surface + skirt triangles, 3 per triangle
  std::uint32_t surface_count = 0;  // the first surface_count indices are the surface
  int step = 1;                   // grid cells per LOD cell
  float max_error = 0.0F;         // [m]
  float skirt_depth = 0.0F;       // [m]
};

struct TerrainTile {
  int i0 = 0, i1 = 0, j0 = 0, j1 = 0;  // sample index ranges (inclusive)
  std::uint32_t first_vertex = 0;      // the tile's vertex block
  std::uint32_t vertex_count = 0;
  Eigen::Vector3f box_min = Eigen::Vector3f::Zero();  // render coords, skirts included
  Eigen::Vector3f box_max = Eigen::Vector3f::Zero();
  std::vector<TerrainTileLod> lods;
};

struct TerrainMesh {
  Eigen::Vector3d origin = Eigen::Vector3d::Zero();  // site coordinates of render (0, 0, 0)
  int tiles_x = 0, tiles_y = 0;
  std::vector<float> vertices;          // 4 floats per vertex
  std::vector<std::uint32_t> indices;
  std::vector<TerrainTile> tiles;       // row-major: tile (tx, ty) at ty * tiles_x + tx

  std::size_t vertex_count() const { return vertices.size() / 4; }
};

// Preconditions: hf has >= 2 x 2 samples; tile_cells a power of two >= 2.
TerrainMesh BuildTerrainMesh(const terrain::HeightField& hf, int tile_cells,
                             const Eigen::Vector3d& origin);

// Sample positions along one axis of a tile for a LOD step: lo, lo + step, ..., hi.
std::vector<int> LodSamples(int lo, int hi, int step);

// Coarsest LOD of `tile` whose error is at most error_px pixels and whose cells are at most
// max_cell_px pixels for a camera at `camera` (render coords) with focal length focal_px, the
// distance being that from the camera to the tile's box; LOD 0 if the camera is inside it.
int SelectLod(const TerrainTile& tile, const Eigen::Vector3f& camera, double focal_px,
              double resolution, double error_px, double max_cell_px);

}  // namespace rover::sim::render::internal
