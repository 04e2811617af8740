#pragma once
/// @file
/// Parameters of the seeded Mars-like terrain generator (see terrain.hpp and README.md).
///
/// Frames and units: site frame (x north, y west, z up), metres, degrees where the name says
/// `_deg`. Angles in the x-y plane are measured from +x (north) towards +y (west), i.e.
/// counter-clockwise seen from above (the same sense as yaw).
///
/// Scenario files set these through rover::ParamSet: DeclareTerrainParams() declares every
/// field under a prefix (default "terrain", so YAML `terrain: {rocks: {preset: vl2}}` sets
/// `terrain.rocks.preset`), and TerrainParamsFromParamSet() reads them back, reporting any
/// error as `file:line: key 'terrain.rocks.k': ...`. Field names below are the keys without the
/// prefix.

#include <cstdint>
#include <string>

#include "rover/base/params.hpp"
#include "rover/base/status.hpp"

namespace rover::sim::terrain {

/// Rock abundance presets (Golombek & Rapp 1997 model, rock_model.hpp).
enum class RockPreset {
  kNone,        ///< no rocks (k = 0)
  kVl1,         ///< Viking Lander 1 site, k = 0.069: benign
  kVl2,         ///< Viking Lander 2 site, k = 0.176: rock-strewn
  kImpassable,  ///< k = 0.40, near the densest rock abundance seen on Mars
  kCustom,      ///< k from RockParams::k
};
const char* RockPresetName(RockPreset p);
/// Parses "none" | "vl1" | "vl2" | "impassable" | "custom".
Result<RockPreset> ParseRockPreset(const std::string& name);
/// k of a preset (kCustom has none: returns -1).
double RockPresetK(RockPreset p);

struct SlopeParams {
  double angle_deg = 0.0;             ///< base (regional) slope, [0, 60)
  double uphill_direction_deg = 0.0;  ///< direction of steepest ascent, from +x towards +y
};

struct HillParams {
  double amplitude = 0.35;    ///< [m] lattice amplitude of the first (largest) octave; 0 = flat
  double wavelength = 16.0;   ///< [m] wavelength of the first octave
  int octaves = 6;            ///< octaves (each half the wavelength); those below 2 cells dropped
  double persistence = 0.45;  ///< amplitude ratio between successive octaves, (0, 1]
};

struct CraterParams {
  int count = 3;              ///< craters whose centres fall in the map
  double diameter_min = 2.0;  ///< [m] rim-to-rim diameter range; sizes follow N(>D) ~ D^-2
  double diameter_max = 10.0;
  double depth_ratio = 0.15;  ///< depth / diameter (fresh simple craters ~0.2, degraded less)
  double rim_ratio = 0.03;    ///< rim height / diameter
};

struct RockParams {
  RockPreset preset = RockPreset::kVl1;
  double k = 0.0;              ///< total rock area fraction, used when preset == kCustom
  double diameter_min = 0.10;  ///< [m] smallest generated rock (>= 2 * resolution)
  double diameter_max = 2.0;   ///< [m] largest generated rock
  double height_ratio = 0.5;   ///< mean height / diameter (rocks stand about half as high as wide)
  double height_ratio_spread = 0.1;  ///< per-rock ratio uniform in mean +- spread
  int texture_count = 8;             ///< rock texture ids are drawn from [0, texture_count)
  /// The k in effect: preset's k, or `k` for kCustom.
  double EffectiveK() const;
};

struct SoilPatchParams {
  double sand_fraction = 0.15;     ///< share of cells that are loose sand, [0, 1]
  double bedrock_fraction = 0.10;  ///< share of cells that are bedrock, [0, 1]
  double patch_scale = 6.0;        ///< [m] typical patch size (noise wavelength)
};

struct StartParams {
  double x = 0.0;  ///< [m] rover start, site frame
  double y = 0.0;
  double keep_out_radius = 2.0;  ///< [m] rock-free, flat (planar at the base slope) disc
  double blend_width = 1.0;      ///< [m] ring outside the disc where relief fades back in
};

struct TerrainParams {
  double size_x = 50.0;   ///< [m] extent along x (north)
  double size_y = 50.0;   ///< [m] extent along y (west)
  double center_x = 0.0;  ///< [m] map centre in the site frame
  double center_y = 0.0;
  double resolution = 0.04;  ///< [m] grid spacing
  std::uint64_t seed = 1;
  SlopeParams slope;
  HillParams hills;
  CraterParams craters;
  RockParams rocks;
  SoilPatchParams soil;
  StartParams start;

  /// Checks every field; the message starts with the offending key, e.g.
  /// "rocks.k: 1.5 > 1: rocks cannot cover more than the whole surface".
  Status Validate() const;
};

/// Largest rock area fraction (with D in [diameter_min, diameter_max]) the generator accepts.
/// Rocks do not overlap, and random sequential placement jams near 50 % cover.
inline constexpr double kMaxRockCover = 0.45;
/// Largest grid the generator allocates (cells).
inline constexpr double kMaxTerrainCells = 64.0e6;

/// Declares every TerrainParams field under `prefix` ("terrain" -> "terrain.size_x"; "" -> flat
/// keys) with the defaults of TerrainParams{}, ranges and docs.
void DeclareTerrainParams(ParamSet& params, const std::string& prefix = "terrain");
/// Reads the fields back; validates both the ParamSet and TerrainParams::Validate(), naming
/// file:line and key of the offending value. Setting `rocks.k` without `rocks.preset` selects
/// the custom preset; setting k with a preset other than custom is an error.
Result<TerrainParams> TerrainParamsFromParamSet(const ParamSet& params,
                                                const std::string& prefix = "terrain");

namespace internal {
/// Validate() with the offending key (without prefix) in *key.
Status ValidateTerrainParams(const TerrainParams& p, std::string* key);
/// "prefix.name" or "name".
std::string JoinKey(const std::string& prefix, const std::string& name);
}  // namespace internal

}  // namespace rover::sim::terrain
