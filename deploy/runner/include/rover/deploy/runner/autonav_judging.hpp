#pragma once
/// @file
/// The judge's autonomous-driving figures (no DDS): hazard-map quality of the last
/// apl/goodness_map against the truth rock list, and the traverse rate and share of time
/// standing still from the truth track. Hazard contacts are the sim judge's (judge.hpp,
/// `hazard_contacts`: a rock taller than the traversable height touched by a wheel, the
/// suspension or the body; `footprint_overlaps` also counts the ones the rover straddled).
///
/// Hazard-map quality. Truth hazards are the rocks taller than the traversable height whose
/// centre lies within `path_radius` (5 m) of a point of the truth track. The rover saw a hazard
/// when the map's cell holding its centre is known (flag bit 0). A seen hazard is marked when a
/// known cell with goodness <= `obstacle_goodness` lies within its radius plus one cell of its
/// centre. recall = marked / seen. GESTALT's goodness is per rover position (the rover disc is
/// merged into every cell), so a cell marked obstacle is true when a truth hazard's footprint
/// lies within `reach` (the rover disc radius) of the cell centre; false-obstacle rate = marked
/// cells without one / all marked cells. Terrain hazards that are not rocks (steep crater
/// walls) count as false obstacles: the shipped autonav scenarios have no craters.
///
/// Motion. Over the track points with t in [t0, t1] (the command's window): distance = the
/// horizontal path length, traverse rate = distance / (t1 - t0) in m/h of simulated time, and
/// standing still = the share of the window's time in track intervals whose speed is below
/// `still_speed` and, when the track's yaws are given, whose yaw rate is below
/// `still_turn_rate` (a turn in place is driving, not standing still); turning in place = the
/// share below `still_speed` but turning at least that fast (0 without yaws).

#include <array>
#include <vector>

#include "rover/deploy/run_report.hpp"
#include "rover/sim/judge/judge.hpp"

namespace rover::deploy::runner {

using Track = std::vector<std::array<double, 3>>;  ///< t [s], x, y [m]

struct HazardMapOptions {
  double path_radius = 5.0;     ///< [m] hazards this close to the truth track count
  double reach = 1.3;           ///< [m] GESTALT's rover disc radius (MER: 2.6 m across)
  int obstacle_goodness = 0;    ///< cells with goodness <= this are marked obstacles
};

struct HazardMapQuality {
  int hazards_near_path = 0;  ///< truth hazards within path_radius of the track
  int hazards_seen = 0;       ///< ... whose centre cell the map knows
  int hazards_marked = 0;     ///< ... of those, marked as obstacles
  int obstacle_cells = 0;     ///< known cells marked obstacle
  int false_obstacle_cells = 0;  ///< ... with no truth hazard within reach
  /// hazards_marked / hazards_seen; NaN when nothing was seen.
  double Recall() const;
  /// false_obstacle_cells / obstacle_cells; NaN when no cell is marked.
  double FalseObstacleRate() const;
};

/// See the file comment. `rocks` may hold rocks of any height (the low ones are skipped).
HazardMapQuality EvaluateHazardMap(const GoodnessGrid& map,
                                   const std::vector<sim::judge::JudgeRock>& rocks,
                                   double traversable_height, const Track& truth_track,
                                   const HazardMapOptions& options = {});

struct MotionFigures {
  double distance = 0;            ///< [m]
  double duration = 0;            ///< [s] t1 - t0
  double traverse_rate = 0;       ///< [m/h]
  double standing_still = 0;      ///< share of the window's time, [0, 1]
  double turning_in_place = 0;    ///< share of the window's time, [0, 1]
};

/// See the file comment. Precondition: t1 >= t0.
/// `truth_yaw` [rad]: empty, or one yaw per track point.
MotionFigures EvaluateMotion(const Track& truth_track, double t0, double t1,
                             const std::vector<double>& truth_yaw = {}, double still_speed = 0.01,
                             double still_turn_rate = 0.01);

/// Truth track points at which the rover was inside a keep-out zone or closer to one than
/// `margin` (the rover's front overhang: its centre that close means its front is in). Zones are
/// simple polygons, either winding.
int KeepOutEntries(const Track& truth_track,
                   const std::vector<std::vector<Eigen::Vector2d>>& zones, double margin);

/// The figures result.json gets for a mobility run: mobility_steps, mobility_images,
/// traverse_rate (m/h), standing_still (%), turning_in_place (% , with yaws), then
/// hazard_map_recall and
/// hazard_map_false_obstacle_rate (%) when the last goodness map saw a hazard / marks a cell.
/// Not judged.
std::vector<sim::judge::Criterion> AutonavFigures(const MobilityOutcome& mobility,
                                                  const Track& truth_track,
                                                  const std::vector<sim::judge::JudgeRock>& rocks,
                                                  double traversable_height,
                                                  const HazardMapOptions& options = {},
                                                  const std::vector<double>& truth_yaw = {});

}  // namespace rover::deploy::runner
