#include "rover/sim/world/world.hpp"

#include <numbers>

#include "rover/sim/terrain/lander.hpp"
#include "rover/sim/terrain/terrain_params.hpp"

namespace rover::sim {

const std::vector<std::string>& WorldSections() {
  static const std::vector<std::string> k = {"terrain", "lander", "science_targets", "rover"};
  return k;
}

void DeclareWorldParams(ParamSet& params) {
  DeclareTerrainParams(params, "terrain");
  DeclareLanderParams(params, "lander");
  DeclareScienceTargets(params, "science_targets");
  params.Declare("rover.start.yaw_deg", 0.0, "[deg] initial heading, from +x towards +y")
      .Range(-360.0, 360.0);
}

Result<World> BuildWorld(const ParamSet& params) {
  auto tp = TerrainParamsFromParamSet(params, "terrain");
  if (!tp.ok()) return tp.status();
  auto terrain = GenerateTerrain(*tp);
  if (!terrain.ok()) return terrain.status();
  ROVER_RETURN_IF_ERROR(PlaceScenarioObjects(&*terrain, params, "lander", "science_targets"));
  World w;
  w.start_x = tp->start.x;
  w.start_y = tp->start.y;
  w.start_yaw = params.GetDouble("rover.start.yaw_deg") * std::numbers::pi / 180.0;
  w.terrain = std::move(*terrain);
  return w;
}

}  // namespace rover::sim
