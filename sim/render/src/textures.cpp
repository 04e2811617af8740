#include "textures.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <numbers>

#include "rover/base/check.hpp"
#include "rover/base/units.hpp"
#include "rover/sim/terrain/random.hpp"

namespace rover::sim::render::internal {

using terrain::MixSeed;
using terrain::Rng;

namespace {

bool IsPow2(int n) { return n > 0 && (n & (n - 1)) == 0; }

// A tileable scalar field.
struct Field {
  int n = 0;
  std::vector<float> v;
  explicit Field(int size, float init = 0.0F)
      : n(size), v(static_cast<std::size_t>(size) * static_cast<std::size_t>(size), init) {}
  int Wrap(int i) const { return i & (n - 1); }
  float& at(int x, int y) { return v[static_cast<std::size_t>(Wrap(y)) * n + Wrap(x)]; }
  float at(int x, int y) const { return v[static_cast<std::size_t>(Wrap(y)) * n + Wrap(x)]; }
};

double Fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

// Adds weight * value noise of wavelength w (texels, power of two <= n) to f.
void AddValueNoise(Rng* rng, int w, double weight, Field* f) {
  const int n = f->n;
  const int cells = std::max(1, n / w);
  std::vector<float> lattice(static_cast<std::size_t>(cells) * cells);
  for (auto& l : lattice) l = static_cast<float>(rng->Uniform(-1.0, 1.0));
  auto lat = [&](int i, int j) {
    i = ((i % cells) + cells) % cells;
    j = ((j % cells) + cells) % cells;
    return static_cast<double>(lattice[static_cast<std::size_t>(j) * cells + i]);
  };
  const double inv_w = 1.0 / w;
  for (int y = 0; y < n; ++y) {
    const double gy = (y + 0.5) * inv_w;
    const int j = static_cast<int>(std::floor(gy));
    const double ty = Fade(gy - j);
    for (int x = 0; x < n; ++x) {
      const double gx = (x + 0.5) * inv_w;
      const int i = static_cast<int>(std::floor(gx));
      const double tx = Fade(gx - i);
      const double a = lat(i, j) + tx * (lat(i + 1, j) - lat(i, j));
      const double b = lat(i, j + 1) + tx * (lat(i + 1, j + 1) - lat(i, j + 1));
      f->v[static_cast<std::size_t>(y) * n + x] += static_cast<float>(weight * (a + ty * (b - a)));
    }
  }
}

Field Fbm(Rng* rng, int n, int base_wavelength, int octaves, double persistence) {
  Field f(n);
  double amp = 1.0, total = 0.0;
  int w = std::min(base_wavelength, n);
  for (int o = 0; o < octaves && w >= 2; ++o, w /= 2, amp *= persistence) {
    AddValueNoise(rng, w, amp, &f);
    total += amp;
  }
  if (total > 0.0) {
    for (auto& x : f.v) x = static_cast<float>(x / total);
  }
  return f;
}

Field WhiteNoise(Rng* rng, int n, double amplitude) {
  Field f(n);
  for (auto& x : f.v) x = static_cast<float>(amplitude * rng->Uniform(-1.0, 1.0));
  return f;
}

// 3x3 box blur with wrap (softens white noise to a ~1.5 texel grain).
Field Blur3(const Field& in) {
  Field out(in.n);
  for (int y = 0; y < in.n; ++y) {
    for (int x = 0; x < in.n; ++x) {
      float s = 0.0F;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) s += in.at(x + dx, y + dy);
      out.at(x, y) = s / 9.0F;
    }
  }
  return out;
}

// Tileable Worley (cellular) noise: one feature point per cell of `cell` texels.
struct Worley {
  int n = 0, cell = 1, cells = 1;
  std::vector<Eigen::Vector2d> points;
  Worley(Rng* rng, int size, int cell_size) : n(size), cell(cell_size), cells(size / cell_size) {
    points.resize(static_cast<std::size_t>(cells) * cells);
    for (int j = 0; j < cells; ++j)
      for (int i = 0; i < cells; ++i)
        points[static_cast<std::size_t>(j) * cells + i] =
            Eigen::Vector2d((i + rng->Uniform(0.1, 0.9)) * cell, (j + rng->Uniform(0.1, 0.9)) * cell);
  }
  // Distances to the nearest and second nearest point and the nearest point's index.
  void Eval(double x, double y, double* f1, double* f2, int* id) const {
    const int ci = static_cast<int>(std::floor(x / cell)), cj = static_cast<int>(std::floor(y / cell));
    *f1 = 1e30;
    *f2 = 1e30;
    *id = 0;
    for (int dj = -1; dj <= 1; ++dj) {
      for (int di = -1; di <= 1; ++di) {
        int i = ci + di, j = cj + dj;
        double ox = 0.0, oy = 0.0;
        if (i < 0) { i += cells; ox = -n; }
        if (i >= cells) { i -= cells; ox = n; }
        if (j < 0) { j += cells; oy = -n; }
        if (j >= cells) { j -= cells; oy = n; }
        const std::size_t k = static_cast<std::size_t>(j) * cells + i;
        const double d = std::hypot(points[k].x() + ox - x, points[k].y() + oy - y);
        if (d < *f1) {
          *f2 = *f1;
          *f1 = d;
          *id = static_cast<int>(k);
        } else if (d < *f2) {
          *f2 = d;
        }
      }
    }
  }
};

// Stamps an elliptical dome (a pebble, a pit or a spot) with wrap-around. Inside the footprint
// the albedo is blended towards `albedo` (weight `albedo_weight`, softened at the rim) and the
// height is max'ed (dome) or added (pit, height < 0).
void Stamp(double cx, double cy, double radius, double elongation, double angle, double height,
           double albedo, double albedo_weight, Field* h, Field* a) {
  const double ca = std::cos(angle), sa = std::sin(angle);
  const double ra = radius * std::sqrt(elongation), rb = radius / std::sqrt(elongation);
  const int reach = static_cast<int>(std::ceil(ra)) + 1;
  const int x0 = static_cast<int>(std::floor(cx)), y0 = static_cast<int>(std::floor(cy));
  for (int y = y0 - reach; y <= y0 + reach; ++y) {
    for (int x = x0 - reach; x <= x0 + reach; ++x) {
      const double dx = x + 0.5 - cx, dy = y + 0.5 - cy;
      const double u = (ca * dx + sa * dy) / ra, v = (-sa * dx + ca * dy) / rb;
      const double rho2 = u * u + v * v;
      if (rho2 >= 1.0) continue;
      const double profile = std::pow(1.0 - rho2, 0.6);
      if (h != nullptr) {
        if (height >= 0.0) {
          h->at(x, y) = std::max(h->at(x, y), static_cast<float>(h->at(x, y) * 0.3 + height * profile));
        } else {
          h->at(x, y) += static_cast<float>(height * profile);
        }
      }
      if (a != nullptr) {
        const double w = albedo_weight * std::min(1.0, 4.0 * (1.0 - rho2));
        a->at(x, y) = static_cast<float>(a->at(x, y) * (1.0 - w) + albedo * w);
      }
    }
  }
}

// Power-law radius in [r0, r1] with density ~ r^-alpha (alpha != 1).
double PowerLawRadius(Rng* rng, double r0, double r1, double alpha) {
  const double e = 1.0 - alpha;
  const double u = rng->Uniform();
  return std::pow(std::pow(r0, e) + u * (std::pow(r1, e) - std::pow(r0, e)), 1.0 / e);
}

std::uint8_t Byte(double v) {
  return static_cast<std::uint8_t>(std::clamp(std::lround(v), 0L, 255L));
}

// Writes one RGBA layer from albedo multiplier and height (texel units).
void Encode(const Field& albedo, const Field& height, std::uint8_t* out) {
  const int n = albedo.n;
  float hmin = 1e30F, hmax = -1e30F;
  for (float x : height.v) {
    hmin = std::min(hmin, x);
    hmax = std::max(hmax, x);
  }
  const double hs = hmax > hmin ? 255.0 / (hmax - hmin) : 0.0;
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const double sx = 0.5 * (height.at(x + 1, y) - height.at(x - 1, y));
      const double sy = 0.5 * (height.at(x, y + 1) - height.at(x, y - 1));
      std::uint8_t* p = out + (static_cast<std::size_t>(y) * n + x) * 4;
      p[0] = Byte(127.5 * albedo.at(x, y));
      p[1] = Byte(127.5 + 127.5 * std::clamp(sx / kSlopeRange, -1.0, 1.0));
      p[2] = Byte(127.5 + 127.5 * std::clamp(sy / kSlopeRange, -1.0, 1.0));
      p[3] = Byte((height.at(x, y) - hmin) * hs);
    }
  }
}

