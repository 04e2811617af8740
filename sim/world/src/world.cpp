#include "rover/sim/world/world.hpp"

#include <numbers>

#include "rover/sim/terrain/features.hpp"
#include "rover/sim/terrain/lander.hpp"
#include "rover/sim/terrain/terrain_params.hpp"

namespace rover::sim::world {

using terrain::DeclareLanderParams;
using terrain::DeclareScienceTargets;
using terrain::DeclareTerrainFeatures;
using terrain::DeclareTerrainParams;
using terrain::GenerateTerrain;
using terrain::PlaceScenarioFeatures;
using terrain::PlaceScenarioObjects;
using terrain::TerrainParamsFromParamSet;

const std::vector<std::string>& WorldSections() {
  static const std::vector<std::string> k = {"terrain", "terrain_features", "lander",
                                             "science_targets", "rover"};
  return k;
}

void DeclareWorldParams(ParamSet& params) {
  DeclareTerrainParams(params, "terrain");
  DeclareLanderParams(params, "lander");
  DeclareScienceTargets(params, "science_targets");
  DeclareTerrainFeatures(params, "terrain_features");
  params.Declare("rover.start.x", 0.0, "[m] rover start, site frame").Range(-1e4, 1e4);
  params.Declare("rover.start.y", 0.0, "[m] rover start, site frame").Range(-1e4, 1e4);
  params.Declare("rover.start.yaw_deg", 0.0, "[deg] initial heading, from +x towards +y")
      .Range(-360.0, 360.0);
}

Result<World> BuildWorld(const ParamSet& params) {
  auto tp = TerrainParamsFromParamSet(params, "terrain");
  if (!tp.ok()) return tp.status();
  // The rover start is rover.start.x/y; the terrain's rock-free disc is centred there.
  for (const char* axis : {"x", "y"}) {
    const std::string key = std::string("terrain.start.") + axis;
    if (params.Origin(key).source != "default") {
      return InvalidArgument(params.Origin(key).ToString() + ": key '" + key +
                             "': set the start with rover.start." + axis + " instead");
    }
  }
  tp->start.x = params.GetDouble("rover.start.x");
  tp->start.y = params.GetDouble("rover.start.y");
  auto terrain = GenerateTerrain(*tp);
  if (!terrain.ok()) return terrain.status();
  ROVER_RETURN_IF_ERROR(PlaceScenarioFeatures(&*terrain, params, "terrain_features"));
  ROVER_RETURN_IF_ERROR(PlaceScenarioObjects(&*terrain, params, "lander", "science_targets"));
  World w;
  w.start_x = tp->start.x;
  w.start_y = tp->start.y;
  w.start_yaw = params.GetDouble("rover.start.yaw_deg") * std::numbers::pi / 180.0;
  w.terrain = std::move(*terrain);
  return w;
}

}  // namespace rover::sim::world
