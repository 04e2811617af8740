#include "rover/apl/mobility/navigation.hpp"

#include <memory>

#include "rover/apl/enav/enav_planner.hpp"
#include "rover/apl/enav/height_terrain.hpp"
#include "rover/apl/gestalt/arc_evaluator.hpp"
#include "rover/apl/gestalt/options.hpp"
#include "rover/apl/gestalt/terrain_map.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/hwconfig/rover_description.hpp"

namespace rover::apl::mobility {

void DeclareNavigationParams(ParamSet& params) {
  DeclareParams<MobilityOptions>(params, "mobility.");
  DeclareParams<gestalt::GestaltOptions>(params, "gestalt.");
  DeclareParams<enav::EnavOptions>(params, "enav.");
  DeclareParams<hwconfig::RoverDescription>(params, "geometry.");
  params.Declare("nav.planner", "gestalt",
                 "local planner: gestalt (MER's arc voting over a goodness map, the baseline) or "
                 "enav (a tree of multi-segment paths ranked by cost and cost-to-go, clearance-"
                 "checked for wheels, suspension and belly over a remembered height map)")
      .OneOf({"gestalt", "enav"});
}

std::string PlannerName(const ParamSet& params) { return params.GetString("nav.planner"); }

Status ValidateNavigationParams(const ParamSet& params) {
  ROVER_RETURN_IF_ERROR(ReadParams<MobilityOptions>(params, "mobility.").status());
  ROVER_RETURN_IF_ERROR(gestalt::ReadGestaltOptionsForRover(params).status());
  return enav::ReadEnavOptionsForRover(params).status();
}

namespace {
Status MergePrior(nav_core::TerrainAssessor& assessor,
                  const std::vector<nav_core::RangeScan>& scans) {
  for (std::size_t i = 0; i < scans.size(); ++i) {
    if (auto r = assessor.Update(scans[i]); !r.ok()) {
      return InvalidArgument("prior scan " + std::to_string(i) + ": " + r.status().message());
    }
  }
  return Status::Ok();
}
}  // namespace

Result<MobilityManager> MakeMobilityManager(const ParamSet& params,
                                            const std::vector<nav_core::RangeScan>& prior_scans) {
  ROVER_ASSIGN_OR_RETURN(const MobilityOptions options,
                         ReadParams<MobilityOptions>(params, "mobility."));
  if (PlannerName(params) == "enav") {
    ROVER_ASSIGN_OR_RETURN(const enav::EnavOptions e, enav::ReadEnavOptionsForRover(params));
    ROVER_ASSIGN_OR_RETURN(enav::HeightTerrain terrain, enav::HeightTerrain::Create(e));
    ROVER_ASSIGN_OR_RETURN(enav::EnavPlanner planner, enav::EnavPlanner::Create(e));
    ROVER_RETURN_IF_ERROR(MergePrior(terrain, prior_scans));
    return MobilityManager::Create(options,
                                   std::make_unique<enav::HeightTerrain>(std::move(terrain)),
                                   std::make_unique<enav::EnavPlanner>(std::move(planner)));
  }
  ROVER_ASSIGN_OR_RETURN(const gestalt::GestaltOptions g,
                         gestalt::ReadGestaltOptionsForRover(params));
  ROVER_ASSIGN_OR_RETURN(gestalt::TerrainMap map, gestalt::TerrainMap::Create(g));
  ROVER_ASSIGN_OR_RETURN(gestalt::ArcEvaluator arcs, gestalt::ArcEvaluator::Create(g));
  ROVER_RETURN_IF_ERROR(MergePrior(map, prior_scans));
  return MobilityManager::Create(options, std::make_unique<gestalt::TerrainMap>(std::move(map)),
                                 std::make_unique<gestalt::ArcEvaluator>(std::move(arcs)));
}

}  // namespace rover::apl::mobility
