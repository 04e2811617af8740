#pragma once
/// @file
/// The edge of a range image's field of view, found from its pixel grid.
///
/// The footprint of a scan on the ground is the set of pixels whose points are used. Its outline
/// is where the field of view (or the range limit) cuts the terrain: along each image row the
/// first and last used pixel (the left and right image edges, or where range runs out), along
/// each column the first and last (far and near edges). A pixel is an edge pixel when it lies
/// within `band` pixels of the outline along its row or its column:
///   u < first_row(v) + band,  u > last_row(v) - band,  v < first_col(u) + band,  or  v >
///   last_col(u) - band.
/// Holes inside the footprint (stereo dropouts, the shadow behind a rock) are not edges: what
/// lies behind them was not in view, but the cells around them were seen whole.
///
/// Cells that receive points from edge pixels are only partly seen, so GESTALT merges them
/// conservatively (seed 000 "Partial Range Data - Clipping").

#include <cstdint>
#include <vector>

namespace rover::apl::gestalt {

/// `edge` (resized to width * height) = 1 at the edge pixels of the footprint `used` (row-major,
/// nonzero = used). band = 0 marks nothing. Preconditions: used.size() == width * height.
void FindFovEdgePixels(int width, int height, const std::vector<std::uint8_t>& used, int band,
                       std::vector<std::uint8_t>* edge);

}  // namespace rover::apl::gestalt
