#pragma once
/// @file
/// Test support: range scans as ROAMAN gets them, from a mast NAVCAM pair about 1.5 m above the
/// ground, ray-cast against a sim::terrain::HeightField, so that tests see what FIDO saw: dense
/// near, sparse far, nothing past the usable range, shadows behind rocks.
///
/// Camera: an ideal pinhole of width x height pixels, horizontal field of view hfov, square
/// pixels, at `head` in the rover frame (x forward, y left, z up; default the sim rover's mast
/// head: pan joint at (0.35, 0, 0.65) + 0.85 m mast), pointed by `pan` (about z, + looks left)
/// and `tilt` (+ looks up). Camera frame x right, y down, z along the boresight; pixel (u, v)
/// looks along ((u + 0.5 - w/2) / f, (v + 0.5 - h/2) / f, 1), f = (w/2) / tan(hfov/2).
///
/// Ray casting: from the camera along each ray in steps of half a heightfield sample (measured
/// horizontally) against HeightField::Height (bilinear), the crossing refined by 10 bisections;
/// a hit within max_range (horizontal, from the rover) is a valid pixel, reported in the rover
/// frame. Optional noise N(0, (noise_at_10m (r / 10)^2)^2) along the ray, from
/// sim::terrain::Rng(seed) in pixel order, so every scan is reproducible bit for bit.

#include <Eigen/Geometry>
#include <cstdint>
#include <numbers>
#include <vector>

#include "rover/apl/nav_core/range_scan.hpp"
#include "rover/base/units.hpp"
#include "rover/sim/heightfield.hpp"

namespace rover::apl::roaman::testing {

struct MastCamera {
  int width = 160;
  int height = 120;
  double hfov = 45.0 * kDegree;                            ///< [rad] (MER NAVCAM 45°)
  Eigen::Vector3d head = Eigen::Vector3d(0.35, 0.0, 1.5);  ///< [m] rover frame
  double pan = 0.0;    ///< [rad]
  double tilt = -20.0 * kDegree;  ///< [rad]
  double max_range = 12.0;     ///< [m] horizontal, from the rover
  double noise_at_10m = 0.0;   ///< [m] 1-sigma range error at 10 m
  std::uint64_t seed = 1;
};

/// The pointings of a panorama: pans from -half_sector to +half_sector in `pans` steps, at each
/// of `tilts`.
std::vector<MastCamera> PanoramaPointings(const MastCamera& camera, double half_sector, int pans,
                                          const std::vector<double>& tilts);

/// A rover standing at site (x, y) with heading yaw, its origin on `ground` (no roll, pitch).
Eigen::Isometry3d RoverPose(const sim::terrain::HeightField& ground, double x, double y,
                            double yaw);

/// One scan of `camera` on a rover at `site_from_rover`.
nav_core::RangeScan SynthesizeScan(const sim::terrain::HeightField& ground,
                                   const MastCamera& camera,
                                   const Eigen::Isometry3d& site_from_rover);
/// One scan per pointing.
std::vector<nav_core::RangeScan> SynthesizePanorama(const sim::terrain::HeightField& ground,
                                                    const std::vector<MastCamera>& pointings,
                                                    const Eigen::Isometry3d& site_from_rover);

/// A scan without occlusion: every heightfield sample in the site box [x0, x1] x [y0, y1] taken
/// every `step` metres, as seen by a rover at `site_from_rover` (for tests of the planners that
/// want a complete map). Pixel grid: columns along x, rows along y.
nav_core::RangeScan OverheadScan(const sim::terrain::HeightField& ground, double x0, double y0,
                                 double x1, double y1, double step,
                                 const Eigen::Isometry3d& site_from_rover);

}  // namespace rover::apl::roaman::testing
