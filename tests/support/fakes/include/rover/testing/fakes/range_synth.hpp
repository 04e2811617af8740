#pragma once
/// @file
/// Test support: a ray-casting range-image synthesiser and small scene builders, so the autonomy
/// tests and tools run on range data shaped like a HAZCAM's (dense near, sparse far, occlusion
/// shadows behind rocks, the footprint's outline cut by the image edges and the range limit)
/// rather than on hand-placed points.
///
/// Camera: an ideal pinhole (no distortion) of width x height pixels with horizontal field of
/// view hfov and square pixels, mounted in the rover frame at `position` with its boresight
/// `depression` below horizontal and rotated `yaw` about the rover's z (0 = front, pi = rear).
/// Camera frame x right, y down, z forward; pixel (u, v)'s ray has direction
/// ((u + 0.5 - w/2) / f, (v + 0.5 - h/2) / f, 1) with f = (w / 2) / tan(hfov / 2).
/// Defaults follow the front HAZCAM of the simulated rover (0.52 m ahead, 0.50 m up, 45° down;
/// MER's HAZCAMs see 120°) at MER's autonav resolution 256 x 256.
///
/// Ray casting: from the camera centre along each ray, in steps of min(max(0.5 (z_ray - h),
/// 1 cm), 4 cm) against HeightField::Height (bilinear), refined by bisection to 1 mm; a hit
/// between min_range and max_range is a valid pixel whose point is reported in the rover frame.
/// Optional range noise: N(0, (noise_at_1m r²)²) along the ray (stereo error grows with range²),
/// drawn from sim::terrain::Rng(seed) in pixel order, so scans are reproducible bit for bit.

#include <Eigen/Geometry>
#include <cstdint>
#include <numbers>
#include <vector>

#include "rover/apl/nav_core/range_scan.hpp"
#include "rover/sim/heightfield.hpp"
#include "rover/sim/terrain/terrain.hpp"

namespace rover::testing {

struct PinholeCamera {
  int width = 256;
  int height = 256;
  double hfov = 120.0 * std::numbers::pi / 180.0;               ///< [rad] horizontal
  Eigen::Vector3d position = Eigen::Vector3d(0.52, 0.0, 0.50);  ///< [m] rover frame
  double depression = 45.0 * std::numbers::pi / 180.0;          ///< [rad] below horizontal
  double yaw = 0.0;                                             ///< [rad] about rover z
  double min_range = 0.3;                                       ///< [m] along the ray
  double max_range = 6.0;                                       ///< [m]
  double noise_at_1m = 0.0;                                     ///< [m] range 1-sigma at 1 m
  std::uint64_t seed = 1;

  double focal_px() const;
  /// Pose of the camera frame in the rover frame.
  Eigen::Isometry3d RoverFromCamera() const;
};

/// The front HAZCAM at 256 x 256 (the defaults).
PinholeCamera FrontHazcam();

/// Ray-casts `camera` on a rover at `site_from_rover` against `ground`.
apl::nav_core::RangeScan SynthesizeScan(const sim::terrain::HeightField& ground,
                                        const PinholeCamera& camera,
                                        const Eigen::Isometry3d& site_from_rover, Time capture = {});

/// A rover standing at site (x, y) with heading `yaw`, its origin on `ground` (no roll, pitch).
Eigen::Isometry3d RoverPose(const sim::terrain::HeightField& ground, double x, double y,
                            double yaw);

/// A flat world of side `size` (centred on the origin, 2 cm grid) with no rocks.
sim::terrain::Terrain FlatWorld(double size = 20.0, double resolution = 0.02);
/// A seeded rock field (preset "vl1" or "vl2"): gentle hills, no craters, start disc at the
/// origin 1.5 m in radius.
sim::terrain::Terrain SeededRockField(const char* preset, std::uint64_t seed, double size = 24.0);
/// Adds a rock (round, profile exponent `bluntness`) on the bare ground and rebuilds heights.
void AddRock(sim::terrain::Terrain* terrain, double x, double y, double diameter, double height,
             double bluntness = 0.5);

}  // namespace rover::testing
