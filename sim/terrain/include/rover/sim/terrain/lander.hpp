#pragma once
/// @file
/// A MER/Pathfinder-like lander and science targets, placed into a generated Terrain.
///
/// Lander geometry (site frame, metres): a hexagonal deck (circumradius R, top at deck_z =
/// bare ground height at the centre + deck_height) on six truss legs (one at each vertex, with
/// X braces on every face), and two ramps leaving two opposite deck edges: ramp 0 runs down and
/// away from the deck in direction yaw, ramp 1 in direction yaw + 180 deg. A ramp is a plank of
/// width W from the deck edge (apothem R cos 30 deg from the centre, at deck_z) down to the
/// ground at horizontal distance ramp_length further out.
///
/// Each ramp carries six dark stripes across it on a light surface. Stripe widths are
/// stripe_unit * code, and the codes (bottom to top) are
///     ramp 0: 2 3 4 5 6 7        ramp 1: 7 5 3 6 4 2
/// so within a ramp every stripe has its own width, and every ordered pair of neighbouring
/// widths (seen from the bottom of a ramp) occurs once over both ramps, which tells the two
/// ramps and every stripe apart (kRampStripeCodes).
///
/// The renderer draws the lander from `quads` (each planar, convex, corners counter-clockwise
/// seen from the side its normal points to, with an RGB albedo). Physics sees the lander in
/// Terrain::ground: the deck footprint is a block up to deck_z (a 1 m wall the rover cannot
/// climb), and the ramps are planes from the ground up to the deck, so the only way onto the
/// deck is up a ramp. Lander cells get Soil::kBedrock (hard, no sinkage).

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/params.hpp"
#include "rover/base/status.hpp"
#include "rover/hwconfig/lander_description.hpp"
#include "rover/sim/heightfield.hpp"

namespace rover::sim::terrain {

struct Terrain;

struct LanderParams {
  double x = 0.0;  ///< [m] deck centre, site frame
  double y = 0.0;
  double yaw_deg = 0.0;         ///< [deg] direction ramp 0 descends, from +x towards +y
  double deck_height = 1.0;     ///< [m] deck top above the bare ground at the centre
  double deck_thickness = 0.2;  ///< [m]
  double deck_radius = 1.5;     ///< [m] circumradius of the hexagonal deck (= edge length)
  double ramp_length = 3.0;     ///< [m] horizontal run of a ramp beyond the deck edge
  double ramp_width = 1.4;      ///< [m] (<= deck_radius, the edge the ramp hangs from)
  double stripe_unit = 0.03;    ///< [m] stripe width per code unit (widths 2..7 units)
  double stripe_gap = 0.15;     ///< [m] gap between neighbouring stripes along the ramp
  double rock_clearance = 0.3;  ///< [m] rocks this close to the footprint are removed

  /// Checks the fields; messages start with "lander.<field>: ".
  Status Validate() const;
  /// The dimensions as the rover knows them (core/hwconfig), from which the stripes are laid out.
  hwconfig::LanderDescription Description() const;
};

enum class LanderPart : std::uint8_t { kDeck, kLeg, kBrace, kRamp, kStripe };
const char* LanderPartName(LanderPart p);

struct LanderQuad {
  std::array<Eigen::Vector3d, 4> corners;  ///< site frame, counter-clockwise about Normal()
  Eigen::Vector3d albedo = Eigen::Vector3d::Constant(0.5);  ///< RGB reflectance in [0, 1]
  LanderPart part = LanderPart::kDeck;
  int ramp = -1;    ///< ramp index for kRamp / kStripe
  int stripe = -1;  ///< stripe index (0 = lowest) for kStripe
  /// Unit normal (right-hand rule over the corners).
  Eigen::Vector3d Normal() const;
};

/// Stripe width codes per ramp, bottom to top (the rover's lander description's).
using hwconfig::kRampStripeCodes;

struct LanderStripe {
  int ramp = 0;
  int index = 0;                                     ///< 0 = lowest on the ramp
  int code = 0;                                      ///< width in stripe units (kRampStripeCodes)
  double width = 0.0;                                ///< [m] along the ramp surface
  double length = 0.0;                               ///< [m] across the ramp
  Eigen::Vector3d center = Eigen::Vector3d::Zero();  ///< on the ramp surface, site frame
};

struct LanderRamp {
  Eigen::Vector2d direction = Eigen::Vector2d::UnitX();     ///< horizontal, down the ramp
  Eigen::Vector3d top_center = Eigen::Vector3d::Zero();     ///< middle of the deck edge
  Eigen::Vector3d bottom_center = Eigen::Vector3d::Zero();  ///< middle of the ground edge
  double width = 0.0;
  std::array<LanderStripe, 6> stripes;
  /// [deg] inclination of the ramp surface.
  double SlopeDeg() const;
};

struct Lander {
  LanderParams params;
  double deck_z = 0.0;                           ///< [m] deck top, site frame
  std::array<Eigen::Vector2d, 6> deck_vertices;  ///< counter-clockwise seen from above
  std::array<LanderRamp, 2> ramps;
  std::vector<LanderQuad> quads;

