#pragma once
/// @file
/// The seeded Mars-like terrain generator.
///
/// GenerateTerrain() builds, on a regular grid (HeightField) covering
/// [center - size/2, center + size/2] in the site frame (x north, y west, z up; metres):
///   1. a base plane z = tan(slope) * ((p - c) . u), u = uphill direction;
///   2. hills: fractal value noise (noise.hpp), amplitude * sum_o persistence^o * noise_o;
///   3. craters: bowl z = -d + (d + h) s^2 inside (s = r / R < 1), rim/ejecta h s^-3 outside,
///      faded to 0 between s = 1.5 and 3; diameters from N(>D) ~ D^-2, d = depth_ratio D f,
///      h = rim_ratio D f with a per-crater freshness f in [0.6, 1];
///   4. a keep-out disc around the rover start: the relief is replaced by the base plane through
///      the start point inside keep_out_radius and faded back in over blend_width;
///   5. soil: loose-sand and bedrock patches from two value-noise fields (wavelength
///      patch_scale), biased so that sand collects in lows and bedrock crops out on highs,
///      thresholded at the quantiles that give exactly the requested fractions of cells;
///   6. rocks from the Golombek & Rapp (1997) model (rock_model.hpp): N = round(A n_bar) rocks,
///      A = map area, n_bar = rocks per m^2 with D in [d_min, d_max]; diameters sampled from
///      n(D), placed largest first at uniform random positions without overlapping (centre
///      distance >= sum of the nominal radii); a rock whose first position falls in the
///      keep-out disc (centre closer than keep_out_radius + D/2) is dropped, which thins the
///      field there without changing the density elsewhere.
///
/// Rock shape: footprint an ellipse of axis ratio `elongation` (area pi D^2 / 4) with a small
/// three-lobed outline perturbation; profile z = H (1 - rho^2)^bluntness over the normalised
/// radius rho in [0, 1); H = height = h_ratio D, h_ratio uniform in height_ratio +- spread
/// (rocks stand about half as high as they are wide: Golombek & Rapp 1997; Golombek et al.
/// 2003). Rocks sit on the bare ground: natural = bare + max over rocks of their relief.
///
/// Determinism: every random draw comes from std::mt19937_64 streams seeded with
/// MixSeed(seed, stream) (random.hpp), one stream per feature (hills, craters, soil, rock
/// sizes, rock positions, rock shapes), with our own uniform/normal transforms. Same params ->
/// bit-identical heights, soils and rock list; changing, say, the rock preset leaves the
/// topography unchanged.

#include <Eigen/Core>
#include <optional>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/sim/heightfield.hpp"
#include "rover/sim/terrain/lander.hpp"
#include "rover/sim/terrain/terrain_params.hpp"

namespace rover::sim::terrain {

struct Rock {
  int id = 0;
  /// Centre of the footprint at ground level (bare ground under the centre), site frame [m].
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  double diameter = 0.0;  ///< [m] nominal: the footprint area is pi D^2 / 4
  double height = 0.0;    ///< [m] top above position.z
  bool science_target = false;
  bool placed = false;  ///< placed by the scenario (features.hpp), not generated
  int texture_id = 0;
  // Shape (for the heightfield and the renderer; see RockRelief()).
  double yaw = 0.0;             ///< [rad] long axis direction, from +x towards +y
  double elongation = 1.0;      ///< long / short footprint axis, >= 1
  double bluntness = 0.5;       ///< profile exponent: 0.5 = half ellipsoid, smaller = blunter
  double lobe_amplitude = 0.0;  ///< relative 3-lobe outline perturbation, [0, 0.2]
  double lobe_phase = 0.0;      ///< [rad]
  /// > 0: a layered outcrop instead of a boulder (features.hpp): a rectangular footprint
  /// `diameter` long along `yaw` and diameter / elongation deep, built of `layers` flat-topped
  /// beds of height / layers each, every bed inset from the one below by kOutcropInset of the
  /// depth / layers on all sides, so the faces show horizontal steps (straight level edges).
  /// The lobe and bluntness fields are unused then.
  int layers = 0;
};

/// Inset of an outcrop's bed from the one below, as a fraction of depth / layers per side.
inline constexpr double kOutcropInset = 0.35;

/// Height of the rock's surface above position.z at (x, y); 0 outside the footprint.
double RockRelief(const Rock& rock, double x, double y);
/// Radius of a circle about the centre that contains the footprint.
double RockBoundingRadius(const Rock& rock);
/// `n` points on the footprint outline (x, y), counter-clockwise.
std::vector<Eigen::Vector2d> RockOutline(const Rock& rock, int n = 24);

struct Crater {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();  ///< site frame [m]
  double diameter = 0.0;                             ///< [m] rim to rim
  double depth = 0.0;                                ///< [m] floor below the pre-crater surface
  double rim_height = 0.0;                           ///< [m] rim above the pre-crater surface
};
/// Height change the crater makes at (x, y).
double CraterRelief(const Crater& crater, double x, double y);

struct Terrain {
  TerrainParams params;
  /// What physics drives on: natural surface plus lander obstacles (deck block, ramps).
  HeightField ground;
  /// Bare ground plus rocks: what the renderer draws as terrain (it draws the lander from
  /// lander->quads).
  HeightField natural;
  /// Bare ground: slope, hills, craters, keep-out disc, soil; no rocks, no lander.
  HeightField bare;
  std::vector<Rock> rocks;  ///< generated rocks (largest first) then science targets
  std::vector<Crater> craters;
  std::optional<Lander> lander;
  int next_rock_id = 0;

  /// The rock with this id, or nullptr.
  const Rock* FindRock(int id) const;
};

/// Generates a terrain (see the file comment). Errors name the offending parameter, including
/// a rock density that cannot be placed without overlap.
Result<Terrain> GenerateTerrain(const TerrainParams& params);

/// Recomputes terrain->natural and terrain->ground from terrain->bare, terrain->rocks and
/// terrain->lander (after editing the rock list by hand).
void RebuildHeights(Terrain* terrain);

}  // namespace rover::sim::terrain
