#pragma once
/// @file
/// Exact Euclidean distance transform on a grid (Felzenszwalb & Huttenlocher 2012: the lower
/// envelope of parabolas, one pass per axis, O(cells)). Used to grow hazard borders (step 6) and
/// for the clearance map the planners test the rover footprint against.

#include <cstdint>

#include "rover/apl/roaman/grid.hpp"

namespace rover::apl::roaman {

/// For every cell, the distance in cells from its centre to the centre of the nearest cell
/// where `feature` is nonzero (0 on features). +infinity everywhere when there is no feature.
Layer<float> DistanceTransform(const Layer<std::uint8_t>& feature);

}  // namespace rover::apl::roaman
