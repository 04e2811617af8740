#include "rover/sim/terrain/terrain_params.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "rover/base/format.hpp"
#include "rover/base/key_checker.hpp"
#include "rover/sim/terrain/rock_model.hpp"

namespace rover::sim::terrain {
namespace {

// The checker's verdict, with the failing key (relative to the terrain prefix) when asked.
Status Failed(const KeyChecker& c, std::string* key) {
  if (key != nullptr) *key = c.key();
  return c.status();
}

}  // namespace

const char* RockPresetName(RockPreset p) {
  switch (p) {
    case RockPreset::kNone:
      return "none";
    case RockPreset::kVl1:
      return "vl1";
    case RockPreset::kVl2:
      return "vl2";
    case RockPreset::kImpassable:
      return "impassable";
    case RockPreset::kCustom:
      return "custom";
  }
  return "?";
}

Result<RockPreset> ParseRockPreset(const std::string& name) {
  for (RockPreset p : {RockPreset::kNone, RockPreset::kVl1, RockPreset::kVl2,
                       RockPreset::kImpassable, RockPreset::kCustom}) {
    if (name == RockPresetName(p)) return p;
  }
  return InvalidArgument("rocks.preset: '" + name +
                         "' is not one of: none, vl1, vl2, impassable, custom");
}

double RockPresetK(RockPreset p) {
  switch (p) {
    case RockPreset::kNone:
      return 0.0;
    case RockPreset::kVl1:
      return 0.069;
    case RockPreset::kVl2:
      return 0.176;
    case RockPreset::kImpassable:
      return 0.40;
    case RockPreset::kCustom:
      return -1.0;
  }
  return -1.0;
}

double RockParams::EffectiveK() const {
  return preset == RockPreset::kCustom ? k : RockPresetK(preset);
}

namespace internal {

std::string JoinKey(const std::string& prefix, const std::string& name) {
  return prefix.empty() ? name : prefix + "." + name;
}

Status ValidateTerrainParams(const TerrainParams& p, std::string* key) {
  KeyChecker c;
  c.Positive("resolution", p.resolution) && c.InRange("resolution", p.resolution, 1e-3, 10.0);
  c.Positive("size_x", p.size_x) &&
      (p.size_x >= 2.0 * p.resolution ||
       c.Fail("size_x", FormatNumber(p.size_x) +
                            " m is smaller than two grid cells of resolution " +
                            FormatNumber(p.resolution) + " m"));
  c.Positive("size_y", p.size_y) &&
      (p.size_y >= 2.0 * p.resolution ||
       c.Fail("size_y", FormatNumber(p.size_y) +
                            " m is smaller than two grid cells of resolution " +
                            FormatNumber(p.resolution) + " m"));
  c.Finite("center_x", p.center_x);
  c.Finite("center_y", p.center_y);
  if (!c.ok()) return Failed(c, key);
  const double cells =
      (std::floor(p.size_x / p.resolution) + 1.0) * (std::floor(p.size_y / p.resolution) + 1.0);
  if (cells > kMaxTerrainCells) {
    c.Fail("resolution", FormatNumber(p.resolution) + " m gives " + FormatNumber(cells) +
                             " cells for a " + FormatNumber(p.size_x) + " x " +
                             FormatNumber(p.size_y) + " m map (limit " +
                             FormatNumber(kMaxTerrainCells) + "): use a coarser resolution");
  }

  c.InRange("slope.angle_deg", p.slope.angle_deg, 0.0, 59.0);
  c.InRange("slope.uphill_direction_deg", p.slope.uphill_direction_deg, -360.0, 360.0);

  c.AtLeast("hills.amplitude", p.hills.amplitude, 0.0);
  c.Positive("hills.wavelength", p.hills.wavelength);
  c.InRange("hills.octaves", p.hills.octaves, 1, 16);
  c.Positive("hills.persistence", p.hills.persistence) &&
      c.InRange("hills.persistence", p.hills.persistence, 0.0, 1.0);

  c.InRange("craters.count", p.craters.count, 0, 100000);
  c.Positive("craters.diameter_min", p.craters.diameter_min);
  c.Positive("craters.diameter_max", p.craters.diameter_max) &&
      (p.craters.diameter_max >= p.craters.diameter_min ||
       c.Fail("craters.diameter_max", FormatNumber(p.craters.diameter_max) +
                                          " is smaller than craters.diameter_min " +
                                          FormatNumber(p.craters.diameter_min)));
  c.InRange("craters.depth_ratio", p.craters.depth_ratio, 0.0, 1.0);
  c.InRange("craters.rim_ratio", p.craters.rim_ratio, 0.0, 0.5);

  const RockParams& r = p.rocks;
  const std::string k_key = r.preset == RockPreset::kCustom ? "rocks.k" : "rocks.preset";
  if (r.preset == RockPreset::kCustom) {
    c.Finite("rocks.k", r.k) &&
        (r.k >= 0.0 ||
         c.Fail("rocks.k", FormatNumber(r.k) + " must be >= 0 (fraction of area covered)")) &&
        (r.k <= 1.0 ||
         c.Fail("rocks.k", FormatNumber(r.k) + " > 1: the cumulative rock area fraction "
                                               "cannot exceed the whole surface"));
  }
  c.Positive("rocks.diameter_min", r.diameter_min) &&
      (r.diameter_min >= 2.0 * p.resolution ||
       c.Fail("rocks.diameter_min", FormatNumber(r.diameter_min) +
                                        " m is below two grid cells (2 x resolution = " +
                                        FormatNumber(2.0 * p.resolution) +
                                        " m): such rocks are not resolved; raise it or "
                                        "refine the resolution"));
  c.Positive("rocks.diameter_max", r.diameter_max) &&
      (r.diameter_max > r.diameter_min ||
       c.Fail("rocks.diameter_max", FormatNumber(r.diameter_max) +
                                        " must exceed rocks.diameter_min " +
                                        FormatNumber(r.diameter_min)));
  c.InRange("rocks.height_ratio", r.height_ratio, 0.05, 2.0);
  c.AtLeast("rocks.height_ratio_spread", r.height_ratio_spread, 0.0) &&
      (r.height_ratio_spread < r.height_ratio ||
       c.Fail("rocks.height_ratio_spread", FormatNumber(r.height_ratio_spread) +
                                               " must be below rocks.height_ratio " +
                                               FormatNumber(r.height_ratio)));
  c.InRange("rocks.texture_count", r.texture_count, 1, 1 << 20);
  if (c.ok()) {
    const double k = r.EffectiveK();
    const double cover = RockAreaFraction(k, r.diameter_min, r.diameter_max);
    if (cover > kMaxRockCover) {
      c.Fail(k_key,
             "k = " + FormatNumber(k) + " asks rocks of " + FormatNumber(r.diameter_min) + "-" +
                 FormatNumber(r.diameter_max) + " m to cover " + FormatNumber(100.0 * cover) +
                 " % of the surface; non-overlapping rocks cannot be placed above " +
                 FormatNumber(100.0 * kMaxRockCover) + " %: lower k or raise rocks.diameter_min");
    }
  }

  c.InRange("soil.sand_fraction", p.soil.sand_fraction, 0.0, 1.0);
  c.InRange("soil.bedrock_fraction", p.soil.bedrock_fraction, 0.0, 1.0) &&
      (p.soil.sand_fraction + p.soil.bedrock_fraction <= 1.0 + 1e-12 ||
       c.Fail("soil.bedrock_fraction",
              FormatNumber(p.soil.bedrock_fraction) + " + soil.sand_fraction " +
                  FormatNumber(p.soil.sand_fraction) + " exceed 1 (the whole surface)"));
  c.Positive("soil.patch_scale", p.soil.patch_scale);

  const double min_x = p.center_x - 0.5 * p.size_x, max_x = p.center_x + 0.5 * p.size_x;
  const double min_y = p.center_y - 0.5 * p.size_y, max_y = p.center_y + 0.5 * p.size_y;
  c.Finite("start.x", p.start.x) &&
      ((p.start.x >= min_x && p.start.x <= max_x) ||
       c.Fail("start.x", FormatNumber(p.start.x) + " is off the map (x in [" + FormatNumber(min_x) +
                             ", " + FormatNumber(max_x) + "])"));
  c.Finite("start.y", p.start.y) &&
      ((p.start.y >= min_y && p.start.y <= max_y) ||
       c.Fail("start.y", FormatNumber(p.start.y) + " is off the map (y in [" + FormatNumber(min_y) +
                             ", " + FormatNumber(max_y) + "])"));
  c.AtLeast("start.keep_out_radius", p.start.keep_out_radius, 0.0);
  c.AtLeast("start.blend_width", p.start.blend_width, 0.0);
  return Failed(c, key);
}

}  // namespace internal

Status TerrainParams::Validate() const { return internal::ValidateTerrainParams(*this, nullptr); }

void DeclareTerrainParams(ParamSet& ps, const std::string& prefix) {
  const TerrainParams d;
  auto key = [&prefix](const char* name) { return internal::JoinKey(prefix, name); };
  ps.Declare(key("size_x"), d.size_x, "[m] terrain extent along x (north)");
  ps.Declare(key("size_y"), d.size_y, "[m] terrain extent along y (west)");
  ps.Declare(key("center_x"), d.center_x, "[m] map centre x in the site frame");
  ps.Declare(key("center_y"), d.center_y, "[m] map centre y in the site frame");
  ps.Declare(key("resolution"), d.resolution, "[m] heightfield grid spacing");
  ps.Declare(key("seed"), static_cast<std::int64_t>(d.seed),
             "random seed (same seed, same terrain)")
      .Min(0);
  ps.Declare(key("slope.angle_deg"), d.slope.angle_deg, "[deg] base (regional) slope");
  ps.Declare(key("slope.uphill_direction_deg"), d.slope.uphill_direction_deg,
             "[deg] direction of steepest ascent, from +x (north) towards +y (west)");
  ps.Declare(key("hills.amplitude"), d.hills.amplitude,
             "[m] amplitude of the largest value-noise octave (0 = no hills)");
  ps.Declare(key("hills.wavelength"), d.hills.wavelength, "[m] wavelength of the largest octave");
  ps.Declare(key("hills.octaves"), d.hills.octaves, "number of octaves, each half the wavelength");
  ps.Declare(key("hills.persistence"), d.hills.persistence,
             "amplitude ratio of successive octaves");
  ps.Declare(key("craters.count"), d.craters.count, "number of craters");
  ps.Declare(key("craters.diameter_min"), d.craters.diameter_min, "[m] smallest crater diameter");
  ps.Declare(key("craters.diameter_max"), d.craters.diameter_max, "[m] largest crater diameter");
  ps.Declare(key("craters.depth_ratio"), d.craters.depth_ratio, "crater depth / diameter");
  ps.Declare(key("craters.rim_ratio"), d.craters.rim_ratio, "crater rim height / diameter");
  ps.Declare(key("rocks.preset"), RockPresetName(d.rocks.preset),
             "rock abundance: none, vl1 (k=0.069), vl2 (k=0.176), impassable (k=0.40), custom")
      .OneOf({"none", "vl1", "vl2", "impassable", "custom"});
  ps.Declare(key("rocks.k"), d.rocks.k,
             "total rock area fraction k of F_k(D) = k exp(-q(k) D) (selects preset custom)");
  ps.Declare(key("rocks.diameter_min"), d.rocks.diameter_min, "[m] smallest rock diameter");
  ps.Declare(key("rocks.diameter_max"), d.rocks.diameter_max, "[m] largest rock diameter");
  ps.Declare(key("rocks.height_ratio"), d.rocks.height_ratio, "mean rock height / diameter");
  ps.Declare(key("rocks.height_ratio_spread"), d.rocks.height_ratio_spread,
             "per-rock height ratio is uniform in mean +- spread");
  ps.Declare(key("rocks.texture_count"), d.rocks.texture_count,
             "rock texture ids are drawn from [0, texture_count)");
  ps.Declare(key("soil.sand_fraction"), d.soil.sand_fraction, "share of the surface in loose sand");
  ps.Declare(key("soil.bedrock_fraction"), d.soil.bedrock_fraction,
             "share of the surface in bedrock");
  ps.Declare(key("soil.patch_scale"), d.soil.patch_scale, "[m] typical soil patch size");
  ps.Declare(key("start.x"), d.start.x, "[m] rover start x (site frame)");
  ps.Declare(key("start.y"), d.start.y, "[m] rover start y (site frame)");
  ps.Declare(key("start.keep_out_radius"), d.start.keep_out_radius,
             "[m] radius of the flat, rock-free disc around the start");
  ps.Declare(key("start.blend_width"), d.start.blend_width,
             "[m] width of the ring where relief fades back in around the disc");
}

Result<TerrainParams> TerrainParamsFromParamSet(const ParamSet& ps, const std::string& prefix) {
  ROVER_RETURN_IF_ERROR(ps.Validate());
  auto key = [&prefix](const char* name) { return internal::JoinKey(prefix, name); };
  TerrainParams p;
  p.size_x = ps.GetDouble(key("size_x"));
  p.size_y = ps.GetDouble(key("size_y"));
  p.center_x = ps.GetDouble(key("center_x"));
  p.center_y = ps.GetDouble(key("center_y"));
  p.resolution = ps.GetDouble(key("resolution"));
  p.seed = static_cast<std::uint64_t>(ps.GetInt(key("seed")));
  p.slope.angle_deg = ps.GetDouble(key("slope.angle_deg"));
  p.slope.uphill_direction_deg = ps.GetDouble(key("slope.uphill_direction_deg"));
  p.hills.amplitude = ps.GetDouble(key("hills.amplitude"));
  p.hills.wavelength = ps.GetDouble(key("hills.wavelength"));
  auto to_int = [](std::int64_t v) {
    return static_cast<int>(std::clamp<std::int64_t>(v, std::numeric_limits<int>::min(),
                                                     std::numeric_limits<int>::max()));
  };
  p.hills.octaves = to_int(ps.GetInt(key("hills.octaves")));
  p.hills.persistence = ps.GetDouble(key("hills.persistence"));
  p.craters.count = to_int(ps.GetInt(key("craters.count")));
  p.craters.diameter_min = ps.GetDouble(key("craters.diameter_min"));
  p.craters.diameter_max = ps.GetDouble(key("craters.diameter_max"));
  p.craters.depth_ratio = ps.GetDouble(key("craters.depth_ratio"));
  p.craters.rim_ratio = ps.GetDouble(key("craters.rim_ratio"));

  const std::string preset_key = key("rocks.preset"), k_key = key("rocks.k");
  auto preset = ParseRockPreset(ps.GetString(preset_key));
  if (!preset.ok()) return AtParamKey(ps, preset_key, preset.status());
  p.rocks.preset = *preset;
  const bool k_set = ps.Origin(k_key).source != "default";
  const bool preset_set = ps.Origin(preset_key).source != "default";
  p.rocks.k = ps.GetDouble(k_key);
  if (k_set && !preset_set) {
    p.rocks.preset = RockPreset::kCustom;
  } else if (k_set && p.rocks.preset != RockPreset::kCustom) {
    return AtParamKey(
        ps, k_key,
        InvalidArgument(k_key + ": is set but " + preset_key + " is '" +
                        RockPresetName(p.rocks.preset) + "' (" + ps.Origin(preset_key).ToString() +
                        "); use preset 'custom' or drop k"));
  }
  p.rocks.diameter_min = ps.GetDouble(key("rocks.diameter_min"));
  p.rocks.diameter_max = ps.GetDouble(key("rocks.diameter_max"));
  p.rocks.height_ratio = ps.GetDouble(key("rocks.height_ratio"));
  p.rocks.height_ratio_spread = ps.GetDouble(key("rocks.height_ratio_spread"));
  p.rocks.texture_count = to_int(ps.GetInt(key("rocks.texture_count")));
  p.soil.sand_fraction = ps.GetDouble(key("soil.sand_fraction"));
  p.soil.bedrock_fraction = ps.GetDouble(key("soil.bedrock_fraction"));
  p.soil.patch_scale = ps.GetDouble(key("soil.patch_scale"));
  p.start.x = ps.GetDouble(key("start.x"));
  p.start.y = ps.GetDouble(key("start.y"));
  p.start.keep_out_radius = ps.GetDouble(key("start.keep_out_radius"));
  p.start.blend_width = ps.GetDouble(key("start.blend_width"));

  std::string bad;
  const Status s = internal::ValidateTerrainParams(p, &bad);
  if (!s.ok()) return AtParamKey(ps, key(bad.c_str()), s);
  return p;
}

}  // namespace rover::sim::terrain
