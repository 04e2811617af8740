#pragma once
// Test helper (header only): renders textured planes into rectified stereo pairs so the VO
// pipeline runs on real pixels with known motion. Not part of the library API.
//
// World frame = left camera frame of the first pair (x right, y down, z forward). The scene is a
// ground plane y = ground_y with a back wall z = wall_z; both carry band-limited value noise
// (three octaves) in their plane coordinates; rays that hit neither see a flat "sky". Each pixel
// averages supersample x supersample rays (box filter), then Gaussian noise and 8-bit rounding.

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <opencv2/core.hpp>
#include <random>

#include "rover/dl/vo/stereo_camera.hpp"
#include "rover/dl/vo/visual_odometry.hpp"

namespace rover::dl::vo::testing {

inline StereoCamera TestCamera() {
  StereoCamera c;
  c.width = 640;
  c.height = 480;
  c.fx = c.fy = 500.0;
  c.cx = 319.5;
  c.cy = 239.5;
  c.baseline = 0.3;
  return c;
}

struct SyntheticScene {
  double ground_y = 1.5;  // [m] camera height above the ground
  double wall_z = 25.0;   // [m]
  std::uint64_t texture_seed = 7;
  double noise_sigma = 1.0;  // [grey levels]
  int supersample = 3;
  bool flat = false;    // constant grey everywhere (featureless)
  bool smooth = false;  // only a very low-frequency, low-contrast shading
};

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

inline double ValueNoise(double x, double y, std::uint64_t seed) {
  const double fx = std::floor(x), fy = std::floor(y);
  const auto i = static_cast<std::int64_t>(fx), j = static_cast<std::int64_t>(fy);
  auto fade = [](double t) { return t * t * t * (t * (t * 6 - 15) + 10); };
  const double ax = fade(x - fx), ay = fade(y - fy);
  const double v00 = LatticeValue(i, j, seed), v10 = LatticeValue(i + 1, j, seed);
  const double v01 = LatticeValue(i, j + 1, seed), v11 = LatticeValue(i + 1, j + 1, seed);
  return (1 - ay) * ((1 - ax) * v00 + ax * v10) + ay * ((1 - ax) * v01 + ax * v11);
}

// Texture in [0, 1] at plane coordinates (a, b) [m].
inline double Texture(double a, double b, std::uint64_t seed) {
  const double v = 0.5 * ValueNoise(a / 0.5, b / 0.5, seed) +
                   0.3 * ValueNoise(a / 0.17, b / 0.17, seed + 1) +
                   0.2 * ValueNoise(a / 0.06, b / 0.06, seed + 2);
  return v;
}

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

// Renders the left (right = false) or right image of a camera whose left camera has pose
// t_world_cam.
inline cv::Mat RenderView(const StereoCamera& cam, const SyntheticScene& s,
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

inline StereoFrame RenderPair(const StereoCamera& cam, const SyntheticScene& s,
                              const Eigen::Isometry3d& t_world_cam, double stamp_s,
                              std::uint64_t noise_seed) {
  StereoFrame f;
  f.stamp = Time::FromSeconds(stamp_s);
  f.left = RenderView(cam, s, t_world_cam, false, noise_seed);
  f.right = RenderView(cam, s, t_world_cam, true, noise_seed + 1);
  return f;
}

// A rover-like step in the level world frame: forward (z), sideways and a little up, with a yaw
// (about y, down) and small pitch and roll.
inline Eigen::Isometry3d TestMotion() {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = (Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitY()) *
                Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitX()) *
                Eigen::AngleAxisd(-0.008, Eigen::Vector3d::UnitZ()))
                   .toRotationMatrix();
  t.translation() = Eigen::Vector3d(0.06, -0.01, 0.45);
  return t;
}

// The camera is pitched down by `pitch` [rad] on the rover, as MER pointed its NAVCAMs at the
// terrain for visual odometry. World pose of the left camera after the rover moved by
// `rover_motion` (level world frame): T_world_cam = rover_motion * mount.
inline Eigen::Isometry3d CameraPose(const Eigen::Isometry3d& rover_motion, double pitch = 0.44) {
  Eigen::Isometry3d mount = Eigen::Isometry3d::Identity();
  mount.linear() = Eigen::AngleAxisd(-pitch, Eigen::Vector3d::UnitX()).toRotationMatrix();
  return rover_motion * mount;
}

// The camera-frame motion T_from_to of one TestMotion() step of a pitched camera.
inline Eigen::Isometry3d TestCameraMotion(double pitch = 0.44) {
  return CameraPose(Eigen::Isometry3d::Identity(), pitch).inverse() *
         CameraPose(TestMotion(), pitch);
}

}  // namespace rover::dl::vo::testing