void Normalise(Field* a, double lo, double hi) {
  for (auto& x : a->v) x = static_cast<float>(std::clamp<double>(x, lo, hi));
}

// ---- rock layers ------------------------------------------------------------------------------

void GenericRock(std::uint64_t seed, int layer, int n, Field* a, Field* h) {
  Rng rng(MixSeed(seed, 100 + static_cast<std::uint64_t>(layer)));
  // Per-layer character.
  const double mottling = rng.Uniform(0.10, 0.28);
  const double grain = rng.Uniform(0.05, 0.14);
  const int vesicles = (layer % 3 == 0) ? static_cast<int>(rng.Uniform(400, 1400)) * n / 512 : 0;
  const bool veins = (layer % 4 == 1);
  const double roughness = rng.Uniform(0.6, 1.6);
  Field m = Fbm(&rng, n, n / 4, 7, 0.55);
  Field g = Blur3(WhiteNoise(&rng, n, 1.0));
  Field r = Fbm(&rng, n, n / 8, 6, 0.6);
  for (std::size_t i = 0; i < a->v.size(); ++i) {
    a->v[i] = static_cast<float>(1.0 + mottling * 1.6 * m.v[i] + grain * 2.0 * g.v[i]);
    h->v[i] = static_cast<float>(roughness * (3.0 * r.v[i] + 0.5 * g.v[i]));
  }
  if (veins) {
    Field vn = Fbm(&rng, n, n / 2, 5, 0.5);
    const double bright = rng.Uniform() < 0.5 ? 1.5 : 0.6;
    for (std::size_t i = 0; i < a->v.size(); ++i) {
      const double d = std::abs(vn.v[i]);
      if (d < 0.035) a->v[i] = static_cast<float>(a->v[i] + (bright - a->v[i]) * (1.0 - d / 0.035));
    }
  }
  for (int k = 0; k < vesicles; ++k) {
    const double rad = PowerLawRadius(&rng, 0.8, 4.0, 2.5);
    Stamp(rng.Uniform(0, n), rng.Uniform(0, n), rad, rng.Uniform(1.0, 1.6), rng.Uniform(0, kPi),
          -0.8 * rad, 0.45, 0.8, h, a);
  }
  // Scattered light and dark crystals/clasts.
  const int clasts = static_cast<int>(rng.Uniform(200, 900)) * n / 512;
  for (int k = 0; k < clasts; ++k) {
    const double rad = PowerLawRadius(&rng, 0.7, 3.0, 3.0);
    Stamp(rng.Uniform(0, n), rng.Uniform(0, n), rad, 1.2, rng.Uniform(0, kPi), 0.3 * rad,
          rng.Uniform() < 0.5 ? 0.6 : 1.45, 0.7, h, a);
  }
}

