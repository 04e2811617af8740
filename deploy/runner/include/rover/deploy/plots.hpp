#pragma once
/// @file
/// Plots a person would rather look at than read, written into each run folder:
///  - `map.png`: top-down terrain map with rocks, the planned path (blue), the driven path from
///    truth (green) and the stack's estimated path (orange);
///  - `estimate_error.png`: horizontal position error [m] and heading error [deg] of the pose
///    estimate against truth over simulated time.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/deploy/run_report.hpp"

namespace rover::sim {
struct Terrain;
}

namespace rover::deploy {

Status WriteTrackMap(const sim::Terrain& terrain, const RunResult& run,
                     const std::vector<Eigen::Vector2d>& planned, const std::string& path);

Status WriteErrorPlot(const RunResult& run, const std::string& path);

}  // namespace rover::deploy
