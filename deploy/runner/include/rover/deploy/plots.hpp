#pragma once
/// @file
/// Plots a person would rather look at than read, written into each run folder:
///  - `map.png`: top-down terrain map with rocks, the driven path from truth (green, widest,
///    drawn first), the odometry-only path (purple), the stack's estimated path (orange,
///    narrower), the chosen arcs of a mobility run (pink, 1 m of each from where it was chosen)
///    and the planned path (blue, dashed, on top), over the run's last goodness map (grey from
///    black = obstacle to white = perfect; unknown cells show the terrain; bounds dashed);
///  - `estimate_error.png`: horizontal position error [m] and heading error [deg] of the pose
///    estimate against truth over simulated time.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/deploy/run_report.hpp"
#include "rover/sim/terrain/top_down_map.hpp"

namespace rover::sim::terrain {
struct Terrain;
}

namespace rover::deploy {

/// The goodness map as a map layer: known cells (flag bit 0) grey by goodness.
sim::terrain::MapCellLayer GoodnessLayer(const GoodnessGrid& grid);

/// What map.png draws of a run: the title (scenario, seed, verdict, task outcome), the last
/// goodness map, the truth, odometry-only and estimated paths, the chosen arcs, a phased task's
/// phases and the planned path (dashed), each in the legend beside the map.
sim::terrain::MapOptions TrackMapOptions(const RunResult& run,
                                         const std::vector<Eigen::Vector2d>& planned);
/// The map of TrackMapOptions, written as a PNG.
Status WriteTrackMap(const sim::terrain::Terrain& terrain, const RunResult& run,
                     const std::vector<Eigen::Vector2d>& planned, const std::string& path);

Status WriteErrorPlot(const RunResult& run, const std::string& path);

}  // namespace rover::deploy
