#pragma once
/// @file
/// RouteSearch: the rover's whole way to the goal over the remembered height map, as a search
/// over poses (x, y, heading) rather than cells: a rock field whose gaps are a few centimetres
/// wider than the rover is crossed by lining up with a gap, which a cost-to-go over cells (one
/// value per place, whatever the heading) cannot express and a fixed tree of one turn and two
/// arcs rarely finds. The judge's passability (sim/judge) searches the same kind of lattice over
/// true rocks; this one searches the planner's map.
///
/// Lattice (site frame, x north, y west; metres, radians): the height map's cells (cell_size),
/// 16 headings, those of the cell offsets (1,0) (2,1) (1,1) (1,2) and their turns by 90 deg
/// (0, 26.6, 45, 63.4, 90 deg ...), so every move ends on a cell centre. Moves from a pose:
///   straight forward or backward by the heading's offset (0.1, 0.224 or 0.141 m), cost
///     length x factor(end) (x backward_factor backward),
///   a turn in place to the next heading either way, cost turn_cost x angle,
/// where factor is CostToGoField's step factor over the same map with no configuration-space
/// blocking (1 seen, unknown_cost_factor unseen, more near wheel hazards; +inf near body
/// hazards). A pose is allowed when every contact part fits (ClearanceChecker::Fits, the
/// check's planar margin plus `margin`: the route keeps more room than the check demands, so
/// a small error in the pose or the map does not refuse the next step); a turn also at its
/// middle heading. The search is A* over f = g + h, h = that relaxed field's cost-to-go (the
/// way ignoring headings: never more than the lattice's way, up to the fields' resolution). It
/// ends at the first pose within the goal's tolerance, or, when the goal is off the map, on the
/// map's border (h then prices the rest as a straight line through the unknown); at most
/// max_expansions poses are expanded.
///
/// Preconditions: the terrain holds a map (HeightTerrain::height_map() not null); the field was
/// updated for this terrain and goal.

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

#include "rover/apl/enav/clearance.hpp"
#include "rover/apl/enav/cost_to_go.hpp"
#include "rover/apl/enav/height_terrain.hpp"
#include "rover/geometry/planar.hpp"

namespace rover::apl::enav {

struct RouteSearchOptions {
  double margin = 0.03;           ///< [m] beyond the clearance check's planar margin
  double backward_factor = 2.0;   ///< backward moves cost this many times forward ones
  double turn_cost = 1.0;         ///< [m/rad]
  int max_expansions = 400000;    ///< poses expanded before giving up
};

/// One pose of a route; `move` is how it was reached: +1 forward, -1 backward, 0 a turn.
struct RouteNode {
  geometry::Pose2 pose;
  int move = 0;
  double g = 0.0;  ///< [m-equivalent] cost from the route's start to here
};

struct Route {
  std::vector<RouteNode> nodes;  ///< from the start's lattice pose to the end
  double cost = 0.0;             ///< [m-equivalent] g at the end plus h there
  int expansions = 0;
  bool at_goal = false;  ///< ended within the goal's tolerance (else on the map's border)
};

class RouteSearch {
 public:
  /// The heading [rad] of lattice heading h in [0, 16).
  static double Heading(int h);
  /// The lattice heading nearest `heading` [rad].
  static int NearestHeading(double heading);

  /// The cheapest route from `start` over `terrain` to `goal` within `tolerance`, priced by
  /// `field` (updated for the same terrain and goal with no configuration-space blocking). The
  /// search starts at the start's cell at the two lattice headings either side of its heading
  /// (priced by the turn to each), allowed whatever the route's margin says: the rover stands
  /// there. nullopt when its parts do not fit at `start` itself (no margin), or no pose within
  /// the budget ends the search.
  std::optional<Route> Search(const HeightTerrain& terrain, const CostToGoField& field,
                              const geometry::Pose2& start, const Eigen::Vector2d& goal,
                              double tolerance, const RouteSearchOptions& options) const;

 private:
  // Per-search buffers, kept between searches (a 40 m map: 2.6 million poses).
  mutable std::vector<float> g_;
  mutable std::vector<std::int32_t> parent_;
  mutable std::vector<std::uint8_t> state_;  // bit 0 tested, bit 1 allowed, bit 2 closed
};

}  // namespace rover::apl::enav
