#pragma once
/// @file
/// Terrain features a scenario places by hand, on top of the generated terrain: single rocks
/// (a big rock in the way of a guarded drive), rock walls (a row of touching rocks along a
/// segment: a wall to detour around, three of them a cul-de-sac) and layered outcrops (flat
/// beds stepped back one above the other, whose straight level edges look like a lander's deck
/// from far away: the distractors of the long-range lander search). Generated rocks that overlap a
/// placed one are removed, so a seed's other rocks stay where they were.
///
/// Scenario keys (flat number lists, as `science_targets`):
///   terrain_features.rocks   [x, y, diameter, height, ...]          four numbers per rock
///   terrain_features.walls   [x0, y0, x1, y1, diameter, height, ...] six numbers per wall
///   terrain_features.outcrops [x, y, length, depth, height, yaw_deg, ...] six per outcrop
/// Site frame, metres; height 0 = rocks.height_ratio * diameter. A wall's rocks are spaced
/// 0.6 diameters apart from (x0, y0) to (x1, y1), so neighbours overlap and the wall has no gap
/// a rover could pass; each rock's diameter and height vary by +-10 %, its long axis along the
/// wall, drawn from the terrain seed's own stream (same seed -> same wall).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "rover/base/params.hpp"
#include "rover/base/status.hpp"

namespace rover::sim::terrain {

struct Terrain;

struct PlacedRock {
  double x = 0, y = 0;     ///< [m] centre, site frame
  double diameter = 1.0;   ///< [m] in [2 resolution, 10]
  double height = 0.0;     ///< [m] in [0, 5]; 0 = rocks.height_ratio * diameter
};

struct RockWall {
  Eigen::Vector2d from = Eigen::Vector2d::Zero(), to = Eigen::Vector2d::Zero();  ///< [m]
  double diameter = 0.6;  ///< [m] of each rock, in [2 resolution, 5]
  double height = 0.0;    ///< [m] in [0, 5]; 0 = rocks.height_ratio * diameter
};

/// A layered outcrop (Rock::layers > 0): beds of about kOutcropBedHeight each.
struct Outcrop {
  double x = 0, y = 0;     ///< [m] centre, site frame
  double length = 4.0;     ///< [m] along yaw, in [0.5, 20]
  double depth = 1.5;      ///< [m] across, in [0.3, length]
  double height = 1.0;     ///< [m] in [0.1, 5]
  double yaw_deg = 0.0;    ///< [deg] direction of the long side, from +x towards +y
};
/// [m] nominal bed height of an outcrop (layers = max(2, round(height / this))).
inline constexpr double kOutcropBedHeight = 0.3;

struct TerrainFeatures {
  std::vector<PlacedRock> rocks;
  std::vector<RockWall> walls;
  std::vector<Outcrop> outcrops;
};

/// Adds the features' rocks to `terrain` (ids continue from next_rock_id) and rebuilds its
/// heights. Errors name the feature and field ("walls[1].diameter: 9 is out of range [0.08,
/// 5]"); a feature off the map or on the rover's rock-free start disc is an error.
Status PlaceFeatures(Terrain* terrain, const TerrainFeatures& features);

/// Declares `<prefix>.rocks`, `<prefix>.walls` and `<prefix>.outcrops` (empty lists).
void DeclareTerrainFeatures(ParamSet& params, const std::string& prefix = "terrain_features");
/// Reads them back; a list whose length is not a multiple of 4 (rocks) or 6 (walls, outcrops) is an error
/// naming the file:line and key.
Result<TerrainFeatures> TerrainFeaturesFromParamSet(const ParamSet& params,
                                                    const std::string& prefix = "terrain_features");
/// Reads and places them; errors carry the key's file:line.
Status PlaceScenarioFeatures(Terrain* terrain, const ParamSet& params,
                             const std::string& prefix = "terrain_features");

}  // namespace rover::sim::terrain
