// Steps 5-7 of the traversability map: hazards (steep regions, discontinuities, missing data,
// blocked corridors), the border grown around them, and the safe rest.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "rover/apl/roaman/distance_transform.hpp"
#include "rover/apl/roaman/traversability.hpp"

namespace rover::apl::roaman {
namespace {

// Minimum of `in` over the square window of half-side r (infinite values ignored), separably.
Layer<float> WindowMin(const Layer<float>& in, int r) {
  const int w = in.width(), h = in.height();
  const float inf = std::numeric_limits<float>::infinity();
  Layer<float> rows(w, h, inf), out(w, h, inf);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      float m = inf;
      for (int k = std::max(0, i - r); k <= std::min(w - 1, i + r); ++k) m = std::min(m, in.at(k, j));
      rows.at(i, j) = m;
    }
  }
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      float m = inf;
      for (int k = std::max(0, j - r); k <= std::min(h - 1, j + r); ++k) m = std::min(m, rows.at(i, k));
      out.at(i, j) = m;
    }
  }
  return out;
}

void Raise(CellClass* c, CellClass to) {
  if (to > *c) *c = to;
}

}  // namespace

void MarkHazards(const ElevationMap& map, const NormalMap& normals, const RegionMap& regions,
                 const Layer<std::uint8_t>& blocked, const RoamanOptions& options,
                 Layer<CellClass>* cls, Layer<float>* step) {
  const int w = map.geometry.width, h = map.geometry.height;
  const float inf = std::numeric_limits<float>::infinity();
  *cls = Layer<CellClass>(w, h, CellClass::kSafe);
  *step = Layer<float>(w, h, std::numeric_limits<float>::quiet_NaN());

  // Discontinuities: a cell's top above the lowest bottom within the step baseline.
  Layer<float> bottoms(w, h, inf);
  for (std::size_t k = 0; k < bottoms.size(); ++k) {
    if (map.source[k] != HeightSource::kNone) bottoms[k] = map.bottom[k];
  }
  const int r = std::max(1, static_cast<int>(std::lround(options.step_baseline / map.geometry.cell)));
  const Layer<float> low = WindowMin(bottoms, r);

  // Missing data: cells without a height or a normal, in 8-connected regions; regions smaller
  // than min_missing_area are too small to hide anything the rover could not cross.
  Layer<std::uint8_t> missing(w, h, 0);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      missing.at(i, j) = map.source.at(i, j) == HeightSource::kNone || !normals.has(i, j);
    }
  }
  Layer<std::uint8_t> large(w, h, 0);
  {
    const double min_cells = options.min_missing_area / map.geometry.area_per_cell();
    Layer<std::uint8_t> seen(w, h, 0);
    std::vector<int> queue;
    for (int sj = 0; sj < h; ++sj) {
      for (int si = 0; si < w; ++si) {
        if (!missing.at(si, sj) || seen.at(si, sj)) continue;
        queue.assign(1, static_cast<int>(missing.Index(si, sj)));
        seen.at(si, sj) = 1;
        for (std::size_t q = 0; q < queue.size(); ++q) {
          const int ci = queue[q] % w, cj = queue[q] / w;
          for (int dj = -1; dj <= 1; ++dj) {
            for (int di = -1; di <= 1; ++di) {
              const int ni = ci + di, nj = cj + dj;
              if (!missing.Contains(ni, nj) || !missing.at(ni, nj) || seen.at(ni, nj)) continue;
              seen.at(ni, nj) = 1;
              queue.push_back(static_cast<int>(missing.Index(ni, nj)));
            }
          }
        }
        if (static_cast<double>(queue.size()) >= min_cells) {
          for (const int k : queue) large[static_cast<std::size_t>(k)] = 1;
        }
      }
    }
  }

  const double min_steep_cells = options.min_steep_area / map.geometry.area_per_cell();
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      CellClass& c = cls->at(i, j);
      if (missing.at(i, j)) {
        if (large.at(i, j)) c = CellClass::kMissing;
      } else {
        const float s = map.top.at(i, j) - low.at(i, j);
        step->at(i, j) = s;
        if (s > options.body_clearance) Raise(&c, CellClass::kStep);
        const std::int32_t id = regions.id.at(i, j);
        if (id >= 0) {
          const SlopeRegion& region = regions.regions[static_cast<std::size_t>(id)];
          if (region.slope > options.max_slope && region.cells >= min_steep_cells) {
            Raise(&c, CellClass::kSteep);
          }
        }
      }
      if (blocked.size() != 0 && blocked.at(i, j)) Raise(&c, CellClass::kBlocked);
    }
  }
}

int GrowBorder(Layer<CellClass>* cls, double border_cells) {
  Layer<std::uint8_t> hazard(cls->width(), cls->height(), 0);
  for (std::size_t k = 0; k < hazard.size(); ++k) hazard[k] = IsHazard((*cls)[k]) ? 1 : 0;
  const Layer<float> dist = DistanceTransform(hazard);
  int n = 0;
  for (std::size_t k = 0; k < hazard.size(); ++k) {
    if ((*cls)[k] == CellClass::kSafe && dist[k] <= border_cells + 1e-6) {
      (*cls)[k] = CellClass::kBorder;
      ++n;
    }
  }
  return n;
}

}  // namespace rover::apl::roaman
