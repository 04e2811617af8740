// sim-render-bench: milliseconds per rendered stereo pair (NAVCAM and front HAZCAM, 512 and 1024
// px) on a VL-2 terrain (50 m x 50 m at 4 cm), against a baseline measured in the same run: one
// plain cv::remap (bilinear, float maps) of an image of the same size, i.e. the cost of the
// per-pixel warp alone. Also prints the stage split, setup time and peak RSS.
//
//   sim-render-bench [--reps 3] [--sizes 512,1024] [--cameras navcam,front_hazcam]
#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "rover/sim/render/cameras.hpp"
#include "rover/sim/render/renderer.hpp"
#include "rover/sim/terrain/terrain.hpp"

namespace {

double PeakRssMb() {
  std::ifstream f("/proc/self/status");
  std::string line;
  while (std::getline(f, line)) {
    if (line.rfind("VmHWM:", 0) == 0) return std::stod(line.substr(6)) / 1024.0;
  }
  return 0.0;
}

template <class F>
double MedianMs(int reps, F f) {
  std::vector<double> t;
  for (int i = 0; i < reps; ++i) {
    const auto a = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
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
  CLI::App app{"Renderer benchmark: ms per stereo pair vs cv::remap of the same size"};
  int reps = 3;
  std::string sizes = "512,1024", cameras = "navcam,front_hazcam";
  app.add_option("--reps", reps, "repetitions (median reported)")->check(CLI::Range(1, 100));
  app.add_option("--sizes", sizes, "image sizes");
  app.add_option("--cameras", cameras, "camera pairs");
  RenderOptions ro;
  app.add_option("--lod-error-px", ro.lod_error_px, "RenderOptions::lod_error_px");
  app.add_option("--tile-cells", ro.tile_cells, "RenderOptions::tile_cells");
  app.add_option("--shadow-cascades", ro.shadow_cascades, "RenderOptions::shadow_cascades");
  app.add_option("--anisotropy", ro.texture_anisotropy, "RenderOptions::texture_anisotropy");
  CLI11_PARSE(app, argc, argv);
  if (auto s = ro.Validate(); !s.ok()) {
    std::fprintf(stderr, "error: %s\n", s.message().c_str());
    return 2;
  }

  TerrainParams tp;
  tp.rocks.preset = RockPreset::kVl2;
  auto terrain = GenerateTerrain(tp);
  if (!terrain.ok()) {
    std::fprintf(stderr, "error: %s\n", terrain.status().message().c_str());
    return 2;
  }
  const Eigen::Isometry3d pose = RoverPoseOnGround(terrain->ground, 0.0, 0.0, 0.3);
  const std::size_t rocks = terrain->rocks.size();
  auto shared = std::make_shared<const Terrain>(std::move(*terrain));
  const auto s0 = std::chrono::steady_clock::now();
  auto renderer = Renderer::Create(shared, ro);
  if (!renderer.ok()) {
    std::fprintf(stderr, "error: %s\n", renderer.status().message().c_str());
    return 2;
  }
  const double setup_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - s0).count();
  std::printf("VL-2 terrain 1251 x 1251 cells, %zu rocks; %s; renderer setup %.0f ms\n", rocks,
              (*renderer)->gl_renderer().c_str(), setup_ms);
  std::printf("%-13s %5s %9s %9s %9s %7s %7s %7s %7s %6s %9s\n", "camera", "size", "ms/pair",
              "remap ms", "x remap", "shadow", "gl", "warp", "sensor", "views", "triangles");
  for (const std::string& size_s : Split(sizes)) {
    const int size = std::stoi(size_s);
    // Baseline: one bilinear cv::remap of a size x size float image with float maps.
    cv::Mat src(size, size, CV_32FC1), mx(size, size, CV_32FC1), my(size, size, CV_32FC1), dst;
    cv::randu(src, 0.0F, 1.0F);
    for (int r = 0; r < size; ++r)
      for (int c = 0; c < size; ++c) {
        mx.at<float>(r, c) = static_cast<float>(c) * 0.97F + 3.3F;
        my.at<float>(r, c) = static_cast<float>(r) * 0.98F + 2.1F;
      }
    const double remap_ms = MedianMs(std::max(5, reps), [&] {
      cv::remap(src, dst, mx, my, cv::INTER_LINEAR, cv::BORDER_CONSTANT);
    });
    const auto defs = DefaultStereoCameras(size);
    for (const std::string& name : Split(cameras)) {
      auto def = FindStereoCamera(defs, name);
      if (!def.ok()) {
        std::fprintf(stderr, "error: %s\n", def.status().message().c_str());
        return 2;
      }
      auto spec = MakeCameraPairSpec(*def, MastState{0.0, -25.0 * std::numbers::pi / 180.0});
      // Warm-up: builds the warp tables (cached afterwards).
      if (auto w = (*renderer)->RenderStereoPair(pose, *spec, 0); !w.ok()) {
        std::fprintf(stderr, "error: %s\n", w.status().message().c_str());
        return 2;
      }
      std::uint64_t frame = 1;
      RenderStats st;
      const double ms = MedianMs(reps, [&] {
        auto p = (*renderer)->RenderStereoPair(pose, *spec, frame++);
        st = (*renderer)->last_stats();
      });
      std::printf("%-13s %5d %9.1f %9.2f %9.0f %7.1f %7.1f %7.1f %7.1f %6d %9lld\n", name.c_str(),
                  size, ms, remap_ms, ms / remap_ms, st.shadow_ms, st.gl_ms, st.warp_ms,
                  st.sensor_ms, st.views, st.triangles);
      std::fflush(stdout);
    }
  }
  std::printf("peak RSS %.0f MB\n", PeakRssMb());
  return 0;
}
