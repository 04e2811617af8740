#pragma once
/// @file
/// Passability: was there a contact-free way from the start to the goal at all? The judge's
/// answer for a rock field, from truth (issue 35: success is reported over every field and over
/// the passable ones, and a driven path is compared with the shortest contact-free one).
///
/// A Dijkstra search over rover poses (x, y, heading) on a lattice of `cell` metres and
/// `headings` headings in the site frame (x north, y west; metres, radians). A move drives one
/// cell straight forward or backward along the heading (its length) or turns in place by one
/// heading step (`turn_cost` metres). A pose is free when no rock taller than
/// `traversable_height` comes within `margin` of a contact part of the rover that it is taller
/// than: the judge's hazard-contact rule (judge.hpp: parts, clearances less the footprint's
/// clearance margin, rock outlines); with `rectangle`, within `margin` of the whole ground
/// footprint rectangle (the judge's footprint_overlaps, no straddling). The search ends at the
/// first pose within `tolerance` of the goal.
///
/// It ignores slopes, tilt and the drive's curvature limit (a rover turns in place anywhere it
/// fits): a field without such a path cannot be crossed without a contact; one with it may still
/// need manoeuvres the planner does not make. Cost: the states visited, each checked against the
/// rocks within reach (a 36 x 20 m VL-1 field: a few seconds of CPU at most).

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/sim/judge/judge.hpp"

namespace rover::sim::judge {

struct PassabilityQuery {
  Eigen::Vector2d start = Eigen::Vector2d::Zero();  ///< [m] rover centre
  double start_yaw = 0.0;                           ///< [rad]
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();   ///< [m]
  double tolerance = 0.5;                           ///< [m] a pose this close to the goal ends
  Eigen::Vector2d area_min = Eigen::Vector2d::Zero();  ///< [m] the searched rectangle
  Eigen::Vector2d area_max = Eigen::Vector2d::Zero();
  double margin = 0.0;               ///< [m] added around every part (or the rectangle)
  bool rectangle = false;            ///< the whole ground footprint instead of the parts
  double traversable_height = 0.20;  ///< [m] lower rocks never block
  double cell = 0.1;                 ///< [m] lattice spacing
  int headings = 32;                 ///< lattice headings over the full turn
  double turn_cost = 0.05;           ///< [m] the cost of one heading step

  /// Every value finite; tolerance, margin >= 0; cell in [0.02, 1]; headings in [4, 360];
  /// turn_cost >= 0; the area at least one cell across and at most 4e7 states.
  Status Validate() const;
};

/// The shortest contact-free path's length [m] (lattice moves), or nullopt when there is none
/// (also when the start pose itself touches a rock or lies outside the area).
/// Errors: InvalidArgument naming the field of a bad query.
Result<std::optional<double>> ContactFreePathLength(const std::vector<JudgeRock>& rocks,
                                                    const RoverFootprint& footprint,
                                                    const PassabilityQuery& query);

}  // namespace rover::sim::judge