  /// True if (x, y) is inside the hexagonal deck footprint.
  bool InDeck(double x, double y) const;
  /// If (x, y) is on a ramp's footprint, returns its index and the ramp surface height in *z;
  /// otherwise -1.
  int RampAt(double x, double y, double* z) const;
  /// Horizontal distance from (x, y) to the footprint (deck + ramps); 0 inside.
  double DistanceToFootprint(double x, double y) const;
};

/// Writes the lander's obstacles into a heightfield that already holds the natural surface:
/// deck footprint -> deck_z, ramp footprints -> max(surface, ramp plane); both -> kBedrock.
void StampLander(const Lander& lander, HeightField* ground);

/// Places a lander on the terrain: removes rocks within rock_clearance of its footprint,
/// builds the geometry and stamps it into terrain->ground. Errors: invalid params (naming the
/// field), footprint off the map ("lander.x" / "lander.y"), a lander already placed, or a
/// science target under the footprint.
Status PlaceLander(Terrain* terrain, const LanderParams& params);

struct ScienceTargetParams {
  double x = 0.0;  ///< [m] centre, site frame
  double y = 0.0;
  double diameter = 0.3;    ///< [m]
  int texture_id = 0;       ///< renderer texture (>= 0)
  double height = 0.0;      ///< [m] above the ground; 0 -> rocks.height_ratio * diameter
  double yaw_deg = 0.0;     ///< [deg] long-axis direction (with elongation > 1)
  double elongation = 1.0;  ///< long / short axis of the footprint, >= 1
};

/// Adds a science-target rock (Rock::science_target = true) and returns its id. Other rocks
/// overlapping it are removed (targets stay distinct). Errors: bad fields (naming them), the
/// footprint off the map ("science_target.x" / ".y"), overlap with the lander or another
/// target.
Result<int> AddScienceTarget(Terrain* terrain, const ScienceTargetParams& target);

// ---- scenario files ------------------------------------------------------------------------

/// Declares `<prefix>.enabled` (false) and every LanderParams field as `<prefix>.<field>`.
void DeclareLanderParams(ParamSet& params, const std::string& prefix = "lander");
/// The lander of a scenario, or nullopt if `<prefix>.enabled` is false.
Result<std::optional<LanderParams>> LanderParamsFromParamSet(const ParamSet& params,
                                                             const std::string& prefix = "lander");
/// Declares `key` (default "science_targets"): a flat list of numbers, four per target:
/// [x, y, diameter, texture_id, x, y, diameter, texture_id, ...] (empty = none).
void DeclareScienceTargets(ParamSet& params, const std::string& key = "science_targets");
Result<std::vector<ScienceTargetParams>> ScienceTargetsFromParamSet(
    const ParamSet& params, const std::string& key = "science_targets");
/// Places the lander (if enabled) and the science targets declared above; errors carry the
/// file:line of the offending key.
Status PlaceScenarioObjects(Terrain* terrain, const ParamSet& params,
                            const std::string& lander_prefix = "lander",
                            const std::string& targets_key = "science_targets");

}  // namespace rover::sim::terrain
