#pragma once
// Synthetic terrain for apl/enav's tests: a dense point cloud of a height function, as one
// RangeScan taken from the site origin (the rover at identity), so every cell is seen.

#include <functional>

#include "rover/apl/enav/height_terrain.hpp"
#include "rover/apl/enav/options.hpp"
#include "rover/base/check.hpp"
#include "rover/apl/nav_core/range_scan.hpp"

namespace rover::apl::enav::testing {

using HeightFn = std::function<double(double x, double y)>;

/// Points every `spacing` m over [x0, x1] x [y0, y1] at z = f(x, y), in the frame of a rover at
/// `site_from_rover` (so the scan lands where f says in the site frame).
inline nav_core::RangeScan ScanOf(const HeightFn& f, double x0, double x1, double y0, double y1,
                                  double spacing = 0.03,
                                  const Eigen::Isometry3d& site_from_rover =
                                      Eigen::Isometry3d::Identity()) {
  nav_core::RangeScan s;
  const Eigen::Isometry3d rover_from_site = site_from_rover.inverse();
  for (double x = x0; x <= x1 + 1e-9; x += spacing) {
    for (double y = y0; y <= y1 + 1e-9; y += spacing) {
      const Eigen::Vector3d p = rover_from_site * Eigen::Vector3d(x, y, f(x, y));
      s.xyz.push_back(static_cast<float>(p.x()));
      s.xyz.push_back(static_cast<float>(p.y()));
      s.xyz.push_back(static_cast<float>(p.z()));
      s.valid.push_back(1);
    }
  }
  s.width = static_cast<int>(s.valid.size());
  s.height = 1;
  s.site_from_rover = site_from_rover;
  s.camera = "test";
  return s;
}

/// A flat plane with square blocks (centre x, y, half side, height).
struct Block {
  double x, y, half, height;
};
inline HeightFn Blocks(std::vector<Block> blocks) {
  return [blocks](double x, double y) {
    double z = 0.0;
    for (const Block& b : blocks) {
      if (std::abs(x - b.x) <= b.half && std::abs(y - b.y) <= b.half) z = std::max(z, b.height);
    }
    return z;
  };
}

/// Options for tests: a 16 m map that sees 8 m, exact data.
inline EnavOptions TestOptions() {
  EnavOptions o;
  o.map_size = 16.0;
  o.recentre_distance = 2.0;
  o.max_point_distance = 5.0;
  o.drop_self_points = false;  // the scans are synthetic: no rover in them
  return o;
}

/// A terrain that has seen f over [-5, 5]² from the origin.
inline HeightTerrain TerrainOf(const HeightFn& f, const EnavOptions& o = TestOptions()) {
  auto t = HeightTerrain::Create(o);
  ROVER_DEMAND(t.ok());
  ROVER_DEMAND(t->Update(ScanOf(f, -5, 5, -5, 5)).ok());
  return std::move(*t);
}

}  // namespace rover::apl::enav::testing
