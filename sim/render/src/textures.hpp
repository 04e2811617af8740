#pragma once
// Procedural, seeded, tileable textures of the renderer (CPU side; uploaded with mipmaps).
//
// Every texel is RGBA8:
//   R = albedo multiplier / 2            (1.0 = the material's mean albedo; 0..2)
//   G, B = surface slope dh/du, dh/dv    (bump; 127.5 + 127.5 * slope / kSlopeRange)
//   A = height, normalised to 0..255     (for inspection only)
// Heights are in texel units, so the slopes do not change when the texture is scaled.
//
// Soil detail (one layer, `size` texels = one texture period, 1 m in the shader, i.e. ~1 mm per
// texel at 1024): fine grain (white noise + fBm down to 2 texels), albedo mottling, and a
// power-law population of pebbles (radius 1.5..14 texels, ~12 % cover, darker basalt clasts
// and lighter fragments) as domes with their own albedo.
// Rock textures (kRockLayers layers of `size`^2): kGenericRockLayers ordinary rock surfaces
// (mottling, vesicles, veins, grain; a different mix per layer) followed by kScienceLayers
// distinctive science-target patterns (layering, vein network, spherules, cross-bedding,
// speckle, polygonal fractures, ring clusters, mosaic).
// Determinism: std::mt19937_64 streams from MixSeed(seed, stream); same seed -> same bytes.

#include <cstdint>
#include <vector>

namespace rover::sim::render::internal {

inline constexpr double kSlopeRange = 2.0;
inline constexpr int kGenericRockLayers = 8;
inline constexpr int kScienceLayers = 8;
inline constexpr int kRockLayers = kGenericRockLayers + kScienceLayers;

struct TextureImage {
  int size = 0;    // width = height
  int layers = 0;
  std::vector<std::uint8_t> rgba;  // layer-major, row-major, 4 bytes per texel
  const std::uint8_t* Texel(int layer, int x, int y) const {
    return &rgba[((static_cast<std::size_t>(layer) * size + y) * size + x) * 4];
  }
};

// Preconditions: size a power of two in [64, 4096].
TextureImage MakeSoilDetailTexture(std::uint64_t seed, int size);
TextureImage MakeRockTextures(std::uint64_t seed, int size);

// Tileable fBm on a size x size grid: sum over octaves o of persistence^o * value noise with
// wavelength base_wavelength / 2^o texels (octaves below 2 texels dropped), normalised so that
// |value| <= 1. Precondition: size a power of two, base_wavelength a power of two <= size.
std::vector<float> PeriodicFbm(std::uint64_t seed, int size, int base_wavelength, int octaves,
                               double persistence);

}  // namespace rover::sim::render::internal
