// gestalt-demo: a kinematic autonav loop on a synthetic rock field, to look at GESTALT at work.
//
// The rover (a point that follows the chosen primitive exactly) starts at the origin of a seeded
// VL-1 or VL-2 field, takes a synthetic front-HAZCAM scan, updates the map, votes, drives
// `--step` metres of the chosen arc (or turns in place) and repeats until it is within 0.5 m of
// the goal or out of steps. Prints one line per step and the hazard-map quality against the
// truth rocks; writes the last goodness map with rocks, rover and arcs as a PNG.
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>

#include "goodness_render.hpp"
#include "rover/testing/fakes/range_synth.hpp"
#include "rover/apl/gestalt/arc_evaluator.hpp"
#include "rover/apl/gestalt/terrain_map.hpp"
#include "truth_check.hpp"

namespace g = rover::apl::gestalt;
namespace nc = rover::apl::nav_core;

int main(int argc, char** argv) {
  CLI::App app{"GESTALT on a synthetic rock field: drive, map, vote, render"};
  std::string preset = "vl2";
  std::uint64_t seed = 3;
  double goal_x = 12.0, goal_y = 0.0, step = 0.75;
  int max_steps = 40;
  std::string out = "gestalt_demo.png";
  app.add_option("--preset", preset, "rock field: vl1 or vl2")
      ->check(CLI::IsMember({"vl1", "vl2"}));
  app.add_option("--seed", seed, "terrain seed");
  app.add_option("--goal-x", goal_x, "[m] goal x (site)");
  app.add_option("--goal-y", goal_y, "[m] goal y (site)");
  app.add_option("--step", step, "[m] arc length driven per step")->check(CLI::PositiveNumber);
  app.add_option("--steps", max_steps, "maximum number of steps")->check(CLI::PositiveNumber);
  app.add_option("--out", out, "PNG to write");
  bool flat = false;
  double step_k = g::GestaltOptions{}.step_sigma_k, noise = 0.002;
  app.add_option("--step-sigma-k", step_k, "GESTALT step_sigma_k");
  app.add_option("--noise", noise, "[m] synthetic range noise 1-sigma at 1 m (grows with range^2)");
  app.add_flag("--flat", flat, "a flat world without rocks (a sanity check: all should be safe)");
  CLI11_PARSE(app, argc, argv);

  g::GestaltOptions options;
  options.step_sigma_k = step_k;
  auto map_or = g::TerrainMap::Create(options);
  auto eval_or = g::ArcEvaluator::Create(options);
  if (!map_or.ok() || !eval_or.ok()) {
    std::fprintf(stderr, "gestalt-demo: error: %s\n", map_or.status().message().c_str());
    return 2;
  }
  g::TerrainMap& map = *map_or;
  const g::ArcEvaluator& evaluator = *eval_or;
  const rover::sim::terrain::Terrain world =
      flat ? rover::testing::FlatWorld(2.0 * goal_x + 12.0)
           : rover::testing::SeededRockField(preset.c_str(), seed, 2.0 * goal_x + 12.0);
  rover::testing::PinholeCamera cam = rover::testing::FrontHazcam();
  cam.noise_at_1m = noise;

  double x = 0.0, y = 0.0, yaw = 0.0;
  nc::ArcEvaluation last;
  Eigen::Isometry3d pose = rover::testing::RoverPose(world.natural, x, y, yaw);
  double driven = 0.0;
  std::vector<Eigen::Vector2d> path{{x, y}};
  for (int n = 0; n < max_steps; ++n) {
    pose = rover::testing::RoverPose(world.natural, x, y, yaw);
    cam.seed = seed * 1000 + n;
    const nc::RangeScan scan = rover::testing::SynthesizeScan(world.natural, cam, pose);
    const auto t0 = std::chrono::steady_clock::now();
    auto stats = map.Update(scan);
    const auto t1 = std::chrono::steady_clock::now();
    nc::ArcRequest req;
    req.site_from_rover = pose;
    req.goal = {goal_x, goal_y};
    req.goal_tolerance = 0.5;
    auto e = evaluator.Evaluate(map.goodness_map(), req);
    const auto t2 = std::chrono::steady_clock::now();
    if (!stats.ok() || !e.ok()) {
      std::fprintf(stderr, "gestalt-demo: error: %s\n",
                   (stats.ok() ? e.status() : stats.status()).message().c_str());
      return 1;
    }
    last = *e;
    if (n == 0) {
      // Which filter limits the first scan's assessed cells.
      int limited[3] = {0, 0, 0};
      double sum_t = 0, sum_r = 0, sum_s = 0;
      int known = 0;
      double sum_truth = 0.0;
      int missed = 0, false_hits = 0, truth_hazard = 0;
      for (std::size_t ci = 0; ci < map.assessments().size(); ++ci) {
        const g::CellAssessment& a = map.assessments()[ci];
        if (a.status != g::AssessStatus::kAssessed) continue;
        const Eigen::Vector2d cc = map.goodness_map().CellCenter(
            static_cast<int>(ci % static_cast<std::size_t>(map.goodness_map().width)),
            static_cast<int>(ci / static_cast<std::size_t>(map.goodness_map().width)));
        double tallest = 0.0;
        for (const auto& rock : world.rocks) {
          if ((rock.position.head<2>() - cc).norm() <= 1.3 + 0.5 * rock.diameter) {
            tallest = std::max(tallest, rock.height);
          }
        }
        sum_truth += tallest;
        if (tallest >= 0.25 && a.step < options.max_step) ++missed;
        if (tallest < 0.15 && a.step >= options.max_step) ++false_hits;
        if (tallest >= 0.25) ++truth_hazard;
        ++known;
        sum_t += a.tilt * 180.0 / 3.14159265358979;
        sum_r += a.roughness;
        sum_s += a.step;
        if (a.goodness == a.tilt_goodness) ++limited[0];
        if (a.goodness == a.roughness_goodness) ++limited[1];
        if (a.goodness == a.step_goodness) ++limited[2];
      }
      if (known > 0) {
        std::printf(
            "first scan: %d cells assessed; mean tilt %.1f deg, roughness %.3f m, step %.3f m; "
            "limited by tilt %d, roughness %d, step %d; truth: mean tallest rock in the disc %.3f "
            "m; missed %d of %d, false %d\n",
            known, sum_t / known, sum_r / known, sum_s / known, limited[0], limited[1], limited[2],
            sum_truth / known, missed, truth_hazard, false_hits);
      }
    }
    const double ms_update = std::chrono::duration<double, std::milli>(t1 - t0).count();
    const double ms_votes = std::chrono::duration<double, std::milli>(t2 - t1).count();
    std::printf(
        "step %2d at (%6.2f, %6.2f) yaw %6.1f deg: %5d pts, %4d cells assessed (%3d obstacle) "
        "update %.2f ms votes %.2f ms -> ",
        n, x, y, yaw * 180.0 / 3.14159265358979, stats->points_used, stats->cells_assessed,
        stats->cells_obstacle, ms_update, ms_votes);
    if (e->mode == nc::GoalMode::kReached) {
      std::printf("goal reached after %.1f m\n", driven);
      break;
    }
    if (!e->has_choice()) {
      std::printf("no safe path\n");
      break;
    }
    const nc::Candidate& c = e->choice();
    const nc::Vote& v = e->merged[static_cast<std::size_t>(e->chosen)];
    if (c.kind == nc::MotionKind::kPointTurn) {
      std::printf("turn %.0f deg (vote %d)\n", c.turn_angle * 180.0 / 3.14159265358979, v.goodness);
      yaw += c.turn_angle;
      continue;
    }
    std::printf("%s arc k = %+.2f (vote %d)%s\n", c.direction > 0 ? "fwd" : "bwd", c.curvature,
                v.goodness, e->all_paths_safe ? " [all paths safe]" : "");
    const double len = std::min(step, c.length);
    const Eigen::Vector2d p = g::ArcPoint(c.curvature, c.direction, len);
    x += std::cos(yaw) * p.x() - std::sin(yaw) * p.y();
    y += std::sin(yaw) * p.x() + std::cos(yaw) * p.y();
    yaw += c.direction * c.curvature * len;
    driven += len;
    path.emplace_back(x, y);
  }
  g::testing::TruthCheckOptions truth;
  truth.excuse_height = 0.15;
  const g::testing::HazardQuality q = g::testing::CompareWithTruth(
      map.goodness_map(), world, pose.translation().head<2>(), options, truth);
  std::printf(
      "hazard map within 5 m: rocks >= 0.25 m marked %d / %d; obstacle cells %d, of which "
      "%d with no rock >= 0.15 m within reach\n",
      q.hazards_marked, q.hazards_seen, q.obstacle_cells, q.false_obstacles);
  g::testing::RenderOptions ro;
  cv::Mat img = g::testing::RenderGoodnessMap(map.goodness_map(), ro);
  g::testing::DrawRocks(map.goodness_map(), world.rocks, ro, &img);
  g::testing::DrawPath(map.goodness_map(), path, ro, &img);
  g::testing::DrawArcs(map.goodness_map(), pose, last, ro, &img);
  g::testing::DrawRover(map.goodness_map(), pose, ro, &img);
  if (rover::Status s = g::testing::WritePng(img, out); !s.ok()) {
    std::fprintf(stderr, "gestalt-demo: error: %s\n", s.message().c_str());
    return 1;
  }
  std::printf("wrote %s\n", out.c_str());
  return 0;
}