void ScienceRock(std::uint64_t seed, int pattern, int n, Field* a, Field* h) {
  Rng rng(MixSeed(seed, 200 + static_cast<std::uint64_t>(pattern)));
  Field warp = Fbm(&rng, n, n / 2, 4, 0.5);
  Field grain = Blur3(WhiteNoise(&rng, n, 1.0));
  Field rough = Fbm(&rng, n, n / 8, 5, 0.6);
  const double s = n / 512.0;  // patterns are designed at 512 texels
  for (int y = 0; y < n; ++y) {
    for (int x = 0; x < n; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * n + x;
      a->v[i] = static_cast<float>(1.0 + 0.08 * grain.v[i]);
      h->v[i] = static_cast<float>(1.5 * rough.v[i] + 0.3 * grain.v[i]);
    }
  }
  auto band = [&](double phase) { return 0.5 + 0.5 * std::sin(phase); };
  switch (pattern) {
    case 0: {  // fine parallel layering (laminae), gently warped
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const std::size_t i = static_cast<std::size_t>(y) * n + x;
          const double ph = 2.0 * kPi * (y * 32.0 / n + 1.5 * warp.v[i]);
          a->v[i] = static_cast<float>(a->v[i] * (0.65 + 0.8 * band(ph)));
          h->v[i] += static_cast<float>(2.0 * band(ph));
        }
      break;
    }
    case 1: {  // bright vein network (calcium-sulfate-like) on a darker rock
      Worley w(&rng, n, static_cast<int>(64 * s));
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          double f1, f2;
          int id;
          w.Eval(x + 0.5 + 20 * s * warp.at(x, y), y + 0.5, &f1, &f2, &id);
          const std::size_t i = static_cast<std::size_t>(y) * n + x;
          const double e = f2 - f1;
          if (e < 3.0 * s) {
            a->v[i] = 1.9F;
            h->v[i] += static_cast<float>(2.0 * (1.0 - e / (3.0 * s)));
          } else {
            a->v[i] *= 0.75F;
          }
        }
      break;
    }
    case 2: {  // spherules: dark round grains on a light matrix
      for (auto& v : a->v) v *= 1.3F;
      const int count = static_cast<int>(700 * s * s);
      for (int k = 0; k < count; ++k) {
        const double rad = rng.Uniform(2.5, 6.0) * s;
        Stamp(rng.Uniform(0, n), rng.Uniform(0, n), rad, 1.05, 0.0, 0.8 * rad, 0.35, 1.0, h, a);
      }
      break;
    }
    case 3: {  // coarse cross-bedding: two sets of tilted bands
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          const std::size_t i = static_cast<std::size_t>(y) * n + x;
          const bool upper = std::sin(2.0 * kPi * (y * 2.0 / n + 0.3 * warp.v[i])) > 0.0;
          const double ph = 2.0 * kPi * ((upper ? (x + y) : (y - 0.5 * x)) * 10.0 / n);
          a->v[i] = static_cast<float>(a->v[i] * (0.6 + 0.9 * band(ph)));
        }
      break;
    }
    case 4: {  // speckle: high-contrast light/dark blobs
      Field f = Fbm(&rng, n, static_cast<int>(16 * s), 3, 0.5);
      for (std::size_t i = 0; i < a->v.size(); ++i) {
        a->v[i] *= f.v[i] > 0.15 ? 1.7F : (f.v[i] < -0.15 ? 0.45F : 1.0F);
      }
      break;
    }
    case 5: {  // polygonal fractures: light plates with dark cracks
      Worley w(&rng, n, static_cast<int>(32 * s));
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          double f1, f2;
          int id;
          w.Eval(x + 0.5, y + 0.5, &f1, &f2, &id);
          const std::size_t i = static_cast<std::size_t>(y) * n + x;
          const double plate = 1.2 + 0.25 * std::sin(id * 12.9898);
          if (f2 - f1 < 2.0 * s) {
            a->v[i] = 0.3F;
            h->v[i] -= 2.0F;
          } else {
            a->v[i] *= static_cast<float>(plate);
          }
        }
      break;
    }
    case 6: {  // ring clusters (concretions with concentric rims)
      Worley w(&rng, n, static_cast<int>(64 * s));
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
          double f1, f2;
          int id;
          w.Eval(x + 0.5, y + 0.5, &f1, &f2, &id);
          const std::size_t i = static_cast<std::size_t>(y) * n + x;
          a->v[i] = static_cast<float>(a->v[i] * (0.55 + 1.0 * band(2.0 * kPi * f1 / (9.0 * s))));
        }
      break;
    }
    default: {  // mosaic of light and dark blocks
      Rng cell_rng(MixSeed(seed, 300));
      const int c = static_cast<int>(16 * s);
      const int cells = n / c;
      std::vector<float> lv(static_cast<std::size_t>(cells) * cells);
      for (auto& v : lv) v = cell_rng.Uniform() < 0.5 ? 0.5F : 1.6F;
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x)
          a->v[static_cast<std::size_t>(y) * n + x] *=
              lv[static_cast<std::size_t>(y / c) * cells + x / c];
      break;
    }
  }
}

}  // namespace

