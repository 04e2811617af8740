// gestalt-bench: GESTALT terrain assessment and arc evaluation beside straightforward reference
// implementations measured in the same run (ratios), with seed 002's Pentium III 500 MHz and
// Athena SDM timings for context.
//
// Input: 256 x 256 synthetic front-HAZCAM scans (range_synth.hpp) of a seeded rock field at
// 20 cm cells, 10 m x 10 m grid. Rows:
//   update, first scan     TerrainMap::Update into an empty map       vs ReferenceAssess (raw
//                          points of every disc fitted directly, no moment or prefix sums)
//   update, next scan      the incremental update 0.5 m further on (what drive-while-thinking
//                          runs every step)                            vs the same reference
//   arc evaluation         ArcEvaluator::Evaluate, 69 candidates       vs ReferenceEvaluate
//                          (every cell tested against every path)
// and a breakdown of the first update into its stages (binning points, plane fits from prefix
// sums, the filters, the layered merge). Times are medians over --repeat runs of the thread's
// CPU time (CLOCK_THREAD_CPUTIME_ID), so that other processes on a shared machine do not count;
// --wall measures wall-clock time instead.
#include <time.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "rover/testing/fakes/range_synth.hpp"
#include "reference_gestalt.hpp"
#include "rover/apl/gestalt/arc_evaluator.hpp"
#include "rover/apl/gestalt/terrain_map.hpp"

namespace g = rover::apl::gestalt;
namespace nc = rover::apl::nav_core;

namespace {

bool g_wall = false;

double Now() {
  if (g_wall) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch())
        .count();
  }
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

