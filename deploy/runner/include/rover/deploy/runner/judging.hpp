#pragma once
/// @file
/// Judging a run and writing its outputs: the judge holds the scenario's criteria against the
/// world's rocks (the recorder feeds it truth and estimates while the run goes); at the end it
/// scores the run into the RunResult, and the run folder gets result.json, map.png and
/// estimate_error.png.

#include <optional>

#include "rover/deploy/runner/rendezvous_judging.hpp"
#include <Eigen/Core>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/deploy/run_report.hpp"
#include "rover/deploy/scenario.hpp"
#include "rover/sim/judge/judge.hpp"
#include "rover/sim/world/world.hpp"

namespace rover::deploy::runner {

/// The world's rocks as the judge sees them (outline polygons of 32 vertices).
std::vector<sim::judge::JudgeRock> JudgeRocks(const sim::world::World& world);

/// The judge of a run: `scenario.criteria` over the world's rocks.
Result<sim::judge::Judge> MakeJudge(const Scenario& scenario, const sim::world::World& world);

/// Scores the run into `*result`: every criterion, the distance driven, the estimate and
/// odometry-only errors over time, the judge's figures followed by `extra_figures` (the
/// recorder's). When `*failure` is empty and a criterion failed, it becomes the first line of the
/// judge's failure summary.
void ScoreRun(const sim::judge::Judge& judge,
              const std::vector<sim::judge::Criterion>& extra_figures, RunResult* result,
              std::string* failure);

/// The lander-return figures (rendezvous_judging.hpp) of `log`, when the task kept one and the
/// world has a lander, into result->figures; the on_deck figure becomes a criterion when the
/// task expected to end on the deck (a failed one sets *failure when it is still empty).
void AddRendezvousFigures(const sim::world::World& world, const std::optional<RendezvousLog>& log,
                          RunResult* result, std::string* failure);

/// For a mobility run (result.mobility set): appends autonav_judging.hpp's figures (traverse
/// rate, standing still, hazard-map recall and false-obstacle rate against the world's rocks
/// taller than the scenario's criteria.traversable_height) to result.figures and, when the
/// command had keep-out zones, the criterion keep_out_entries (truth track points with the
/// rover's front, hwconfig's ground footprint, in a zone; limit 0). A failed criterion becomes
/// `*failure` when that is empty.
/// With a target (criteria.target_xy) and a rock taller than the traversable height in the
/// world, the field's passability (sim/judge passability.hpp, the judge's contact parts, over
/// the whole terrain, to within the target's tolerance), tried with margins 0.10, 0.05 and 0 m:
/// `passable` (1 when a contact-free path exists at margin 0, else 0), `contact_free_margin`
/// (the largest of the three margins with such a path), `contact_free_path` (its length, m) and
/// `path_length_ratio` (the truth distance driven over that length); the last three are left out
/// when no margin has a path.
void AddMobilityFigures(const Scenario& scenario, const sim::world::World& world, RunResult* result,
                        std::string* failure);

/// Sets result.failure (unless already set) and result.pass, then writes result.json, map.png
/// (terrain, rocks, `planned`, the tracks) and estimate_error.png into result.run_dir. The plots
/// are best effort: an error there does not fail the run; result.json must be written.
Status WriteRunOutputs(RunResult* result, const std::string& failure,
                       const sim::terrain::Terrain& terrain,
                       const std::vector<Eigen::Vector2d>& planned);

}  // namespace rover::deploy::runner
