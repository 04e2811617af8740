#pragma once
/// @file
/// The simulated world of one run: generated terrain, lander, science targets and the rover's
/// start pose, built from one set of parameters. The simulator service and the scenario runner
/// (which needs the same terrain for the judge's rock list and the map) both build it from the
/// same declarations, so a seed gives both exactly the same world.
///
/// Parameters (all under these top-level sections of a scenario or parameter file):
///   terrain.*          sim/terrain's TerrainParams (its rock-free keep-out disc is centred on
///                      the rover start; terrain.start.x/y may not be set)
///   terrain_features   placed rocks and rock walls (sim/terrain features.hpp)
///   lander.*           the lander (lander.enabled, x, y, yaw_deg, ...)
///   science_targets    [x, y, diameter, texture_id, ...]
///   rover.start.x/y    [m] rover start in the site frame
///   rover.start.yaw_deg  initial heading (site frame, from +x towards +y)

#include <string>
#include <vector>

#include "rover/base/params.hpp"
#include "rover/base/status.hpp"
#include "rover/sim/terrain/terrain.hpp"

namespace rover::sim::world {

struct World {
  terrain::Terrain terrain;
  double start_x = 0, start_y = 0;  ///< [m] site frame
  double start_yaw = 0;             ///< [rad]
};

/// The top-level sections that hold world parameters.
const std::vector<std::string>& WorldSections();
void DeclareWorldParams(ParamSet& params);
/// Generates the terrain and places the objects; errors name file:line and key.
Result<World> BuildWorld(const ParamSet& params);

}  // namespace rover::sim::world
