#include "rover/deploy/runner/judging.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <limits>

#include "rover/base/format.hpp"
#include "rover/deploy/plots.hpp"
#include "rover/deploy/runner/autonav_judging.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/msg/rendezvous.hpp"
#include "rover/sim/judge/passability.hpp"
#include "rover/sim/terrain/terrain.hpp"

namespace rover::deploy::runner {

namespace {
// Vertices of a rock's outline for the judge: chords sag ~ R (1 - cos(pi / n)), 1.4 mm at
// R = 0.3 m.
constexpr int kRockOutlineVertices = 32;


// The passability figures of AddMobilityFigures (judging.hpp).
void AddPassabilityFigures(const Scenario& scenario, const sim::world::World& world,
                           const std::vector<sim::judge::JudgeRock>& rocks, RunResult* result) {
  const auto& c = scenario.criteria;
  if (!c.target_xy) return;
  const bool any_tall = std::any_of(rocks.begin(), rocks.end(), [&](const auto& r) {
    return r.height > c.traversable_height;
  });
  if (!any_tall) return;
  const sim::terrain::HeightField& g = world.terrain.bare;
  sim::judge::PassabilityQuery q;
  q.start = {world.start_x, world.start_y};
  q.start_yaw = world.start_yaw;
  q.goal = *c.target_xy;
  q.tolerance = c.position_tolerance;
  q.area_min = {g.min_x(), g.min_y()};
  q.area_max = {g.max_x(), g.max_y()};
  q.traversable_height = c.traversable_height;
  const auto footprint = sim::judge::RoverFootprint::MerDefault();
  constexpr double kNan = std::numeric_limits<double>::quiet_NaN();
  for (const double margin : {0.10, 0.05, 0.0}) {
    q.margin = margin;
    const auto len = sim::judge::ContactFreePathLength(rocks, footprint, q);
    if (!len.ok()) return;  // a terrain larger than the search takes: no figure
    if (!len->has_value()) continue;
    char detail[160];
    std::snprintf(detail, sizeof detail,
                  "a path without hazard contact (judge's parts + %.2f m) from the start to "
                  "within %.2f m of the target, sim/judge passability",
                  margin, c.position_tolerance);
    result->figures.push_back({"passable", 1.0, kNan, "count", true, detail});
    result->figures.push_back(
        {"contact_free_margin", margin, kNan, "m", true, "the largest of 0.10, 0.05, 0 m"});
    result->figures.push_back({"contact_free_path", **len, kNan, "m", true, detail});
    if (**len > 0.0) {
      result->figures.push_back({"path_length_ratio", result->distance_driven / **len, kNan, "",
                                 true, "truth distance driven / contact_free_path"});
    }
    return;
  }
  result->figures.push_back(
      {"passable", 0.0, kNan, "count", true,
       "no path without hazard contact (judge's parts, no margin) reaches the target"});
}
}  // namespace

std::vector<sim::judge::JudgeRock> JudgeRocks(const sim::world::World& world) {
  std::vector<sim::judge::JudgeRock> rocks;
  for (const auto& r : world.terrain.rocks) {
    rocks.push_back({r.id, r.position.head<2>(), r.diameter, r.height,
                     sim::terrain::RockOutline(r, kRockOutlineVertices)});
  }
  return rocks;
}

Result<sim::judge::Judge> MakeJudge(const Scenario& scenario, const sim::world::World& world) {
  return sim::judge::Judge::Create(scenario.criteria, JudgeRocks(world));
}

void AddMobilityFigures(const Scenario& scenario, const sim::world::World& world, RunResult* result,
                        std::string* failure) {
  if (!result->mobility) return;
  const MobilityOutcome& mob = *result->mobility;
  const std::vector<sim::judge::JudgeRock> rocks = JudgeRocks(world);
  const auto figures =
      AutonavFigures(mob, result->truth_track, rocks, scenario.criteria.traversable_height,
                     HazardMapOptions{}, result->truth_yaw);
  result->figures.insert(result->figures.end(), figures.begin(), figures.end());
  AddPassabilityFigures(scenario, world, rocks, result);
  if (mob.keep_out.empty()) return;
  const double front = hwconfig::RoverDescription{}.GroundFootprint().max_x;
  const int entries = KeepOutEntries(result->truth_track, mob.keep_out, front);
  char detail[128];
  std::snprintf(detail, sizeof detail,
                "sim/truth points with the rover's front (%.2f m ahead of its centre) in a zone",
                front);
  result->criteria.push_back(
      {"keep_out_entries", static_cast<double>(entries), 0, "count", entries == 0, detail});
  if (entries > 0 && failure->empty()) {
    *failure = "keep_out_entries: " + std::to_string(entries) + " count (limit 0); " + detail;
  }
}

void AddRendezvousFigures(const sim::world::World& world, const std::optional<RendezvousLog>& log,
                          RunResult* result, std::string* failure) {
  if (!log) return;
  for (const RendezvousSample& s : log->samples) {
    const std::string name = msg::RendezvousPhaseName(static_cast<msg::RendezvousPhase>(s.phase));
    if (result->phases.empty() || result->phases.back().second != name) {
      result->phases.emplace_back(s.t, name);
    }
  }
  if (!world.terrain.lander) return;
  auto figures = RendezvousFigures(*log, *world.terrain.lander, world.terrain.rocks, *result);
  for (auto& f : figures) {
    if (f.name == "toward_distractor") {
      // Never drive toward a distractor: a criterion, not only a figure.
      f.limit = 0;
      f.pass = f.measured <= 0.0;
      result->criteria.push_back(f);
      if (!f.pass && failure->empty()) {
        *failure = "toward_distractor: " + FormatNumber(f.measured) +
                   " sightings put the lander estimate on a layered outcrop";
      }
      continue;
    }
    if (f.name == "on_deck" && log->expect_on_deck) {
      f.limit = 1;
      f.pass = f.measured >= 1.0;
      result->criteria.push_back(f);
      if (!f.pass && failure->empty()) {
        *failure = "on_deck: the run ended off the deck (" + log->end_phase +
                   (log->message.empty() ? "" : ": " + log->message) + ")";
      }
    } else {
      result->figures.push_back(f);
    }
  }
}

void ScoreRun(const sim::judge::Judge& judge,
              const std::vector<sim::judge::Criterion>& extra_figures, RunResult* result,
              std::string* failure) {
  const sim::judge::Verdict v = judge.Evaluate();
  result->criteria = v.criteria;
  result->distance_driven = v.distance_driven;
  result->estimate_error = v.estimate_error;
  result->odometry_only_error = v.odometry_only_error;
  result->figures = v.figures;
  result->hazard_contacts = v.contacts;
  result->figures.insert(result->figures.end(), extra_figures.begin(), extra_figures.end());
  if (failure->empty() && !v.pass) {
    const std::string all = v.FailureSummary();
    *failure = all.substr(0, all.find('\n'));
  }
}

Status WriteRunOutputs(RunResult* result, const std::string& failure,
                       const sim::terrain::Terrain& terrain,
                       const std::vector<Eigen::Vector2d>& planned) {
  if (!failure.empty() && result->failure.empty()) result->failure = failure;
  result->pass = result->failure.empty();
  const std::string path = result->run_dir + "/result.json";
  std::ofstream out(path);
  out << ToJson(*result).dump(2) << "\n";
  if (!out) return Unavailable("cannot write " + path);
  (void)WriteTrackMap(terrain, *result, planned, result->run_dir + "/map.png");
  (void)WriteErrorPlot(*result, result->run_dir + "/estimate_error.png");
  return Status::Ok();
}

}  // namespace rover::deploy::runner
