#pragma once
/// @file
/// CostToGo: distance to the goal over the goodness map, for the footprint check's waypoint vote
/// (cost_to_go, options.hpp). MER's vote only prefers the arc through the goal, so in a dense
/// field a rover facing a wall of rocks a few metres wide turns back and forth before it; the
/// 2006 flight update replaced it with a global planner's cost-to-go (Field D*). This is the
/// local form of that: Dijkstra over the map's cells, 8-connected, each step costing its length
/// times
///   (1 + goodness_weight (255 - g) / 255) x (unknown_cost_factor if the cell is unknown),
/// through cells that are not blocked. A cell is blocked when it lies within `clearance` (the
/// footprint's half width plus margin: a lower bound of what any heading needs) of a hazard
/// cell's centre (GoodnessMap kCellHazard), or is known with goodness below
/// min_allowed_goodness. With `straddle` (GESTALT's footprint_straddle) only tall hazard cells
/// (kCellTall) block; a lower hazard cell, which the rover may pass between its wheels but only
/// lined up, multiplies the step cost of the cells within `clearance` of it by
/// straddle_cost_factor instead. Sources: the goal's cell (cost 0) when the goal lies on the map,
/// else every unblocked cell on the map's edge at its straight-line distance to the goal (beyond
/// the map nothing is known). Cost() of a site point reads the cell under it; blocked or
/// unreachable cells read infinity.

#include <vector>

#include <Eigen/Core>

#include "rover/apl/nav_core/goodness_map.hpp"

namespace rover::apl::gestalt {

struct CostToGoOptions {
  double clearance = 0.73;            ///< [m] hazard cells block cells this close
  int min_allowed_goodness = 10;      ///< known cells below this are blocked
  double goodness_weight = 1.0;       ///< extra cost of a step over a goodness-0 cell
  double unknown_cost_factor = 1.5;   ///< cost factor of unknown cells
  bool straddle = false;              ///< only tall hazards block (file comment)
  double straddle_cost_factor = 2.0;  ///< cost factor near a lower hazard with `straddle`
};

class CostToGo {
 public:
  /// Runs the search over `map` toward site point `goal` (the map is not kept: only its grid
  /// geometry is). Preconditions: map.resolution > 0, clearance >= 0, goodness_weight >= 0,
  /// unknown_cost_factor >= 1.
  CostToGo(const nav_core::GoodnessMap& map, const Eigen::Vector2d& goal,
           const CostToGoOptions& options);

  /// [m] cost from the cell under site point (x, y) to the goal; infinity when blocked,
  /// unreachable or off the map.
  double Cost(double x, double y) const;
  /// Whether the cell under site point (x, y) is blocked (off the map: false).
  bool Blocked(double x, double y) const;
  /// Whether any cell reached the goal (false: the map holds no way to it).
  bool any_reachable() const { return any_reachable_; }

 private:
  nav_core::GoodnessMap grid_;  // geometry only (no cell values)
  std::vector<float> cost_;
  std::vector<std::uint8_t> blocked_;
  bool any_reachable_ = false;
};

}  // namespace rover::apl::gestalt
