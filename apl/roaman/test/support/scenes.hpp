#pragma once
/// @file
/// Test support: small synthetic worlds for ROAMAN's tests and benchmark, as
/// sim::terrain::HeightFields in the site frame (x north, y west, z up; metres): flat ground or any
/// function of (x, y), rocks, walls, a U-shaped cul-de-sac, and seeded rock fields from
/// sim/terrain's generator.

#include <Eigen/Core>
#include <cstdint>
#include <functional>

#include "rover/apl/roaman/grid.hpp"
#include "rover/apl/roaman/traversability.hpp"
#include "rover/sim/heightfield.hpp"
#include "rover/sim/terrain/terrain.hpp"

namespace rover::apl::roaman::testing {

/// Samples z = f(x, y) every `resolution` metres over [x0, x1] x [y0, y1].
sim::terrain::HeightField HeightFieldOf(double x0, double y0, double x1, double y1,
                                        double resolution,
                                        const std::function<double(double, double)>& f);
/// Flat ground at z = 0.
sim::terrain::HeightField FlatGround(double x0, double y0, double x1, double y1,
                                     double resolution = 0.02);

/// Raises a round rock (half ellipsoid of `diameter` and `height`) on the ground.
void AddRock(sim::terrain::HeightField* ground, double x, double y, double diameter, double height);
/// Raises a flat-topped wall `height` above the ground: every sample within half_width of the
/// segment a-b.
void AddWall(sim::terrain::HeightField* ground, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
             double half_width, double height);
/// A U-shaped wall (a cul-de-sac): the base of inner width `inner_width` centred on `base`,
/// the two arms `depth` long reaching from it toward `mouth` (a unit vector: where the opening
/// faces); walls `thickness` thick and `height` high.
void AddCulDeSac(sim::terrain::HeightField* ground, const Eigen::Vector2d& base,
                 const Eigen::Vector2d& mouth, double inner_width, double depth, double thickness,
                 double height);

/// A seeded rock field of rock abundance k (Golombek & Rapp; VL-2 is 0.176) on gentle hills, no
/// craters, square of side `size` centred on the origin, rock-free within 1.5 m of the origin.
sim::terrain::Terrain RockField(double k, std::uint64_t seed, double size,
                                double resolution = 0.04);

/// A w x h grid of 5 cm cells with its origin at (origin_x, origin_y) [m].
GridGeometry CellGeometry(int w, int h, double origin_x = 0.0, double origin_y = 0.0);

/// Input of steps 3-7 without range data: every cell of `geometry` measured once at the
/// ground's height at its centre (sigma 0, top = bottom = mean).
ElevationMap SampledElevation(const sim::terrain::HeightField& ground,
                              const GridGeometry& geometry);

/// Input of the planners without the seven steps: a traversability map of cell size `cell`
/// over [x0, x1) x [y0, y1) with every cell `fill`.
TraversabilityMap ClassMap(double x0, double y0, double x1, double y1, double cell, CellClass fill);
/// Sets every cell whose centre lies within half_width of the segment a-b to `c`.
void Paint(TraversabilityMap* map, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
           double half_width, CellClass c);

}  // namespace rover::apl::roaman::testing
