#pragma once
// Synthetic images for the dl_stereo tests: a seeded band-limited texture that can be sampled
// at any real position (exact sub-pixel shifts), stereo pairs of constant disparity, of a
// foreground square over a background, and of a textured ground plane seen by a pitched camera.

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <numbers>
#include <opencv2/core.hpp>
#include <random>
#include <string>
#include <vector>

namespace rover::dl::stereo::testing {

/// f(x, y) = 128 + sum_i a_i sin(wx_i x + wy_i y + phi_i), periods in [min_period, max_period].
class Texture {
 public:
  explicit Texture(std::uint64_t seed, double min_period = 4.0, double max_period = 24.0,
                   int terms = 40, double contrast = 90.0) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> uni(0.0, 1.0);
    for (int i = 0; i < terms; ++i) {
      const double period = min_period * std::pow(max_period / min_period, uni(rng));
      const double angle = 2.0 * std::numbers::pi * uni(rng);
      const double w = 2.0 * std::numbers::pi / period;
      terms_.push_back({w * std::cos(angle), w * std::sin(angle), 2.0 * std::numbers::pi * uni(rng),
                        contrast / std::sqrt(static_cast<double>(terms)) * (0.5 + uni(rng))});
    }
  }
  double operator()(double x, double y) const {
    double s = 128.0;
    for (const auto& t : terms_) s += t.a * std::sin(t.wx * x + t.wy * y + t.phi);
    return s;
  }
  static std::uint8_t Quantise(double value) {
    return static_cast<std::uint8_t>(std::lround(std::clamp(value, 0.0, 255.0)));
  }

 private:
  struct Term {
    double wx, wy, phi, a;
  };
  std::vector<Term> terms_;
};

/// Left(u, v) = T(u, v), Right(u, v) = T(u + d(u,v)..) for a constant disparity d:
/// right pixel u - d sees what left pixel u sees.
inline void ConstantDisparityPair(const Texture& t, cv::Size size, double d, cv::Mat* left,
                                  cv::Mat* right) {
  *left = cv::Mat(size, CV_8UC1);
  *right = cv::Mat(size, CV_8UC1);
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) {
      left->at<std::uint8_t>(v, u) = Texture::Quantise(t(u, v));
      right->at<std::uint8_t>(v, u) = Texture::Quantise(t(u + d, v));
    }
  }
}

/// Background at disparity d_bg with a foreground rectangle `fg` (left-image coordinates) at
/// disparity d_fg > d_bg. Foreground and background use different textures. Fills the true
/// left disparity and a mask of left pixels occluded in the right view.
inline void ForegroundPair(cv::Size size, cv::Rect fg, double d_bg, double d_fg, cv::Mat* left,
                           cv::Mat* right, cv::Mat* truth, cv::Mat* occluded) {
  const Texture bg_tex(11), fg_tex(22);
  *left = cv::Mat(size, CV_8UC1);
  *right = cv::Mat(size, CV_8UC1);
  *truth = cv::Mat(size, CV_32FC1);
  *occluded = cv::Mat::zeros(size, CV_8UC1);
  // The foreground texture is attached to the object: left u maps to texture u - fg.x.
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) {
      const bool in_fg = fg.contains(cv::Point(u, v));
      left->at<std::uint8_t>(v, u) = Texture::Quantise(in_fg ? fg_tex(u - fg.x, v) : bg_tex(u, v));
      truth->at<float>(v, u) = static_cast<float>(in_fg ? d_fg : d_bg);
      // Right pixel ur: the foreground covers right columns [fg.x - d_fg, fg.x + w - d_fg).
      const double ur = u;
      const double fg_left_r = fg.x - d_fg;
      const bool r_in_fg =
          v >= fg.y && v < fg.y + fg.height && ur >= fg_left_r && ur < fg_left_r + fg.width;
      right->at<std::uint8_t>(v, u) =
          Texture::Quantise(r_in_fg ? fg_tex(ur - fg_left_r, v) : bg_tex(ur + d_bg, v));
      // A background left pixel is occluded if its right position falls under the foreground.
      const double u_r = u - d_bg;
      if (!in_fg && v >= fg.y && v < fg.y + fg.height && u_r >= fg_left_r &&
          u_r < fg_left_r + fg.width) {
        occluded->at<std::uint8_t>(v, u) = 255;
      }
    }
  }
}

/// A rectified pair of the flat ground z = 0 (texture in cm) seen by cameras at height `h` [m],
/// pitched down by `pitch` [rad], focal f [px], baseline b [m]. The world frame is the rover
/// frame (x forward, y left, z up) with the left camera at (0, 0, h). Fills the true disparity
/// (NaN where the ray misses the ground) and returns T_rover_camera.
inline Eigen::Isometry3d GroundPlanePair(cv::Size size, double f, double b, double h, double pitch,
                                         cv::Mat* left, cv::Mat* right, cv::Mat* truth) {
  const Texture tex(33, 6.0, 40.0);
  const double cx = 0.5 * (size.width - 1);
  const double cy = 0.5 * (size.height - 1);
  const double cp = std::cos(pitch), sp = std::sin(pitch);
  Eigen::Matrix3d r;  // columns: camera x (right), y (down), z (forward) in the rover frame
  r.col(0) = Eigen::Vector3d(0, -1, 0);
  r.col(2) = Eigen::Vector3d(cp, 0, -sp);
  r.col(1) = r.col(2).cross(r.col(0));
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = r;
  t.translation() = Eigen::Vector3d(0, 0, h);
  const Eigen::Vector3d c_left = t.translation();
  const Eigen::Vector3d c_right = c_left + b * r.col(0);
  const auto sample = [&](const Eigen::Vector3d& c, double u, double v, double* depth) {
    // 3x3 supersampling against aliasing.
    double sum = 0.0;
    for (int i = -1; i <= 1; ++i) {
      for (int j = -1; j <= 1; ++j) {
        const Eigen::Vector3d ray =
            r * Eigen::Vector3d((u + i / 3.0 - cx) / f, (v + j / 3.0 - cy) / f, 1.0);
        if (ray.z() >= -1e-9) return 128.0;
        const Eigen::Vector3d p = c + (-c.z() / ray.z()) * ray;
        sum += tex(100.0 * p.x(), 100.0 * p.y());
        if (i == 0 && j == 0 && depth != nullptr) *depth = (r.transpose() * (p - c)).z();
      }
    }
    return sum / 9.0;
  };
  *left = cv::Mat(size, CV_8UC1);
  *right = cv::Mat(size, CV_8UC1);
  *truth = cv::Mat(size, CV_32FC1, cv::Scalar(std::nan("")));
  for (int v = 0; v < size.height; ++v) {
    for (int u = 0; u < size.width; ++u) {
      double z = std::nan("");
      left->at<std::uint8_t>(v, u) = Texture::Quantise(sample(c_left, u, v, &z));
      right->at<std::uint8_t>(v, u) = Texture::Quantise(sample(c_right, u, v, nullptr));
      if (std::isfinite(z)) truth->at<float>(v, u) = static_cast<float>(f * b / z);
    }
  }
  return t;
}

/// The shared-data folder (compile definition ROVER_SHARED_DATA_DIR, overridable by the
/// environment variable of the same name).
inline std::string SharedDataDir() {
  if (const char* env = std::getenv("ROVER_SHARED_DATA_DIR")) return env;
#ifdef ROVER_SHARED_DATA_DIR
  return ROVER_SHARED_DATA_DIR;
#else
  return "";
#endif
}

}  // namespace rover::dl::stereo::testing
