// Steps 1 and 2 of the traversability map: binned heights, their distribution, hole filling.
#include <algorithm>
#include <cmath>
#include <limits>

#include "rover/apl/roaman/traversability.hpp"

namespace rover::apl::roaman {

ElevationMap BinElevation(const Layer<CellStats>& cells, const GridGeometry& geometry, int i0,
                          int j0, int width, int height, const RoamanOptions& options) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  ElevationMap m;
  m.geometry = geometry;
  m.geometry.origin_x = geometry.origin_x + i0 * geometry.cell;
  m.geometry.origin_y = geometry.origin_y + j0 * geometry.cell;
  m.geometry.width = width;
  m.geometry.height = height;
  m.mean = Layer<float>(width, height, nan);
  m.top = Layer<float>(width, height, nan);
  m.bottom = Layer<float>(width, height, nan);
  m.sigma = Layer<float>(width, height, nan);
  m.count = Layer<std::uint32_t>(width, height, 0);
  m.source = Layer<HeightSource>(width, height, HeightSource::kNone);
  const double k = options.height_sigma_k;
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      if (!cells.Contains(i0 + i, j0 + j)) continue;
      const CellStats& c = cells.at(i0 + i, j0 + j);
      m.count.at(i, j) = c.count;
      if (c.count < static_cast<std::uint32_t>(options.min_cell_points)) continue;
      const double mean = c.mean();
      const double s = std::sqrt(c.variance());
      m.mean.at(i, j) = static_cast<float>(mean);
      m.sigma.at(i, j) = static_cast<float>(s);
      m.top.at(i, j) = static_cast<float>(std::min<double>(c.max, mean + k * s));
      m.bottom.at(i, j) = static_cast<float>(std::max<double>(c.min, mean - k * s));
      m.source.at(i, j) = HeightSource::kMeasured;
      ++m.measured;
    }
  }
  return m;
}

int FillHoles(ElevationMap* map, const RoamanOptions& options) {
  const int w = map->geometry.width, h = map->geometry.height;
  const double cell = map->geometry.cell;
  const double tan_max = std::tan(options.max_slope);
  // The four lines through a cell: along i, along j and the two diagonals.
  constexpr int kDirs[4][2] = {{1, 0}, {0, 1}, {1, 1}, {1, -1}};
  struct Fill {
    int i, j;
    float z;
  };
  std::vector<Fill> fills;
  const auto measured = [&](int i, int j) {
    return map->source.Contains(i, j) && map->source.at(i, j) == HeightSource::kMeasured;
  };
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      if (map->source.at(i, j) != HeightSource::kNone) continue;
      int lines = 0;
      double sum = 0.0, weight = 0.0;
      for (const auto& d : kDirs) {
        const double step = cell * std::hypot(d[0], d[1]);
        // The hole along this line is the a - 1 missing cells ahead, this one and the b - 1
        // behind: a + b - 1 cells, at most g = max_fill_gap / step of them.
        const int g = static_cast<int>(std::floor(options.max_fill_gap / step + 1e-9));
        int a = 0, b = 0;
        for (int s = 1; s <= g && a == 0; ++s) {
          if (measured(i + s * d[0], j + s * d[1])) a = s;
        }
        if (a == 0) continue;
        for (int s = 1; s <= g - a + 1 && b == 0; ++s) {
          if (measured(i - s * d[0], j - s * d[1])) b = s;
        }
        if (b == 0) continue;
        const float za = map->mean.at(i + a * d[0], j + a * d[1]);
        const float zb = map->mean.at(i - b * d[0], j - b * d[1]);
        const double span = (a + b) * step;
        if (std::abs(za - zb) > span * tan_max) continue;  // an occlusion edge: never bridged
        // Linear interpolation: the nearer end weighs more.
        const double z = (b * static_cast<double>(za) + a * static_cast<double>(zb)) / (a + b);
        sum += z / span;
        weight += 1.0 / span;
        ++lines;
      }
      if (lines >= options.min_fill_directions) {
        fills.push_back({i, j, static_cast<float>(sum / weight)});
      }
    }
  }
  for (const Fill& f : fills) {
    map->mean.at(f.i, f.j) = f.z;
    map->top.at(f.i, f.j) = f.z;
    map->bottom.at(f.i, f.j) = f.z;
    map->sigma.at(f.i, f.j) = 0.0f;
    map->source.at(f.i, f.j) = HeightSource::kFilled;
  }
  map->filled += static_cast<int>(fills.size());
  return static_cast<int>(fills.size());
}

}  // namespace rover::apl::roaman
