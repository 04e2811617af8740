#pragma once
/// @file
/// Test support: straightforward reference implementations of GESTALT's assessment of one scan
/// and of its arc votes, for tests (the fast code must agree with them) and for gestalt-bench
/// (the fast code's speed is reported as a ratio to theirs).
///
/// ReferenceAssess: bins the scan's points into the same grid as TerrainMap (centred on the
/// rover, same range limits), then for every cell gathers the raw points of every cell in its
/// rover disc and fits the plane to them directly (centroid, then Σ (p - m)(p - m)ᵀ / n, Eigen's
/// iterative symmetric eigensolver); cell means and deviations for the step filter come from each
/// cell's points; the step search visits every pair of belly disc and cell. No moment sums,
/// prefix sums, incremental updates or layers: for one scan into an empty map TerrainMap's result
/// is the same by construction (see layered_map.hpp), so the two maps must agree.
///
/// ReferenceEvaluate: the same votes as ArcEvaluator, with each path's cells found by testing
/// every cell of the map against the path (instead of walking along it).

#include <vector>

#include "rover/apl/gestalt/filters.hpp"
#include "rover/apl/gestalt/grid.hpp"
#include "rover/apl/gestalt/options.hpp"
#include "rover/apl/nav_core/arc_selector.hpp"
#include "rover/apl/nav_core/goodness_map.hpp"
#include "rover/apl/nav_core/range_scan.hpp"

namespace rover::apl::gestalt::testing {

struct ReferenceResult {
  Grid<CellAssessment> assessments;
  nav_core::GoodnessMap map;  ///< with unknown and border cells as TerrainMap publishes them
};

/// Preconditions: options.Validate() ok, scan.Validate() ok.
ReferenceResult ReferenceAssess(const GestaltOptions& options, const nav_core::RangeScan& scan);

/// Preconditions: options.Validate() ok; every path stays inside `map`.
nav_core::ArcEvaluation ReferenceEvaluate(const GestaltOptions& options,
                                          const nav_core::GoodnessMap& map,
                                          const nav_core::ArcRequest& request);

}  // namespace rover::apl::gestalt::testing