// Median time [s] of `repeat` runs of `body` (`setup` runs before each, untimed).
double Median(int repeat, const std::function<void()>& setup, const std::function<void()>& body) {
  std::vector<double> t;
  for (int r = 0; r < repeat; ++r) {
    setup();
    const double t0 = Now();
    body();
    t.push_back(Now() - t0);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

void Row(const char* name, double fast, double reference) {
  if (reference > 0.0) {
    std::printf("  %-34s %10.3f ms   reference %10.3f ms   ratio %7.1fx\n", name, 1e3 * fast,
                1e3 * reference, reference / fast);
  } else {
    std::printf("  %-34s %10.3f ms\n", name, 1e3 * fast);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"GESTALT update and arc evaluation beside reference implementations"};
  std::string preset = "vl2";
  std::uint64_t seed = 1;
  int repeat = 15;
  double noise = 0.002;
  app.add_option("--preset", preset, "rock field: vl1 or vl2")
      ->check(CLI::IsMember({"vl1", "vl2"}));
  app.add_option("--seed", seed, "terrain seed");
  app.add_option("--repeat", repeat, "runs per measurement (median)")->check(CLI::PositiveNumber);
  app.add_option("--noise", noise, "[m] synthetic range noise 1-sigma at 1 m");
  app.add_flag("--wall", g_wall, "measure wall-clock time instead of the thread's CPU time");
  CLI11_PARSE(app, argc, argv);

  const g::GestaltOptions options;
  const rover::sim::terrain::Terrain world = rover::testing::SeededRockField(preset.c_str(), seed, 24.0);
  rover::testing::PinholeCamera cam = rover::testing::FrontHazcam();
  cam.noise_at_1m = noise;
  const Eigen::Isometry3d pose0 = rover::testing::RoverPose(world.natural, 0.0, 0.0, 0.0);
  const Eigen::Isometry3d pose1 = rover::testing::RoverPose(world.natural, 0.5, 0.05, 0.1);
  const nc::RangeScan scan0 = rover::testing::SynthesizeScan(world.natural, cam, pose0);
  cam.seed = 2;
  const nc::RangeScan scan1 = rover::testing::SynthesizeScan(world.natural, cam, pose1);

  auto make = [&] {
    auto m = g::TerrainMap::Create(options);
    if (!m.ok()) {
      std::fprintf(stderr, "gestalt-bench: error: %s\n", m.status().message().c_str());
      std::exit(2);
    }
    return std::move(m).value();
  };
  g::TerrainMap map = make();
  nc::AssessmentStats stats0, stats1;
  const double t_grid = Median(
      repeat, [] {}, [&] { map = make(); });
  const double t_first = Median(
      repeat, [&] { map = make(); }, [&] { stats0 = *map.Update(scan0); });
  const double t_next = Median(
      repeat,
      [&] {
        map = make();
        (void)map.Update(scan0);
      },
      [&] { stats1 = *map.Update(scan1); });
  g::testing::ReferenceResult ref;
  const double t_ref = Median(
      std::max(3, repeat / 3), [] {}, [&] { ref = g::testing::ReferenceAssess(options, scan0); });

  // Agreement (the tests check it too; a benchmark of wrong code is worthless).
  g::TerrainMap check = make();
  (void)check.Update(scan0);
  int known = 0, differ = 0;
  for (std::size_t k = 0; k < ref.map.cell_count(); ++k) {
    if (!(ref.map.flags[k] & nc::kCellKnown)) continue;
    ++known;
    differ += std::abs(ref.map.goodness[k] - check.goodness_map().goodness[k]) > 1 ? 1 : 0;
  }

  // Stages of the first update, timed on their own with the library's pieces.
  const int n = options.grid_cells();
  g::Grid<g::Moments> moments(n, n);
  const double t_bin = Median(
      repeat, [&] { moments = g::Grid<g::Moments>(n, n); },
      [&] {
        const double r = options.cell_size;
        const int i0 = static_cast<int>(std::floor(pose0.translation().x() / r)) - n / 2;
        const int j0 = static_cast<int>(std::floor(pose0.translation().y() / r)) - n / 2;
        for (std::size_t k = 0; k < scan0.pixel_count(); ++k) {
          if (!scan0.valid[k]) continue;
          const Eigen::Vector3d p =
              pose0 * Eigen::Vector3d(scan0.xyz[3 * k], scan0.xyz[3 * k + 1], scan0.xyz[3 * k + 2]);
          const int i = static_cast<int>(std::floor(p.x() / r)) - i0;
          const int j = static_cast<int>(std::floor(p.y() / r)) - j0;
          if (moments.Contains(i, j)) moments.at(i, j).Add(p - pose0.translation());
        }
      });
  const g::DiscAssessor assessor(options);
  g::Grid<g::CellStats> cell_stats(n, n);
  g::Grid<int> covered(n, n, 0);
  for (std::size_t k = 0; k < moments.size(); ++k) {
    cell_stats[k] = g::StatsOf(moments[k], options.min_cell_points);
    covered[k] = cell_stats[k].covered ? 1 : 0;
  }
  g::RowPrefix<g::Moments> sums;
  g::RowPrefix<int> counts;
  int fitted = 0;
  const double t_fits = Median(
      repeat, [&] { fitted = 0; },
      [&] {
        sums.Build(moments);
        counts.Build(covered);
        for (int j = 0; j < n; ++j) {
          for (int i = 0; i < n; ++i) {
            if (counts.DiscSum(i, j, assessor.rover_disc()) <
                options.min_coverage * assessor.rover_disc().cell_count())
              continue;
            fitted += g::FitPlane(sums.DiscSum(i, j, assessor.rover_disc()), options.eigen_ratio).ok
                          ? 1
                          : 0;
          }
        }
      });
  g::Grid<std::int16_t> fresh(n, n, g::LayeredGoodness::kAbsent);
  const double t_assess = Median(
      repeat, [] {},
      [&] {
        for (int j = 0; j < n; ++j) {
          for (int i = 0; i < n; ++i) {
            const g::CellAssessment a =
                assessor.Assess(i, j, sums.DiscSum(i, j, assessor.rover_disc()),
                                counts.DiscSum(i, j, assessor.rover_disc()), cell_stats);
            fresh.at(i, j) = a.known() ? a.goodness : g::LayeredGoodness::kAbsent;
          }
        }
      });
  g::LayeredGoodness layers;
  const double t_layers = Median(
      repeat, [&] { layers = g::LayeredGoodness(n, n, options.num_layers); },
      [&] { layers.Merge(fresh, g::Grid<std::uint8_t>(n, n, 0)); });

  // Arc evaluation toward a goal 8 m ahead, 1 m left.
  auto evaluator = g::ArcEvaluator::Create(options);
  nc::ArcRequest req;
  req.site_from_rover = pose0;
  req.goal = {8.0, 1.0};
  req.goal_tolerance = 0.5;
  nc::ArcEvaluation eval, ref_eval;
  const double t_arcs = Median(
      repeat, [] {}, [&] { eval = *evaluator->Evaluate(check.goodness_map(), req); });
  const double t_ref_arcs = Median(
      std::max(3, repeat / 3), [] {},
      [&] { ref_eval = g::testing::ReferenceEvaluate(options, check.goodness_map(), req); });
  int vote_differ = 0;
  for (std::size_t k = 0; k < eval.merged.size(); ++k) {
    vote_differ += eval.merged[k].goodness != ref_eval.merged[k].goodness ? 1 : 0;
  }

  std::printf(
      "gestalt-bench: %s seed %llu, 256 x 256 synthetic HAZCAM scan, %d x %d grid of %.0f cm "
      "cells, %zu candidates, median of %d runs (%s time)\n",
      preset.c_str(), static_cast<unsigned long long>(seed), n, n, 100 * options.cell_size,
      eval.candidates.size(), repeat, g_wall ? "wall-clock" : "thread CPU");
  std::printf(
      "  scan: %d valid pixels, %d points used, %d cells touched (%d at the FOV edge), "
      "%d cells assessed (%d obstacle, %d unknown); next scan: %d cells assessed\n",
      stats0.points_total, stats0.points_used, stats0.cells_touched, stats0.cells_fov_edge,
      stats0.cells_assessed, stats0.cells_obstacle, stats0.cells_unknown, stats1.cells_assessed);
  std::printf(
      "  agreement with the references: %d of %d known cells differ by more than 1; "
      "%d of %zu merged votes differ; chosen %d vs %d\n",
      differ, known, vote_differ, eval.merged.size(), eval.chosen, ref_eval.chosen);
  std::printf("\nthis machine:\n");
  Row("grid initialisation", t_grid, 0.0);
  Row("update, first scan (empty map)", t_first, t_ref);
  Row("update, next scan (incremental)", t_next, t_ref);
  Row("  bin points into cell moments", t_bin, 0.0);
  Row("  plane fits, all cells (prefix sums)", t_fits, 0.0);
  Row("  fits + filters, all cells", t_assess, 0.0);
  Row("  layered merge (7 layers)", t_layers, 0.0);
  Row("arc evaluation", t_arcs, t_ref_arcs);
  Row("update + arc evaluation", t_next + t_arcs, t_ref + t_ref_arcs);
  std::printf(
      "  -> %.0f update+vote cycles per second (drive-while-thinking budget at 1 step/s: %.1f "
      "%%)\n",
      1.0 / (t_next + t_arcs), 100.0 * (t_next + t_arcs));

  // Seed 002, Table 3 (Pentium III 500 MHz, 20 x 20 cm cells, 9 m x 9 m grid, one real image pair)
  // and Table 2 (Athena SDM R3000 12 MHz, 20 cm cells, 10 m x 10 m grid).
  const double p3_init = 0.00611, p3_fit = 0.14, p3_trav = 0.0192, p3_votes = 0.0454;
  std::printf(
      "\nseed 002 for context (not like for like: other CPU, grid and image, no layers):\n");
  std::printf(
      "  Pentium III 500 MHz (Table 3, 20 cm): grid init %.1f ms, fit planes %.0f ms, "
      "traversability %.1f ms, path votes %.1f ms; GESTALT total %.0f ms\n",
      1e3 * p3_init, 1e3 * p3_fit, 1e3 * p3_trav, 1e3 * p3_votes,
      1e3 * (p3_fit + p3_trav + p3_votes));
  std::printf(
      "  Athena R3000 12 MHz (Table 2): add to grid 2.6 s, planes 5.2 s, traversability "
      "2.34 s, path votes 3.0 s; total 13.1 s\n");
  std::printf(
      "  ours vs Pentium III: update %.0fx faster than its fit planes + traversability, "
      "arc evaluation %.0fx faster than its path votes\n",
      (p3_fit + p3_trav) / t_first, p3_votes / t_arcs);
  return 0;
}
