// rover-pictures: renders the simulated rover's stereo cameras on a scenario's terrain and writes
// <out>/<camera>_left.png, <camera>_right.png (8-bit, as the cameras deliver them) and
// <out>/terrain_map.png (top-down map with the rover marked).
//
//   rover-pictures --params scenario.yaml --x 3 --y -2 --yaw-deg 30 --tilt-deg -25 --out pics
//   rover-pictures --set terrain.rocks.preset=vl2 --cameras navcam --size 512 --out pics
//   rover-pictures --help-params
#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "rover/base/params.hpp"
#include "rover/sim/render/cameras.hpp"
#include "rover/sim/render/renderer.hpp"
#include "rover/sim/terrain/features.hpp"
#include "rover/sim/terrain/terrain.hpp"
#include "rover/sim/terrain/top_down_map.hpp"

namespace {

int Fail(const std::string& message) {
  std::fprintf(stderr, "error: %s\n", message.c_str());
  return 2;
}

std::vector<std::string> Split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) {
    if (!item.empty()) out.push_back(item);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace rover::sim::render;
  using namespace rover::sim::terrain;
  CLI::App app{"Render the simulated rover's stereo cameras (PNG) on a scenario's terrain"};
  std::vector<std::string> files, sets;
  std::string out = "pictures", cameras = "navcam,front_hazcam,rear_hazcam";
  double x = 0.0, y = 0.0, yaw_deg = 0.0, pan_deg = 0.0, tilt_deg = -25.0;
  double sun_az = 135.0, sun_el = 35.0;
  int size = 1024;
  std::uint64_t seed = 1, frame = 0;
  bool help_params = false, no_noise = false, range = false, no_map = false;
  app.add_option("--params", files, "scenario or parameter YAML file(s); their terrain, terrain_features, lander and science_targets sections are read");
  app.add_option("--set", sets, "override key=value (YAML value), e.g. terrain.rocks.preset=vl2");
  app.add_option("--x", x, "rover position north [m], site frame");
  app.add_option("--y", y, "rover position west [m], site frame");
  app.add_option("--yaw-deg", yaw_deg, "rover heading [deg] from north towards west");
  app.add_option("--pan-deg", pan_deg, "mast pan [deg], + looks left");
  app.add_option("--tilt-deg", tilt_deg, "mast tilt [deg], + looks up");
  app.add_option("--cameras", cameras, "comma-separated: navcam, front_hazcam, rear_hazcam");
  app.add_option("--size", size, "image side [px] (default cameras are 1024 x 1024)")
      ->check(CLI::Range(16, 4096));
  app.add_option("--sun-azimuth-deg", sun_az, "sun azimuth [deg] from north towards west");
  app.add_option("--sun-elevation-deg", sun_el, "sun elevation [deg]");
  app.add_option("--seed", seed, "texture and noise seed");
  app.add_option("--frame", frame, "frame number (noise stream)");
  app.add_option("--out", out, "output folder (created)");
  app.add_flag("--no-noise", no_noise, "no sensor noise");
  app.add_flag("--range", range, "also write range images (16-bit PNG, millimetres)");
  app.add_flag("--no-map", no_map, "do not write the top-down map");
  app.add_flag("--help-params", help_params, "describe every scenario parameter and exit");
  CLI11_PARSE(app, argc, argv);

  rover::ParamSet ps("rover_pictures");
  DeclareTerrainParams(ps);
  DeclareLanderParams(ps);
  DeclareScienceTargets(ps);
  rover::sim::terrain::DeclareTerrainFeatures(ps, "terrain_features");
  if (help_params) {
    std::printf("%s", ps.DescribeAll().c_str());
    return 0;
  }
  // A scenario file or a plain parameter file: only its world sections are read, so a whole
  // scenario (name, task, criteria, ...) can be given as it is.
  for (const auto& f : files) {
    std::ifstream in(f);
    if (!in) return Fail(f + ": cannot open");
    std::stringstream text;
    text << in.rdbuf();
    if (auto s = ps.LoadYamlSections(text.str(), f, {"terrain", "terrain_features", "lander", "science_targets"});
        !s.ok()) {
      return Fail(s.message());
    }
  }
  for (const auto& a : sets) {
    if (auto s = ps.SetFromString(a); !s.ok()) return Fail(s.message());
  }
  auto params = TerrainParamsFromParamSet(ps);
  if (!params.ok()) return Fail(params.status().message());

  // Cameras first: a typo should not cost a terrain generation.
  const auto defs = DefaultStereoCameras(size);
  std::vector<StereoCameraDefinition> chosen;
  for (const auto& name : Split(cameras)) {
    auto d = FindStereoCamera(defs, name);
    if (!d.ok()) return Fail("--cameras: " + d.status().message());
    chosen.push_back(*d);
  }
  if (chosen.empty()) return Fail("--cameras: no camera named");
  for (auto [name, v] : {std::pair{"--x", x}, {"--y", y}, {"--yaw-deg", yaw_deg},
                         {"--pan-deg", pan_deg}, {"--tilt-deg", tilt_deg}}) {
    if (!std::isfinite(v)) return Fail(std::string(name) + ": not a finite number");
  }

  const auto t0 = std::chrono::steady_clock::now();
  auto terrain = GenerateTerrain(*params);
  if (!terrain.ok()) return Fail(terrain.status().message());
  if (auto s = rover::sim::terrain::PlaceScenarioFeatures(&*terrain, ps, "terrain_features"); !s.ok()) {
    return Fail(s.message());
  }
  if (auto s = PlaceScenarioObjects(&*terrain, ps); !s.ok()) return Fail(s.message());
  const HeightField& g = terrain->ground;
  if (!g.Contains(x, y)) {
    char buf[256];
    std::snprintf(buf, sizeof buf,
                  "--x/--y: rover position (%.3f, %.3f) is off the map [%.2f, %.2f] x [%.2f, %.2f]",
                  x, y, g.min_x(), g.max_x(), g.min_y(), g.max_y());
    return Fail(buf);
  }
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  if (ec) return Fail("--out: cannot create folder '" + out + "': " + ec.message());

  const double deg = std::numbers::pi / 180.0;
  const Eigen::Isometry3d pose = RoverPoseOnGround(g, x, y, yaw_deg * deg);
  if (!no_map) {
    MapOptions mo;
    mo.title = "rover at (" + std::to_string(x).substr(0, 6) + ", " + std::to_string(y).substr(0, 6) + ")";
    MapPolyline heading;
    heading.points = {Eigen::Vector2d(x, y),
                      Eigen::Vector2d(x + 1.5 * std::cos(yaw_deg * deg), y + 1.5 * std::sin(yaw_deg * deg))};
    heading.color = {255, 0, 255};
    heading.label = "rover heading";
    heading.thickness = 3;
    mo.polylines.push_back(heading);
    if (auto s = WriteTopDownMap(*terrain, out + "/terrain_map.png", mo); !s.ok()) {
      return Fail(s.message());
    }
  }
  const auto t1 = std::chrono::steady_clock::now();

  RenderOptions ro;
  ro.seed = seed;
  ro.sun.azimuth_deg = sun_az;
  ro.sun.elevation_deg = sun_el;
  ro.sensor.noise = !no_noise;
  ro.output_range = range;
  auto shared = std::make_shared<const Terrain>(std::move(*terrain));
  auto renderer = Renderer::Create(shared, ro);
  if (!renderer.ok()) return Fail(renderer.status().message());
  const auto t2 = std::chrono::steady_clock::now();
  auto ms = [](auto a, auto b) { return std::chrono::duration<double, std::milli>(b - a).count(); };
  std::printf("terrain + map %.0f ms, renderer setup %.0f ms (%s)\n", ms(t0, t1), ms(t1, t2),
              (*renderer)->gl_renderer().c_str());
  for (const auto& def : chosen) {
    auto spec = MakeCameraPairSpec(def, MastState{pan_deg * deg, tilt_deg * deg});
    if (!spec.ok()) return Fail(spec.status().message());
    const auto a = std::chrono::steady_clock::now();
    auto pair = (*renderer)->RenderStereoPair(pose, *spec, frame);
    if (!pair.ok()) return Fail(def.name + ": " + pair.status().message());
    const auto b = std::chrono::steady_clock::now();
    for (auto [side, img] : {std::pair{"left", &pair->left}, {"right", &pair->right}}) {
      const std::string path = out + "/" + def.name + "_" + side + ".png";
      if (!cv::imwrite(path, img->image)) return Fail("cannot write '" + path + "'");
      if (range) {
        cv::Mat mm;
        img->range.convertTo(mm, CV_16U, 1000.0);
        const std::string rpath = out + "/" + def.name + "_" + side + "_range_mm.png";
        if (!cv::imwrite(rpath, mm)) return Fail("cannot write '" + rpath + "'");
      }
    }
    const auto& st = (*renderer)->last_stats();
    std::printf("%-13s %dx%d: %.0f ms (shadow %.0f, gl %.0f, warp %.0f, sensor %.0f, plan %.0f), "
                "%d views, %lld triangles, exposure %.2f\n",
                def.name.c_str(), pair->left.image.cols, pair->left.image.rows, ms(a, b),
                st.shadow_ms, st.gl_ms, st.warp_ms, st.sensor_ms, st.plan_ms, st.views,
                st.triangles, pair->left.exposure);
  }
  std::printf("wrote %s/\n", out.c_str());
  return 0;
}
