#include "rover/testing/fakes/range_synth.hpp"

#include <algorithm>
#include <cmath>

#include "rover/base/check.hpp"
#include "rover/sim/terrain/random.hpp"

namespace rover::testing {

double PinholeCamera::focal_px() const { return 0.5 * width / std::tan(0.5 * hfov); }

Eigen::Isometry3d PinholeCamera::RoverFromCamera() const {
  const double cd = std::cos(depression), sd = std::sin(depression);
  const double cy = std::cos(yaw), sy = std::sin(yaw);
  const Eigen::Vector3d z(cd * cy, cd * sy, -sd);  // boresight
  const Eigen::Vector3d x(sy, -cy, 0.0);           // image right
  const Eigen::Vector3d y = z.cross(x);            // image down
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear().col(0) = x;
  t.linear().col(1) = y;
  t.linear().col(2) = z;
  t.translation() = position;
  return t;
}

PinholeCamera FrontHazcam() { return PinholeCamera{}; }

apl::nav_core::RangeScan SynthesizeScan(const sim::terrain::HeightField& ground,
                                        const PinholeCamera& camera,
                                        const Eigen::Isometry3d& site_from_rover, Time capture) {
  ROVER_DEMAND(camera.width > 0 && camera.height > 0);
  apl::nav_core::RangeScan scan;
  scan.width = camera.width;
  scan.height = camera.height;
  scan.xyz.assign(3 * scan.pixel_count(), 0.0f);
  scan.valid.assign(scan.pixel_count(), 0);
  scan.capture_time = capture;
  scan.site_from_rover = site_from_rover;
  scan.camera = "synthetic_hazcam";
  const Eigen::Isometry3d site_from_camera = site_from_rover * camera.RoverFromCamera();
  const Eigen::Isometry3d rover_from_site = site_from_rover.inverse();
  const Eigen::Vector3d o = site_from_camera.translation();
  const double f = camera.focal_px();
  sim::terrain::Rng rng(camera.seed);
  auto clearance = [&](const Eigen::Vector3d& p) { return p.z() - ground.Height(p.x(), p.y()); };
  for (int v = 0; v < camera.height; ++v) {
    for (int u = 0; u < camera.width; ++u) {
      const Eigen::Vector3d ray_c((u + 0.5 - 0.5 * camera.width) / f,
                                  (v + 0.5 - 0.5 * camera.height) / f, 1.0);
      const Eigen::Vector3d d = site_from_camera.linear() * ray_c.normalized();
      double t = 0.0;
      double c = clearance(o);
      if (c <= 0.0) continue;  // camera under the ground
      bool hit = false;
      double t_prev = 0.0;
      while (t < camera.max_range) {
        t_prev = t;
        t += std::clamp(0.5 * c, 0.01, 0.04);
        c = clearance(o + t * d);
        if (c <= 0.0) {
          hit = true;
          break;
        }
      }
      if (!hit) continue;
      double lo = t_prev, hi = t;  // clearance > 0 at lo, <= 0 at hi
      while (hi - lo > 1e-3) {
        const double mid = 0.5 * (lo + hi);
        (clearance(o + mid * d) > 0.0 ? lo : hi) = mid;
      }
      double range = 0.5 * (lo + hi);
      if (range < camera.min_range || range > camera.max_range) continue;
      if (camera.noise_at_1m > 0.0) range += camera.noise_at_1m * range * range * rng.Normal();
      const Eigen::Vector3d p = rover_from_site * (o + range * d);
      const std::size_t k = static_cast<std::size_t>(v) * camera.width + u;
      scan.xyz[3 * k] = static_cast<float>(p.x());
      scan.xyz[3 * k + 1] = static_cast<float>(p.y());
      scan.xyz[3 * k + 2] = static_cast<float>(p.z());
      scan.valid[k] = 1;
    }
  }
  return scan;
}

Eigen::Isometry3d RoverPose(const sim::terrain::HeightField& ground, double x, double y,
                            double yaw) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  t.translation() = Eigen::Vector3d(x, y, ground.Height(x, y));
  return t;
}

namespace {

sim::terrain::TerrainParams QuietParams(double size, double resolution) {
  sim::terrain::TerrainParams p;
  p.size_x = p.size_y = size;
  p.resolution = resolution;
  p.hills.amplitude = 0.0;
  p.craters.count = 0;
  p.rocks.preset = sim::terrain::RockPreset::kNone;
  p.start.keep_out_radius = 1.5;
  return p;
}

}  // namespace

sim::terrain::Terrain FlatWorld(double size, double resolution) {
  auto t = sim::terrain::GenerateTerrain(QuietParams(size, resolution));
  ROVER_DEMAND_MSG(t.ok(), t.status().message().c_str());
  return std::move(t).value();
}

sim::terrain::Terrain SeededRockField(const char* preset, std::uint64_t seed, double size) {
  sim::terrain::TerrainParams p = QuietParams(size, 0.02);
  auto parsed = sim::terrain::ParseRockPreset(preset);
  ROVER_DEMAND_MSG(parsed.ok(), parsed.status().message().c_str());
  p.rocks.preset = *parsed;
  p.seed = seed;
  p.hills.amplitude = 0.15;
  auto t = sim::terrain::GenerateTerrain(p);
  ROVER_DEMAND_MSG(t.ok(), t.status().message().c_str());
  return std::move(t).value();
}

void AddRock(sim::terrain::Terrain* terrain, double x, double y, double diameter, double height,
             double bluntness) {
  sim::terrain::Rock r;
  r.id = terrain->next_rock_id++;
  r.position = Eigen::Vector3d(x, y, terrain->bare.Height(x, y));
  r.diameter = diameter;
  r.height = height;
  r.bluntness = bluntness;
  terrain->rocks.push_back(r);
  sim::terrain::RebuildHeights(terrain);
}

}  // namespace rover::testing
