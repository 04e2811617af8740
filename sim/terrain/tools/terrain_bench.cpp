// sim-terrain-bench: time to generate a 50 m x 50 m terrain at 4 cm (1251 x 1251 cells) per
// rock preset, against a baseline measured in the same run on the same grid size: one 5x5
// Gaussian blur of a float image (OpenCV), i.e. "how many cheap image passes is a terrain".
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "rover/sim/terrain/terrain.hpp"

namespace {

template <class F>
double MedianMs(int reps, F f) {
  std::vector<double> t;
  for (int i = 0; i < reps; ++i) {
    const auto a = std::chrono::steady_clock::now();
    f();
    t.push_back(
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - a).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main() {
  using namespace rover::sim::terrain;
  TerrainParams p;  // 50 m x 50 m at 0.04 m
  cv::Mat src(1251, 1251, CV_32F), dst;
  cv::randu(src, 0.0f, 1.0f);
  const double blur = MedianMs(9, [&] { cv::GaussianBlur(src, dst, cv::Size(5, 5), 1.0); });
  std::printf("grid 1251 x 1251; baseline cv::GaussianBlur 5x5 (float): %.2f ms\n", blur);
  std::printf("%-11s %8s %10s %12s\n", "preset", "rocks", "median ms", "x baseline");
  for (RockPreset preset :
       {RockPreset::kNone, RockPreset::kVl1, RockPreset::kVl2, RockPreset::kImpassable}) {
    p.rocks.preset = preset;
    std::size_t rocks = 0;
    const double ms = MedianMs(3, [&] {
      auto t = GenerateTerrain(p);
      rocks = t.ok() ? t->rocks.size() : 0;
    });
    std::printf("%-11s %8zu %10.1f %12.1f\n", RockPresetName(preset), rocks, ms, ms / blur);
  }
  return 0;
}
