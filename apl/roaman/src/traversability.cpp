// The seven steps in order, over the part of the map memory that holds data.
#include "rover/apl/roaman/traversability.hpp"

#include <algorithm>
#include <cmath>

namespace rover::apl::roaman {

const char* CellClassName(CellClass c) {
  switch (c) {
    case CellClass::kSafe:
      return "safe";
    case CellClass::kBorder:
      return "border";
    case CellClass::kMissing:
      return "missing data";
    case CellClass::kSteep:
      return "steep slope";
    case CellClass::kStep:
      return "step";
    case CellClass::kBlocked:
      return "blocked";
  }
  return "?";
}

CellClass TraversabilityMap::ClassAt(double x, double y) const {
  int i = 0, j = 0;
  geometry.CellOf(x, y, &i, &j);
  return cls.Get(i, j, CellClass::kMissing);
}

std::vector<int> TraversabilityMap::ClassCounts() const {
  std::vector<int> n(static_cast<int>(CellClass::kBlocked) + 1, 0);
  for (const CellClass c : cls.values()) ++n[static_cast<int>(c)];
  return n;
}

TraversabilityMap ComputeTraversability(const SiteMap& map, const RoamanOptions& options) {
  TraversabilityMap t;
  t.revision = map.revision();
  const GridGeometry& g = map.geometry();
  int i0 = 0, j0 = 0, i1 = -1, j1 = -1;
  bool any = map.DataBounds(&i0, &j0, &i1, &j1);
  // Blocked corridors count as data: they must show even where nothing was seen.
  const Layer<std::uint8_t>& blocked = map.blocked();
  for (int j = 0; j < g.height; ++j) {
    for (int i = 0; i < g.width; ++i) {
      if (!blocked.at(i, j)) continue;
      if (!any) {
        i0 = i1 = i;
        j0 = j1 = j;
        any = true;
      }
      i0 = std::min(i0, i);
      i1 = std::max(i1, i);
      j0 = std::min(j0, j);
      j1 = std::max(j1, j);
    }
  }
  if (!any) {
    t.geometry = g;
    t.geometry.width = t.geometry.height = 0;
    return t;
  }
  // Grow the window by what the filters reach, so that its edge cells are as good as any.
  const double reach = options.hazard_border + options.normal_window + options.step_baseline +
                       options.max_fill_gap;
  const int margin = static_cast<int>(std::ceil(reach / g.cell)) + 2;
  i0 = std::max(0, i0 - margin);
  j0 = std::max(0, j0 - margin);
  i1 = std::min(g.width - 1, i1 + margin);
  j1 = std::min(g.height - 1, j1 + margin);
  const int w = i1 - i0 + 1, h = j1 - j0 + 1;

  // Steps 1 and 2.
  t.elevation = BinElevation(map.cells(), g, i0, j0, w, h, options);
  FillHoles(&t.elevation, options);
  t.geometry = t.elevation.geometry;
  // Step 3.
  t.normals = FitNormals(t.elevation, options);
  // Step 4.
  t.regions = GrowRegions(t.elevation, t.normals, options);
  // Step 5.
  Layer<std::uint8_t> window_blocked(w, h, 0);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) window_blocked.at(i, j) = blocked.at(i0 + i, j0 + j);
  }
  MarkHazards(t.elevation, t.normals, t.regions, window_blocked, options, &t.cls, &t.step);
  // Steps 6 and 7.
  GrowBorder(&t.cls, options.hazard_border / g.cell);
  return t;
}

}  // namespace rover::apl::roaman
