#pragma once
/// @file
/// Test support: hand-made goodness maps.

#include <cstdint>

#include "rover/apl/nav_core/goodness_map.hpp"

namespace rover::apl::gestalt::testing {

/// A map of `cells` x `cells` cells of `resolution` centred on the site origin, every cell known
/// with goodness `g` and certainty 255; unknown value MER's (11, 0).
inline nav_core::GoodnessMap KnownMap(int g = 255, int cells = 50, double resolution = 0.2) {
  nav_core::GoodnessMap m;
  m.resolution = resolution;
  m.width = m.height = cells;
  m.origin_x = m.origin_y = -0.5 * cells * resolution;
  m.goodness.assign(m.cell_count(), static_cast<std::uint8_t>(g));
  m.certainty.assign(m.cell_count(), 255);
  m.flags.assign(m.cell_count(), nav_core::kCellKnown);
  m.unknown_goodness = 11;
  m.unknown_certainty = 0;
  return m;
}

}  // namespace rover::apl::gestalt::testing
