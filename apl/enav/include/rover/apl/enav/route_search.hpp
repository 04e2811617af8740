#pragma once
/// @file
/// RouteSearch: the rover's whole way to the goal over the remembered height map, as a search
/// over poses (x, y, heading) rather than cells: a rock field whose gaps are a few centimetres
/// wider than the rover is crossed by lining up with a gap, which a cost-to-go over cells (one
/// value per place, whatever the heading) cannot express and a fixed tree of one turn and two
/// arcs rarely finds. The judge's passability (sim/judge) searches the same kind of lattice over
/// true rocks; this one searches the planner's map.
///
/// Lattice (site frame, x north, y west; metres, radians): anchored at the rover's exact pose,
/// so every route is a sequence of moves the rover can drive from where it stands. Its points
/// are start + R(start heading) (i, j) x cell_size (the height map's cell count, centred on the
/// rover); its 16 headings are the start's plus those of the cell offsets (1,0) (2,1) (1,1)
/// (1,2) and their turns by 90 deg (0, 26.6, 45, 63.4, 90 deg ...), so every move ends on a
/// lattice point. Moves from a pose:
///   straight forward or backward by the heading's offset (0.1, 0.224 or 0.141 m), cost
///     length x factor(end) (x backward_factor backward),
///   a turn in place to the next heading either way, cost turn_cost x angle,
/// where factor is CostToGoField's step factor over the same map with no configuration-space
/// blocking (1 seen, unknown_cost_factor unseen, more near wheel hazards; +inf near body
/// hazards). A pose is allowed when its parts have NeededRoom (ClearanceChecker::Room: the
/// check's planar margin plus `margin`, so a small error in the pose or the map does not refuse
/// the next step; near the start no more than the rover has there); a turn also at its middle
/// heading. The search is A* over f = g + h, h = that relaxed field's cost-to-go (the way
/// ignoring headings: never more than the lattice's way, up to the fields' resolution). It ends
/// at the first pose within the goal's tolerance, or, when the goal is off the map, on the
/// map's border (h then prices the rest as a straight line through the unknown); at most
/// max_expansions poses are expanded. (A first form used the map's own cell centres and started
/// from the rover's cell: a route's first turn then happened up to 0.07 m from where the rover
/// stood, and the clearance check refused it there; a hybrid A* from the exact pose, bins
/// standing for the first pose to reach them, lost the narrow gaps: routes 30 % longer.)
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
  /// [m] Within this of the start a pose needs only as much room as the rover has now, when
  /// that is less than `margin` (see NeededRoom).
  double near_start = 0.5;
};

/// [m] The room (ClearanceChecker::Room) a route pose `distance` [m] from the start needs:
/// options.margin; within options.near_start of the start, no more than the rover has where it
/// stands (`start_room`, less 1 um: a pose exactly as near passes `Room > NeededRoom`), so a rover that stopped nearer a rock than the margin can still leave
/// by a way that takes it no nearer. (A search that demanded the margin there found routes the
/// rover could not start on: every step's first poses failed.)
double NeededRoom(const RouteSearchOptions& options, double start_room, double distance);

/// One pose of a route; `move` is how it was reached: +1 forward, -1 backward, 0 a turn (the
/// first node, the start, has 0 too).
struct RouteNode {
  geometry::Pose2 pose;
  int move = 0;
  double g = 0.0;  ///< [m-equivalent] cost from the route's start to here
};

struct Route {
  std::vector<RouteNode> nodes;  ///< from the start pose itself to the end
  double cost = 0.0;             ///< [m-equivalent] g at the end plus h there
  int expansions = 0;
  bool at_goal = false;  ///< ended within the goal's tolerance (else on the map's border)
};

class RouteSearch {
 public:
  static constexpr int kHeadings = 16;  ///< lattice headings (see the file comment)
  /// The heading [rad] of lattice heading h in [0, 16) relative to the start's.
  static double Heading(int h);

  /// The cheapest route from `start` over `terrain` to `goal` within `tolerance`, priced by
  /// `field` (updated for the same terrain and goal with no configuration-space blocking). The
  /// rover stands at `start`, so it is allowed whatever the route's margin says; poses near it
  /// need NeededRoom. nullopt when its parts touch a hazard at `start` itself (no margin), or
  /// no pose within the budget ends the search.
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
