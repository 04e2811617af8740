#pragma once
/// @file
/// CostToGoField: the cost from every cell of the remembered map to the goal (ENav's global
/// cost-to-go), over cells of options.cost_cell_size (0.2 m) covering the HeightTerrain.
///
/// Step cost between 8-connected cell centres: the step's length times the mean of the two
/// cells' factors, a cell's factor being
///   (unknown_cost_factor if no height cell of it is known, else 1)
///   x (1 + hazard_cost_factor · max(0, 1 - d_wheel / hazard_cost_radius))
/// where d_wheel is its distance to the nearest wheel hazard (so the rover is steered clear of
/// rocks without being forbidden to straddle them); cells within blocked_radius of a body
/// hazard (a rock taller than the belly clearance) are blocked, and so are cells where the
/// rover's parts (ClearanceChecker without ACE) fit in none of cspace_headings headings: a gap
/// narrower than the rover is not a route. Unknown cells are priced, never
/// forbidden. Sources: every unblocked cell whose centre lies within the goal's tolerance (and
/// the goal's own cell) at cost 0, when the goal lies on the map: a rock at the goal point does
/// not cut the goal off while ground within its tolerance is open; when none is unblocked or the
/// goal is off the map, every unblocked cell on the map's border at its straight-line distance
/// to the goal (times unknown_cost_factor: beyond the map nothing is known).
///
/// Updates: Update() recomputes only when the terrain's revision or the goal changed; the search
/// is a Dijkstra over the map (40 m: 200 x 200 cells, a few milliseconds), run again in whole
/// rather than repaired (D* Lite's incremental repair is a later refinement; the field is
/// recomputed at most once per range image).

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "rover/apl/enav/height_terrain.hpp"

namespace rover::apl::enav {

class CostToGoField {
 public:
  /// `cspace` false: no configuration-space blocking whatever the options say (the relaxed
  /// field RouteSearch takes as its heuristic: it searches headings itself).
  explicit CostToGoField(bool cspace = true) : cspace_(cspace) {}

  /// Recomputes the field for `goal` (site x, y) reached within `tolerance` [m] if the terrain,
  /// the goal or the tolerance changed since the last call; returns whether it did.
  bool Update(const HeightTerrain& terrain, const Eigen::Vector2d& goal, double tolerance = 0.0);

  /// [m-equivalent] cost from site point xy to the goal: +inf when blocked, unreachable or off
  /// the map.
  double Cost(const Eigen::Vector2d& xy) const;
  /// The step factor of the cell under xy (+inf when blocked, unknown_cost_factor off the map).
  double Factor(const Eigen::Vector2d& xy) const;
  /// Cells of the field (for pictures): width x height from origin at `resolution`.
  int width() const { return width_; }
  int height() const { return height_; }
  double resolution() const { return resolution_; }
  Eigen::Vector2d origin() const { return origin_; }
  const std::vector<float>& costs() const { return cost_; }
  int searches() const { return searches_; }  ///< Dijkstra runs so far
  /// The goal of the latest Update() (NaN before the first).
  const Eigen::Vector2d& goal() const { return goal_; }

 private:
  bool Cell(const Eigen::Vector2d& xy, int* i, int* j) const;

  std::uint64_t revision_ = ~std::uint64_t{0};
  Eigen::Vector2d goal_{std::numeric_limits<double>::quiet_NaN(), 0.0};
  double tolerance_ = 0.0;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double resolution_ = 0.2;
  double unknown_factor_ = 1.5;
  int width_ = 0, height_ = 0;
  std::vector<float> cost_;
  std::vector<float> factor_;
  int searches_ = 0;
  bool cspace_ = true;
};

}  // namespace rover::apl::enav
