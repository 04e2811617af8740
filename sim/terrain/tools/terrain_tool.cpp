// rover-terrain: generates a terrain from a scenario YAML (keys terrain.*, lander.*,
// science_targets) and writes its top-down map as a PNG, with a summary on stdout.
//
//   rover-terrain --params scenario.yaml --set terrain.rocks.preset=vl2 --out map.png
//   rover-terrain --help-params
#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "rover/base/params.hpp"
#include "rover/sim/terrain/rock_model.hpp"
#include "rover/sim/terrain/terrain.hpp"
#include "rover/sim/terrain/top_down_map.hpp"

int main(int argc, char** argv) {
  CLI::App app{"Generate a seeded Mars-like terrain and draw its top-down map"};
  std::vector<std::string> files, sets;
  std::string out = "terrain.png", title;
  bool help_params = false, print_params = false;
  int max_pixels = 2000;
  double pixels_per_metre = 0.0;
  app.add_option("--params", files, "scenario YAML file(s), applied in order");
  app.add_option("--set", sets, "override key=value (YAML value), e.g. terrain.seed=7");
  app.add_option("--out", out, "output PNG path");
  app.add_option("--title", title, "title drawn on the map");
  app.add_option("--max-pixels", max_pixels, "longest side of the map image");
  app.add_option("--pixels-per-metre", pixels_per_metre, "map scale (0: one pixel per cell)");
  app.add_flag("--help-params", help_params, "describe every parameter and exit");
  app.add_flag("--print-params", print_params, "print the effective parameters");
  CLI11_PARSE(app, argc, argv);

  rover::ParamSet ps("sim_terrain");
  rover::sim::terrain::DeclareTerrainParams(ps);
  rover::sim::terrain::DeclareLanderParams(ps);
  rover::sim::terrain::DeclareScienceTargets(ps);
  if (help_params) {
    std::printf("%s", ps.DescribeAll().c_str());
    return 0;
  }
  for (const auto& f : files) {
    if (auto s = ps.LoadYamlFile(f); !s.ok()) {
      std::fprintf(stderr, "error: %s\n", s.message().c_str());
      return 2;
    }
  }
  for (const auto& a : sets) {
    if (auto s = ps.SetFromString(a); !s.ok()) {
      std::fprintf(stderr, "error: %s\n", s.message().c_str());
      return 2;
    }
  }
  auto params = rover::sim::terrain::TerrainParamsFromParamSet(ps);
  if (!params.ok()) {
    std::fprintf(stderr, "error: %s\n", params.status().message().c_str());
    return 2;
  }
  if (print_params) std::printf("%s", ps.DumpYaml().c_str());

  const auto t0 = std::chrono::steady_clock::now();
  auto terrain = rover::sim::terrain::GenerateTerrain(*params);
  if (!terrain.ok()) {
    std::fprintf(stderr, "error: %s\n", terrain.status().message().c_str());
    return 2;
  }
  const auto t1 = std::chrono::steady_clock::now();
  if (auto s = rover::sim::terrain::PlaceScenarioObjects(&*terrain, ps); !s.ok()) {
    std::fprintf(stderr, "error: %s\n", s.message().c_str());
    return 2;
  }
  const auto t2 = std::chrono::steady_clock::now();
  rover::sim::terrain::MapOptions options;
  options.title = title;
  options.max_pixels = max_pixels;
  options.pixels_per_metre = pixels_per_metre;
  if (auto s = rover::sim::terrain::WriteTopDownMap(*terrain, out, options); !s.ok()) {
    std::fprintf(stderr, "error: %s\n", s.message().c_str());
    return 2;
  }
  const auto t3 = std::chrono::steady_clock::now();
  auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };

  const auto& g = terrain->ground;
  const double area = (g.max_x() - g.min_x()) * (g.max_y() - g.min_y());
  double cover = 0.0;
  int obstacles = 0, targets = 0;
  for (const auto& r : terrain->rocks) {
    if (r.science_target) {
      ++targets;
      continue;
    }
    cover += std::numbers::pi / 4 * r.diameter * r.diameter;
    obstacles += r.height > 0.2;
  }
  const double k = params->rocks.EffectiveK();
  std::printf("grid %d x %d cells at %.3f m (%.1f x %.1f m)\n", g.nx(), g.ny(), g.resolution(),
              g.max_x() - g.min_x(), g.max_y() - g.min_y());
  std::printf(
      "rocks %zu (preset %s, k %.3f): cover %.4f, model %.4f; %d higher than 0.2 m; "
      "%d science targets; %zu craters; lander %s\n",
      terrain->rocks.size() - static_cast<std::size_t>(targets),
      rover::sim::terrain::RockPresetName(params->rocks.preset), k, cover / area,
      rover::sim::terrain::RockAreaFraction(k, params->rocks.diameter_min,
                                            params->rocks.diameter_max),
      obstacles, targets, terrain->craters.size(), terrain->lander ? "yes" : "no");
  std::printf("time: generate %.0f ms, lander+targets %.0f ms, map %.0f ms -> %s\n", ms(t0, t1),
              ms(t1, t2), ms(t2, t3), out.c_str());
  return 0;
}
