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
#include <vector>

#include "rover/apl/mobility/mobility_manager.hpp"
#include "rover/base/params.hpp"

namespace rover::apl::mobility {

/// Declares every key above.
void DeclareNavigationParams(ParamSet& params);
/// Reads and checks them all (the unused planner's keys too). Errors name the key.
Status ValidateNavigationParams(const ParamSet& params);
/// "gestalt" or "enav".
std::string PlannerName(const ParamSet& params);
/// The manager with the chosen planner. `prior_scans` are merged into its terrain map before
/// it is handed over (a map known in advance; autonav-kinematic's --known-field uses it to
/// judge the planner apart from what the cameras saw). Errors: as ValidateNavigationParams,
/// or a prior scan the assessor refuses (its message, with the scan's index).
Result<MobilityManager> MakeMobilityManager(const ParamSet& params,
                                            const std::vector<nav_core::RangeScan>& prior_scans = {});

}  // namespace rover::apl::mobility
