// enav-demo: the ENav-class planner on a synthetic rock field, to look at it at work.
//
// A kinematic rover (it follows each chosen first segment exactly) starts at the origin of a
// seeded VL-1 or VL-2 field (sim/terrain's presets), takes a ray-cast front-HAZCAM scan, merges it
// into the height map, plans, drives the first segment (a turn, or `--step` metres of the first
// arc) and repeats until within 0.5 m of the goal, out of steps or without a choice. Prints one
// line per step (CPU time of the update and the plan, paths ranked, clearance checks) and writes
// a picture of the last decision: left, the height map's hazard classes with the true rock
// outlines, the path tree (grey), the paths checked and refused (red), the chosen one (blue) and
// the path driven (white); right, the cost-to-go field.
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "decision_picture.hpp"
#include "rover/apl/enav/enav_planner.hpp"
#include "rover/apl/enav/height_terrain.hpp"
#include "rover/base/cpu_time.hpp"
#include "rover/testing/fakes/range_synth.hpp"

namespace en = rover::apl::enav;
namespace nc = rover::apl::nav_core;
namespace geo = rover::geometry;

namespace {

double CpuMs() { return 1e3 * rover::ThreadCpuSeconds(); }

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"The ENav-class planner on a synthetic rock field: map, plan, drive, render"};
  std::string preset = "vl2";
  std::uint64_t seed = 3;
  double goal_x = 12.0, goal_y = 0.0, step = 0.5, noise = 0.0036;
  int max_steps = 60;
  std::string out = "enav_demo.png";
  app.add_option("--preset", preset, "rock field: vl1 or vl2")->check(CLI::IsMember({"vl1", "vl2"}));
  app.add_option("--seed", seed, "terrain seed");
  app.add_option("--goal-x", goal_x, "[m] goal x (site)");
  app.add_option("--goal-y", goal_y, "[m] goal y (site)");
  app.add_option("--step", step, "[m] arc length driven per step")->check(CLI::PositiveNumber);
  app.add_option("--steps", max_steps, "maximum number of steps")->check(CLI::PositiveNumber);
  app.add_option("--noise", noise, "[m] range noise sigma at 1 m (grows with range^2)");
  app.add_option("--out", out, "PNG to write");
  CLI11_PARSE(app, argc, argv);

  en::EnavOptions options;
  options.stereo_noise_coeff = noise;
  auto terrain_or = en::HeightTerrain::Create(options);
  auto planner_or = en::EnavPlanner::Create(options);
  if (!terrain_or.ok() || !planner_or.ok()) {
    std::fprintf(stderr, "enav-demo: error: %s\n",
                 (terrain_or.ok() ? planner_or.status() : terrain_or.status()).message().c_str());
    return 2;
  }
  en::HeightTerrain& terrain = *terrain_or;
  const en::EnavPlanner& planner = *planner_or;
  const rover::sim::terrain::Terrain world =
      rover::testing::SeededRockField(preset.c_str(), seed, 2.0 * goal_x + 12.0);
  rover::testing::PinholeCamera cam = rover::testing::FrontHazcam();
  cam.noise_at_1m = noise;

  geo::Pose2 rover;
  std::vector<Eigen::Vector2d> driven_path{rover.xy()};
  double driven = 0.0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  for (int n = 0; n < max_steps; ++n) {
    pose = rover::testing::RoverPose(world.natural, rover.x, rover.y, rover.heading);
    cam.seed = seed * 1000 + static_cast<std::uint64_t>(n);
    const nc::RangeScan scan = rover::testing::SynthesizeScan(world.natural, cam, pose);
    const double t0 = CpuMs();
    auto stats = terrain.Update(scan);
    const double t1 = CpuMs();
    nc::ArcRequest req;
    req.site_from_rover = pose;
    req.goal = {goal_x, goal_y};
    req.goal_tolerance = 0.5;
    auto e = planner.Plan(terrain, req);
    const double t2 = CpuMs();
    if (!stats.ok() || !e.ok()) {
      std::fprintf(stderr, "enav-demo: error: %s\n",
                   (stats.ok() ? e.status() : stats.status()).message().c_str());
      return 1;
    }
    std::printf("step %2d at (%6.2f, %6.2f) heading %6.1f deg: update %.1f ms, plan %.1f ms, "
                "%d ranked, %d checked -> ",
                n, rover.x, rover.y, rover.heading * 180 / M_PI, t1 - t0, t2 - t1,
                e->candidates_ranked, e->clearance_checks);
    if (e->mode == nc::GoalMode::kReached) {
      std::printf("goal reached after %.1f m\n", driven);
      break;
    }
    if (!e->has_choice()) {
      std::printf("no safe path\n");
      break;
    }
    const nc::Candidate& c = e->choice();
    if (c.kind == nc::MotionKind::kPointTurn) {
      std::printf("turn %.0f deg\n", c.turn_angle * 180 / M_PI);
      rover = geo::Turned(rover, c.turn_angle);
      continue;
    }
    std::printf("%s arc k = %+.2f\n", c.direction > 0 ? "fwd" : "bwd", c.curvature);
    rover = geo::AlongArc(rover, c.curvature, c.direction * std::min(step, c.length));
    driven += std::min(step, c.length);
    driven_path.push_back(rover.xy());
  }

  // The picture of the last decision.
  std::vector<en::PictureRock> rocks;
  for (const auto& rock : world.rocks) {
    if (rock.height > 0.2) rocks.push_back({rock.position.head<2>(), 0.5 * rock.diameter});
  }
  const cv::Mat both = en::DrawDecision(planner, *terrain.height_map(), options.rover,
                                        driven_path, rocks);
  if (!cv::imwrite(out, both)) {
    std::fprintf(stderr, "enav-demo: error: could not write %s\n", out.c_str());
    return 1;
  }
  std::printf("wrote %s (%.0f x %.0f m about the rover; left hazards and tree, right cost-to-go)\n",
              out.c_str(), 2 * en::PictureOptions{}.half, 2 * en::PictureOptions{}.half);
  return 0;
}