std::vector<float> PeriodicFbm(std::uint64_t seed, int size, int base_wavelength, int octaves,
                               double persistence) {
  ROVER_DEMAND(IsPow2(size) && IsPow2(base_wavelength) && base_wavelength <= size);
  Rng rng(seed);
  return Fbm(&rng, size, base_wavelength, octaves, persistence).v;
}

TextureImage MakeSoilDetailTexture(std::uint64_t seed, int size) {
  ROVER_DEMAND(IsPow2(size) && size >= 64 && size <= 4096);
  const int n = size;
  const double s = n / 1024.0;  // designed at 1024 texels per metre
  Rng rng(MixSeed(seed, 1));
  Field a = Fbm(&rng, n, n / 8, 6, 0.6);             // mottling 128..4 texels
  Field fine = Blur3(WhiteNoise(&rng, n, 1.0));      // grain ~1.5 texels
  Field bumps = Fbm(&rng, n, std::max(2, n / 32), 5, 0.65);
  Field h(n);
  for (std::size_t i = 0; i < a.v.size(); ++i) {
    a.v[i] = static_cast<float>(1.0 + 0.16 * a.v[i] + 0.22 * fine.v[i]);
    h.v[i] = static_cast<float>(1.2 * bumps.v[i] + 0.45 * fine.v[i]);
  }
  // Pebbles and granules: radius 1.5..14 texels (1.5..14 mm), density ~ r^-3, ~12 % cover.
  const double target_cover = 0.12 * n * n;
  double cover = 0.0;
  while (cover < target_cover) {
    const double r = PowerLawRadius(&rng, 1.5 * s, 14.0 * s, 3.0);
    const double elong = rng.Uniform(1.0, 1.7);
    const double u = rng.Uniform();
    // Mostly dark basaltic clasts, some light ones, few very dark.
    const double albedo = u < 0.55 ? rng.Uniform(0.55, 0.85) : (u < 0.85 ? rng.Uniform(1.1, 1.5)
                                                                         : rng.Uniform(0.35, 0.5));
    Stamp(rng.Uniform(0, n), rng.Uniform(0, n), r, elong, rng.Uniform(0, kPi),
          0.7 * r * rng.Uniform(0.6, 1.2), albedo, 0.9, &h, &a);
    cover += kPi * r * r;
  }
  Normalise(&a, 0.0, 2.0);
  TextureImage img{n, 1, std::vector<std::uint8_t>(static_cast<std::size_t>(n) * n * 4)};
  Encode(a, h, img.rgba.data());
  return img;
}

TextureImage MakeRockTextures(std::uint64_t seed, int size) {
  ROVER_DEMAND(IsPow2(size) && size >= 64 && size <= 4096);
  const int n = size;
  TextureImage img{n, kRockLayers,
                   std::vector<std::uint8_t>(static_cast<std::size_t>(n) * n * 4 * kRockLayers)};
  for (int layer = 0; layer < kRockLayers; ++layer) {
    Field a(n, 1.0F), h(n);
    if (layer < kGenericRockLayers) {
      GenericRock(seed, layer, n, &a, &h);
    } else {
      ScienceRock(seed, layer - kGenericRockLayers, n, &a, &h);
    }
    Normalise(&a, 0.0, 2.0);
    Encode(a, h, img.rgba.data() + static_cast<std::size_t>(layer) * n * n * 4);
  }
  return img;
}

}  // namespace rover::sim::render::internal
