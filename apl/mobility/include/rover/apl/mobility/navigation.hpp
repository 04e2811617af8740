#pragma once
/// @file
/// The one place that turns parameters into a MobilityManager with its terrain assessor and
/// path selector, for the apl-mobility service and the autonav-kinematic tool alike.
///
/// `nav.planner` chooses the pair: "gestalt" (MER's GESTALT: goodness map and arc voting,
/// apl/gestalt; the baseline) or "enav" (the ENav-class path tree with clearance checks over a
/// remembered height map, apl/enav). Keys: mobility.* (MobilityOptions), gestalt.*, enav.*,
/// geometry.* (the rover description both planners take their geometry from).

#include <string>

#include "rover/apl/mobility/mobility_manager.hpp"
#include "rover/base/params.hpp"

namespace rover::apl::mobility {

/// Declares every key above.
void DeclareNavigationParams(ParamSet& params);
/// Reads and checks them all (the unused planner's keys too). Errors name the key.
Status ValidateNavigationParams(const ParamSet& params);
/// "gestalt" or "enav".
std::string PlannerName(const ParamSet& params);
/// The manager with the chosen planner. Errors: as ValidateNavigationParams.
Result<MobilityManager> MakeMobilityManager(const ParamSet& params);

}  // namespace rover::apl::mobility
