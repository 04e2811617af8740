#pragma once
/// @file
/// Fake scene (header only, no DDS): renders a textured ground plane and back wall into the
/// images of a rectified pinhole stereo pair, so vision code runs on real pixels with known
/// geometry and motion. Used by dl/vo's unit tests (through dl/vo/test/synthetic_scene.hpp) and
/// by the fake camera driver (fake_camera_driver.hpp).
///
/// World frame W is camera-like: x right, y down, z forward [m]. The scene is the ground plane
/// y = ground_y and a back wall z = wall_z; both carry band-limited value noise (three octaves)
/// in their plane coordinates; rays that hit neither see a flat "sky". Each pixel averages
/// supersample x supersample rays (box filter), then Gaussian noise (seeded) and 8-bit rounding.
/// Deterministic: the same scene, pose and seed give the same image.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <opencv2/core.hpp>
#include <random>

namespace rover::testing {

/// A rectified pinhole stereo pair: both cameras x right, y down, z forward, sharing the
/// intrinsics; the right camera's centre at (+baseline, 0, 0) in the left camera frame. Pixel
/// (u, v) = (column, row), the top-left pixel's centre at (0, 0).
struct PinholeStereo {
  int width = 0;          ///< [px]
  int height = 0;         ///< [px]
  double fx = 0.0;        ///< [px]
  double fy = 0.0;        ///< [px]
  double cx = 0.0;        ///< [px]
  double cy = 0.0;        ///< [px]
  double baseline = 0.0;  ///< [m]

  /// Direction (z = 1) of the viewing ray through pixel `px`, in the camera frame.
  Eigen::Vector3d Ray(const Eigen::Vector2d& px) const {
    return {(px.x() - cx) / fx, (px.y() - cy) / fy, 1.0};
  }
  /// Centre of the right camera in the left camera frame [m].
  Eigen::Vector3d RightCentre() const { return {baseline, 0.0, 0.0}; }
};

struct SyntheticScene {
  double ground_y = 1.5;  ///< [m] camera height above the ground (W y of the ground plane)
  double wall_z = 25.0;   ///< [m] W z of the back wall
  std::uint64_t texture_seed = 7;
  double noise_sigma = 1.0;  ///< [grey levels]
  int supersample = 3;
  bool flat = false;    ///< constant grey everywhere (featureless)
  bool smooth = false;  ///< only a very low-frequency, low-contrast shading
};

/// A hash of the lattice point (i, j) in [0, 1).
inline double LatticeValue(std::int64_t i, std::int64_t j, std::uint64_t seed) {
  std::uint64_t h = seed ^ (static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ULL) ^
                    (static_cast<std::uint64_t>(j) * 0xC2B2AE3D27D4EB4FULL);
  h ^= h >> 33;
  h *= 0xff51afd7ed558ccdULL;
  h ^= h >> 33;
  h *= 0xc4ceb9fe1a85ec53ULL;
  h ^= h >> 33;
  return static_cast<double>(h >> 11) / static_cast<double>(1ULL << 53);  // [0, 1)
}

/// Value noise at (x, y) in lattice units: the four lattice values blended with a quintic fade.
inline double ValueNoise(double x, double y, std::uint64_t seed) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto i = static_cast<std::int64_t>(fx), j = static_cast<std::int64_t>(fy);
  auto fade = [](double t) { return t * t * t * (t * (t * 6 - 15) + 10); };
  const double ax = fade(x - fx), ay = fade(y - fy);
  const double v00 = LatticeValue(i, j, seed), v10 = LatticeValue(i + 1, j, seed);
  const double v01 = LatticeValue(i, j + 1, seed), v11 = LatticeValue(i + 1, j + 1, seed);
  return (1 - ay) * ((1 - ax) * v00 + ax * v10) + ay * ((1 - ax) * v01 + ax * v11);
}

/// Texture in [0, 1] at plane coordinates (a, b) [m]: octaves of 0.5, 0.17 and 0.06 m.
inline double Texture(double a, double b, std::uint64_t seed) {
  const double v = 0.5 * ValueNoise(a / 0.5, b / 0.5, seed) +
                   0.3 * ValueNoise(a / 0.17, b / 0.17, seed + 1) +
                   0.2 * ValueNoise(a / 0.06, b / 0.06, seed + 2);
  return v;
}

/// Grey level seen along the ray o + l d (W frame), l > 0.
inline double Shade(const SyntheticScene& s, const Eigen::Vector3d& o, const Eigen::Vector3d& d) {
  if (s.flat) return 128.0;
  double best = std::numeric_limits<double>::infinity();
  double value = 200.0;  // sky
  if (d.y() > 1e-9) {
    const double l = (s.ground_y - o.y()) / d.y();
    if (l > 0 && l < best) {
      const Eigen::Vector3d p = o + l * d;
      if (p.z() < s.wall_z) {
        best = l;
        value = s.smooth ? 128.0 + 30.0 * std::sin(p.x() / 7.0) * std::cos(p.z() / 9.0)
                         : 30.0 + 200.0 * Texture(p.x(), p.z(), s.texture_seed);
      }
    }
  }
  if (d.z() > 1e-9) {
    const double l = (s.wall_z - o.z()) / d.z();
    if (l > 0 && l < best) {
      const Eigen::Vector3d p = o + l * d;
      value = s.smooth ? 128.0 + 30.0 * std::sin(p.x() / 7.0 + 1.0) * std::cos(p.y() / 5.0)
                       : 30.0 + 200.0 * Texture(p.x() + 100.0, p.y(), s.texture_seed + 10);
    }
  }
  return value;
}

/// Renders the left (right = false) or right image of the pair whose left camera has pose
/// t_world_cam (W from camera), with Gaussian noise seeded by `noise_seed`.
inline cv::Mat RenderView(const PinholeStereo& cam, const SyntheticScene& s,
                          const Eigen::Isometry3d& t_world_cam, bool right,
                          std::uint64_t noise_seed) {
  cv::Mat img(cam.height, cam.width, CV_8UC1);
  const Eigen::Matrix3d r = t_world_cam.linear();
  const Eigen::Vector3d o = t_world_cam * (right ? cam.RightCentre() : Eigen::Vector3d::Zero());
  std::mt19937_64 rng(noise_seed);
  std::normal_distribution<double> noise(0.0, s.noise_sigma);
  const int n = std::max(1, s.supersample);
  for (int v = 0; v < cam.height; ++v) {
    auto* row = img.ptr<std::uint8_t>(v);
    for (int u = 0; u < cam.width; ++u) {
      double acc = 0.0;
      for (int j = 0; j < n; ++j) {
        for (int i = 0; i < n; ++i) {
          const Eigen::Vector2d px(u + (i + 0.5) / n - 0.5, v + (j + 0.5) / n - 0.5);
          acc += Shade(s, o, r * cam.Ray(px));
        }
      }
      double g = acc / (n * n);
      if (s.noise_sigma > 0.0) g += noise(rng);
      row[u] = static_cast<std::uint8_t>(std::clamp(std::lround(g), 0L, 255L));
    }
  }
  return img;
}

}  // namespace rover::testing
