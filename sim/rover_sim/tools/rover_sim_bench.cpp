// rover-sim-bench: the simulator's real-time factor while driving 20 m on flat ground, up a 15 deg
// slope and through a VL-2 rock field: physics + sensors, then again with one NAVCAM stereo pair
// rendered every 2 s of simulated time; milliseconds per rendered pair; peak memory.
// Baseline in the same run: real time itself (factor 1) -- the goal is physics + sensors >= 10x.
#include <sys/resource.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <string>
#include <vector>

#include "rover/base/clock.hpp"
#include "rover/sim/render/cameras.hpp"
#include "rover/sim/render/renderer.hpp"
#include "rover/sim/rover_sim/sim_engine.hpp"

namespace {
using namespace rover;
using namespace rover::sim::render;
using namespace rover::sim::rover_sim;
using namespace rover::sim::terrain;

double PeakRssMb() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss / 1024.0;
}

struct Case {
  const char* name;
  const char* terrain_yaml;
};

struct Outcome {
  double rtf = 0, distance = 0, sim_s = 0, ms_per_pair = 0;
  int pairs = 0;
};

Result<Outcome> Drive(const Case& c, double distance_m, double max_sim_s, double render_every_s) {
  ParamSet p("bench");
  SimEngine::DeclareParams(p);
  ROVER_RETURN_IF_ERROR(p.LoadYamlSections(c.terrain_yaml, c.name, {"terrain", "rover"}));
  ROVER_RETURN_IF_ERROR(p.Validate());
  auto engine = SimEngine::Create(p);
  if (!engine.ok()) return engine.status();
  SimEngine& e = **engine;
  std::unique_ptr<Renderer> renderer;
  std::vector<StereoCameraDefinition> cams;
  if (render_every_s > 0) {
    auto r = Renderer::Create(std::make_shared<const Terrain>(e.world().terrain), RenderOptions{});
    if (!r.ok()) return r.status();
    renderer = std::move(*r);
    cams = DefaultStereoCameras(1024);
  }
  hw::MotorGoals g;
  for (int i = 0; i < 6; ++i) {
    const double cpr = e.hardware().motors[static_cast<std::size_t>(i)].CountsPerRad();
    g.goals[static_cast<std::size_t>(i)].mode = hw::MotorMode::kVelocity;
    g.goals[static_cast<std::size_t>(i)].velocity = static_cast<std::int32_t>(0.4 * cpr);  // 5 cm/s
  }
  ROVER_RETURN_IF_ERROR(e.ApplyMotorGoals(g));
  Outcome o;
  double next_render = render_every_s;
  double render_ms = 0;
  const Eigen::Vector2d start = e.physics().Readings().chassis.pose_site.translation().head<2>();
  const Time t0 = MonotonicNow();
  while (e.time() < max_sim_s) {
    auto out = e.Step();
    if (!out.ok()) return out.status();
    if (out->truth) {
      o.distance = (out->truth->pose.translation().head<2>() - start).norm();
      if (o.distance >= distance_m) break;
    }
    if (renderer && e.time() >= next_render) {
      next_render += render_every_s;
      const auto r = e.physics().Readings();
      auto def = FindStereoCamera(cams, "navcam");
      auto spec = MakeCameraPairSpec(*def, MastState{0.0, -0.5});
      const Time r0 = MonotonicNow();
      auto images = renderer->RenderStereoPair(r.chassis.pose_site, *spec, static_cast<std::uint64_t>(o.pairs + 1));
      if (!images.ok()) return images.status();
      render_ms += ToSeconds(MonotonicNow() - r0) * 1e3;
      ++o.pairs;
    }
  }
  const double wall = ToSeconds(MonotonicNow() - t0);
  o.sim_s = e.time();
  o.rtf = o.sim_s / wall;
  o.ms_per_pair = o.pairs ? render_ms / o.pairs : 0;
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"rover-sim-bench: simulator real-time factor with and without rendering"};
  double distance = 20, render_sim_s = 60;
  app.add_option("--distance", distance, "[m] drive length for physics + sensors")->check(CLI::Range(1.0, 200.0));
  app.add_option("--render-sim-seconds", render_sim_s,
                 "[s] simulated time of the runs with rendering (the factor is steady, so a "
                 "shorter run measures it)")->check(CLI::Range(4.0, 1000.0));
  CLI11_PARSE(app, argc, argv);
  const std::vector<Case> cases = {
      {"flat", "terrain: {size_x: 60, size_y: 20, center_x: 20, resolution: 0.04, hills: {amplitude: 0}, "
               "craters: {count: 0}, rocks: {preset: none}, soil: {sand_fraction: 0, bedrock_fraction: 0}}\n"},
      {"slope15", "terrain: {size_x: 60, size_y: 20, center_x: 20, resolution: 0.04, slope: {angle_deg: 15}, "
                  "hills: {amplitude: 0}, craters: {count: 0}, rocks: {preset: none}, "
                  "soil: {sand_fraction: 0, bedrock_fraction: 0}}\n"},
      {"vl2", "terrain: {size_x: 60, size_y: 30, center_x: 20, resolution: 0.04, seed: 4, "
              "rocks: {preset: vl2}}\n"},
  };
  std::printf("rover-sim-bench: drive at 5 cm/s; real-time factor = simulated s / wall s (baseline "
              "1.0 = real time; goal for physics + sensors >= 10)\n\n");
  std::printf("%-9s %-26s %8s %9s %10s %12s\n", "terrain", "case", "dist m", "sim s", "x real", "ms / pair");
  int rc = 0;
  for (const auto& c : cases) {
    auto a = Drive(c, distance, distance / 0.05 * 3, 0);
    if (!a.ok()) {
      std::printf("%-9s error: %s\n", c.name, a.status().message().c_str());
      rc = 1;
      continue;
    }
    std::printf("%-9s %-26s %8.2f %9.1f %10.2f %12s\n", c.name, "physics + sensors", a->distance,
                a->sim_s, a->rtf, "-");
    auto b = Drive(c, 1e9, render_sim_s, 2.0);
    if (!b.ok()) {
      std::printf("%-9s %-26s unavailable: %s\n", c.name, "+ NAVCAM pair every 2 s", b.status().message().c_str());
      continue;
    }
    std::printf("%-9s %-26s %8.2f %9.1f %10.2f %12.1f\n", c.name, "+ NAVCAM pair every 2 s",
                b->distance, b->sim_s, b->rtf, b->ms_per_pair);
  }
  std::printf("\npeak resident memory: %.0f MB\n", PeakRssMb());
  return rc;
}
