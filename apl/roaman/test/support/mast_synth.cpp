#include "mast_synth.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rover/sim/terrain/random.hpp"

namespace rover::apl::roaman::testing {
namespace {

// Rover-frame rotation of the camera frame (x right, y down, z boresight).
Eigen::Matrix3d RoverFromCamera(const MastCamera& c) {
  const Eigen::Vector3d z(std::cos(c.tilt) * std::cos(c.pan), std::cos(c.tilt) * std::sin(c.pan),
                          std::sin(c.tilt));
  const Eigen::Vector3d x(std::sin(c.pan), -std::cos(c.pan), 0.0);
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d r;
  r.col(0) = x;
  r.col(1) = y;
  r.col(2) = z;
  return r;
}

// Highest and lowest sample of the field (bounds for the ray march).
void HeightRange(const sim::terrain::HeightField& g, double* lo, double* hi) {
  const auto [mn, mx] = std::minmax_element(g.heights().begin(), g.heights().end());
  *lo = *mn;
  *hi = *mx;
}

}  // namespace

std::vector<MastCamera> PanoramaPointings(const MastCamera& camera, double half_sector, int pans,
                                          const std::vector<double>& tilts) {
  std::vector<MastCamera> out;
  for (const double tilt : tilts) {
    for (int k = 0; k < pans; ++k) {
      MastCamera c = camera;
      c.pan = pans == 1 ? 0.0 : -half_sector + 2.0 * half_sector * k / (pans - 1);
      c.tilt = tilt;
      c.seed = camera.seed * 1000 + out.size();
      out.push_back(c);
    }
  }
  return out;
}

Eigen::Isometry3d RoverPose(const sim::terrain::HeightField& ground, double x, double y,
                            double yaw) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(x, y, ground.Height(x, y));
  return t;
}

nav_core::RangeScan SynthesizeScan(const sim::terrain::HeightField& ground,
                                   const MastCamera& camera,
                                   const Eigen::Isometry3d& site_from_rover) {
  nav_core::RangeScan scan;
  scan.width = camera.width;
  scan.height = camera.height;
  scan.xyz.assign(3 * scan.pixel_count(), 0.0f);
  scan.valid.assign(scan.pixel_count(), 0);
  scan.site_from_rover = site_from_rover;
  scan.camera = "navcam";
  double h_lo = 0.0, h_hi = 0.0;
  HeightRange(ground, &h_lo, &h_hi);
  const Eigen::Matrix3d site_from_camera = site_from_rover.linear() * RoverFromCamera(camera);
  const Eigen::Vector3d origin = site_from_rover * camera.head;
  const Eigen::Vector2d rover_xy = site_from_rover.translation().head<2>();
  const double f = 0.5 * camera.width / std::tan(0.5 * camera.hfov);
  const double step_h = 0.5 * ground.resolution();
  sim::terrain::Rng rng(camera.seed);
  const Eigen::Isometry3d rover_from_site = site_from_rover.inverse();
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d d =
          (site_from_camera * Eigen::Vector3d((u + 0.5 - 0.5 * camera.width) / f,
                                              (v + 0.5 - 0.5 * camera.height) / f, 1.0))
              .normalized();
      const double noise = camera.noise_at_10m > 0.0 ? rng.Normal() : 0.0;
      if (d.z() >= 0.0 && origin.z() >= h_hi) continue;  // above the horizon of the highest peak
      const double dh = std::hypot(d.x(), d.y());
      const double dt = dh > 1e-6 ? step_h / dh : step_h;
      // Start where the ray comes down to the highest sample, stop past the range or the lowest.
      double t = d.z() < 0.0 ? std::max(0.0, (origin.z() - h_hi) / -d.z() - dt) : 0.0;
      const auto above = [&](double s) {
        const Eigen::Vector3d p = origin + s * d;
        return p.z() - ground.Height(p.x(), p.y());
      };
      double prev_t = t, prev = above(t);
      bool hit = false;
      while (true) {
        const Eigen::Vector3d p = origin + t * d;
        if ((p.head<2>() - rover_xy).norm() > camera.max_range || p.z() < h_lo - 1.0 ||
            !ground.Contains(p.x(), p.y())) {
          break;
        }
        const double a = above(t);
        if (a <= 0.0) {
          hit = prev > 0.0;
          break;
        }
        prev_t = t;
        prev = a;
        t += dt;
      }
      if (!hit) continue;
      double lo = prev_t, hi = t;
      for (int k = 0; k < 10; ++k) {
        const double mid = 0.5 * (lo + hi);
        (above(mid) > 0.0 ? lo : hi) = mid;
      }
      double range = 0.5 * (lo + hi);
      range += noise * camera.noise_at_10m * (range / 10.0) * (range / 10.0);
      const Eigen::Vector3d p_rover = rover_from_site * (origin + range * d);
      if (p_rover.head<2>().norm() > camera.max_range) continue;
      const std::size_t k = static_cast<std::size_t>(v) * camera.width + u;
      scan.xyz[3 * k] = static_cast<float>(p_rover.x());
      scan.xyz[3 * k + 1] = static_cast<float>(p_rover.y());
      scan.xyz[3 * k + 2] = static_cast<float>(p_rover.z());
      scan.valid[k] = 1;
    }
  }
  return scan;
}

std::vector<nav_core::RangeScan> SynthesizePanorama(const sim::terrain::HeightField& ground,
                                                    const std::vector<MastCamera>& pointings,
                                                    const Eigen::Isometry3d& site_from_rover) {
  std::vector<nav_core::RangeScan> out;
  for (const MastCamera& c : pointings) out.push_back(SynthesizeScan(ground, c, site_from_rover));
  return out;
}

nav_core::RangeScan OverheadScan(const sim::terrain::HeightField& ground, double x0, double y0,
                                 double x1, double y1, double step,
                                 const Eigen::Isometry3d& site_from_rover) {
  nav_core::RangeScan scan;
  scan.width = std::max(1, static_cast<int>(std::floor((x1 - x0) / step)) + 1);
  scan.height = std::max(1, static_cast<int>(std::floor((y1 - y0) / step)) + 1);
  scan.xyz.assign(3 * scan.pixel_count(), 0.0f);
  scan.valid.assign(scan.pixel_count(), 0);
  scan.site_from_rover = site_from_rover;
  scan.camera = "overhead";
  const Eigen::Isometry3d rover_from_site = site_from_rover.inverse();
  for (int v = 0; v < scan.height; ++v) {
    for (int u = 0; u < scan.width; ++u) {
      const double x = x0 + u * step, y = y0 + v * step;
      if (!ground.Contains(x, y)) continue;
      const Eigen::Vector3d p = rover_from_site * Eigen::Vector3d(x, y, ground.Height(x, y));
      const std::size_t k = static_cast<std::size_t>(v) * scan.width + u;
      scan.xyz[3 * k] = static_cast<float>(p.x());
      scan.xyz[3 * k + 1] = static_cast<float>(p.y());
      scan.xyz[3 * k + 2] = static_cast<float>(p.z());
      scan.valid[k] = 1;
    }
  }
  return scan;
}

}  // namespace rover::apl::roaman::testing
