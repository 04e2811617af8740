#include "rover/apl/gestalt/fov_edge.hpp"

#include <cstddef>

#include "rover/base/check.hpp"

namespace rover::apl::gestalt {

void FindFovEdgePixels(int width, int height, const std::vector<std::uint8_t>& used, int band,
                       std::vector<std::uint8_t>* edge) {
  ROVER_DEMAND(edge != nullptr && width >= 0 && height >= 0);
  const std::size_t n = static_cast<std::size_t>(width) * height;
  ROVER_DEMAND(used.size() == n);
  edge->assign(n, 0);
  if (band <= 0) return;
  auto idx = [width](int u, int v) { return static_cast<std::size_t>(v) * width + u; };
  // Rows: first and last used pixel.
  for (int v = 0; v < height; ++v) {
    int first = -1, last = -1;
    for (int u = 0; u < width; ++u) {
      if (used[idx(u, v)] != 0) {
        if (first < 0) first = u;
        last = u;
      }
    }
    if (first < 0) continue;
    for (int u = first; u < width && u < first + band; ++u) {
      if (used[idx(u, v)] != 0) (*edge)[idx(u, v)] = 1;
    }
    for (int u = last; u >= 0 && u > last - band; --u) {
      if (used[idx(u, v)] != 0) (*edge)[idx(u, v)] = 1;
    }
  }
  // Columns.
  std::vector<int> first(static_cast<std::size_t>(width), -1),
      last(static_cast<std::size_t>(width), -1);
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      if (used[idx(u, v)] == 0) continue;
      if (first[static_cast<std::size_t>(u)] < 0) first[static_cast<std::size_t>(u)] = v;
      last[static_cast<std::size_t>(u)] = v;
    }
  }
  for (int u = 0; u < width; ++u) {
    const int f = first[static_cast<std::size_t>(u)], l = last[static_cast<std::size_t>(u)];
    if (f < 0) continue;
    for (int v = f; v < height && v < f + band; ++v) {
      if (used[idx(u, v)] != 0) (*edge)[idx(u, v)] = 1;
    }
    for (int v = l; v >= 0 && v > l - band; --v) {
      if (used[idx(u, v)] != 0) (*edge)[idx(u, v)] = 1;
    }
  }
}

}  // namespace rover::apl::gestalt
