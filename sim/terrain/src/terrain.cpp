#include "rover/sim/terrain/terrain.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>

#include "rover/base/check.hpp"
#include "rover/base/format.hpp"
#include "rover/base/units.hpp"
#include "rover/sim/terrain/noise.hpp"
#include "rover/sim/terrain/random.hpp"
#include "rover/sim/terrain/rock_model.hpp"

namespace rover::sim::terrain {
namespace {

constexpr int kMaxPlacementAttempts = 2000;
// How strongly soil patches follow the relief (in units of the noise's own spread).
constexpr double kSoilReliefBias = 0.35;

// Independent random streams (MixSeed(seed, stream)).
enum Stream : std::uint64_t {
  kHillStream = 1,
  kCraterStream = 2,
  kSandStream = 3,
  kBedrockStream = 4,
  kRockSizeStream = 5,
  kRockPositionStream = 6,
  kRockShapeStream = 7,
};

double Smoothstep(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3.0 - 2.0 * t);
}

// Inclusive cell index range of samples with coordinate in [lo, hi] along one axis.
void SampleRange(double origin, double resolution, int n, double lo, double hi, int* first,
                 int* last) {
  *first = std::max(0, static_cast<int>(std::ceil((lo - origin) / resolution)));
  *last = std::min(n - 1, static_cast<int>(std::floor((hi - origin) / resolution)));
}

// Octaves whose wavelength stays at or above two grid cells (at least one).
int ResolvedOctaves(double wavelength, int octaves, double resolution) {
  int n = 1;
  while (n < octaves && wavelength / std::pow(2.0, n) >= 2.0 * resolution) ++n;
  return n;
}

// Threshold t such that about `count` of `values` are >= t (count in [1, size]).
float TopThreshold(std::vector<float> values, std::size_t count) {
  ROVER_DEMAND(count >= 1 && count <= values.size());
  const auto nth = values.begin() + static_cast<std::ptrdiff_t>(values.size() - count);
  std::nth_element(values.begin(), nth, values.end());
  return *nth;
}

struct ShapeAxes {
  double a, b, lobe, cos_phase, sin_phase, cos_yaw, sin_yaw;
};

ShapeAxes Axes(const Rock& r) {
  const double radius = 0.5 * r.diameter;
  const double norm = 1.0 / std::sqrt(1.0 + 0.5 * r.lobe_amplitude * r.lobe_amplitude);
  const double se = std::sqrt(std::max(r.elongation, 1.0));
  return {radius * se * norm,     radius / se * norm, r.lobe_amplitude, std::cos(r.lobe_phase),
          std::sin(r.lobe_phase), std::cos(r.yaw),    std::sin(r.yaw)};
}

}  // namespace

// ---- rock and crater shapes ----------------------------------------------------------------

double RockRelief(const Rock& rock, double x, double y) {
  if (rock.layers > 0) {
    // Rectangle half sizes; bed k covers the rectangle inset by k * step on every side.
    const double hl = 0.5 * rock.diameter, hd = 0.5 * rock.diameter / std::max(rock.elongation, 1.0);
    const double step = kOutcropInset * 2.0 * hd / rock.layers;
    const double dx = x - rock.position.x(), dy = y - rock.position.y();
    const double c = std::cos(rock.yaw), sn = std::sin(rock.yaw);
    const double u = std::abs(c * dx + sn * dy), v = std::abs(-sn * dx + c * dy);
    const double inside = std::min(hl - u, hd - v);  // distance inside the footprint's edge
    if (inside <= 0.0) return 0.0;
    const int beds = std::min(rock.layers, 1 + static_cast<int>(std::floor(inside / step)));
    return rock.height * beds / rock.layers;
  }
  const ShapeAxes s = Axes(rock);
  const double dx = x - rock.position.x(), dy = y - rock.position.y();
  const double u = (s.cos_yaw * dx + s.sin_yaw * dy) / s.a;
  const double v = (-s.sin_yaw * dx + s.cos_yaw * dy) / s.b;
  const double rho_e2 = u * u + v * v;
  const double bound = 1.0 + std::abs(s.lobe);
  if (rho_e2 >= bound * bound) return 0.0;
  double rho2 = rho_e2;
  if (s.lobe != 0.0 && rho_e2 > 0.0) {
    // Outline radius 1 + A cos(3 theta + phase), theta = atan2(v, u), via the triple-angle
    // formulas (no trigonometric calls per sample).
    const double rho_e = std::sqrt(rho_e2);
    const double c = u / rho_e, sn = v / rho_e;
    const double c3 = 4.0 * c * c * c - 3.0 * c, s3 = 3.0 * sn - 4.0 * sn * sn * sn;
    const double outline = 1.0 + s.lobe * (c3 * s.cos_phase - s3 * s.sin_phase);
    rho2 = rho_e2 / (outline * outline);
  }
  if (rho2 >= 1.0) return 0.0;
  return rock.height * std::pow(1.0 - rho2, rock.bluntness);
}

double RockBoundingRadius(const Rock& rock) {
  if (rock.layers > 0) return 0.5 * std::hypot(rock.diameter, rock.diameter / std::max(rock.elongation, 1.0));
  const ShapeAxes s = Axes(rock);
  return std::max(s.a, s.b) * (1.0 + std::abs(s.lobe));
}

std::vector<Eigen::Vector2d> RockOutline(const Rock& rock, int n) {
  ROVER_DEMAND(n >= 3);
  std::vector<Eigen::Vector2d> out;
  out.reserve(static_cast<std::size_t>(n));
  if (rock.layers > 0) {
    // The rectangle's perimeter walked counter-clockwise from the +u,-v corner, n points.
    const double hl = 0.5 * rock.diameter, hd = 0.5 * rock.diameter / std::max(rock.elongation, 1.0);
    const double c = std::cos(rock.yaw), sn = std::sin(rock.yaw);
    const double perimeter = 4.0 * (hl + hd);
    const std::array<Eigen::Vector2d, 5> corner = {
        Eigen::Vector2d(hl, -hd), Eigen::Vector2d(hl, hd), Eigen::Vector2d(-hl, hd),
        Eigen::Vector2d(-hl, -hd), Eigen::Vector2d(hl, -hd)};
    for (int k = 0; k < n; ++k) {
      double t = perimeter * k / n;
      int e = 0;
      while (e < 3 && t > (corner[e + 1] - corner[e]).norm()) t -= (corner[e + 1] - corner[e]).norm(), ++e;
      const Eigen::Vector2d d = corner[e + 1] - corner[e];
      const Eigen::Vector2d p = corner[e] + d * (t / d.norm());
      out.emplace_back(rock.position.x() + c * p.x() - sn * p.y(), rock.position.y() + sn * p.x() + c * p.y());
    }
    return out;
  }
  const ShapeAxes s = Axes(rock);
  for (int k = 0; k < n; ++k) {
    const double t = 2.0 * std::numbers::pi * k / n;
    const double l = 1.0 + s.lobe * std::cos(3.0 * t + rock.lobe_phase);
    const double u = s.a * l * std::cos(t), v = s.b * l * std::sin(t);
    out.emplace_back(rock.position.x() + s.cos_yaw * u - s.sin_yaw * v,
                     rock.position.y() + s.sin_yaw * u + s.cos_yaw * v);
  }
  return out;
}

double CraterRelief(const Crater& c, double x, double y) {
  const double radius = 0.5 * c.diameter;
  if (radius <= 0.0) return 0.0;
  const double s = std::hypot(x - c.center.x(), y - c.center.y()) / radius;
  if (s < 1.0) return -c.depth + (c.depth + c.rim_height) * s * s;
  if (s >= 3.0) return 0.0;
  return c.rim_height / (s * s * s) * (1.0 - Smoothstep((s - 1.5) / 1.5));
}

const Rock* Terrain::FindRock(int id) const {
  for (const Rock& r : rocks) {
    if (r.id == id) return &r;
  }
  return nullptr;
}

// ---- composition ---------------------------------------------------------------------------

void RebuildHeights(Terrain* t) {
  ROVER_DEMAND(t != nullptr && t->bare.nx() >= 2);
  t->natural = t->bare;
  HeightField& h = t->natural;
  for (const Rock& rock : t->rocks) {
    const double br = RockBoundingRadius(rock);
    int i0, i1, j0, j1;
    SampleRange(h.min_x(), h.resolution(), h.nx(), rock.position.x() - br, rock.position.x() + br,
                &i0, &i1);
    SampleRange(h.min_y(), h.resolution(), h.ny(), rock.position.y() - br, rock.position.y() + br,
                &j0, &j1);
    for (int j = j0; j <= j1; ++j) {
      const double y = h.min_y() + j * h.resolution();
      for (int i = i0; i <= i1; ++i) {
        const double relief = RockRelief(rock, h.min_x() + i * h.resolution(), y);
        if (relief <= 0.0) continue;
        const float z = static_cast<float>(t->bare.at(i, j) + relief);
        if (z > h.at(i, j)) h.at(i, j) = z;
      }
    }
  }
  t->ground = t->natural;
  if (t->lander) StampLander(*t->lander, &t->ground);
}

// ---- generation ----------------------------------------------------------------------------

Result<Terrain> GenerateTerrain(const TerrainParams& p) {
  ROVER_RETURN_IF_ERROR(p.Validate());
  const int nx = static_cast<int>(std::floor(p.size_x / p.resolution + 1e-9)) + 1;
  const int ny = static_cast<int>(std::floor(p.size_y / p.resolution + 1e-9)) + 1;
  const Eigen::Vector2d origin(p.center_x - 0.5 * p.size_x, p.center_y - 0.5 * p.size_y);

  Terrain t;
  t.params = p;
  t.bare = HeightField(nx, ny, p.resolution, origin);
  HeightField& bare = t.bare;
  const Eigen::Vector2d lo(bare.min_x(), bare.min_y()), hi(bare.max_x(), bare.max_y());
  const double res = p.resolution;
  const std::size_t n = static_cast<std::size_t>(nx) * static_cast<std::size_t>(ny);
  auto index = [nx](int i, int j) {
    return static_cast<std::size_t>(j) * static_cast<std::size_t>(nx) + static_cast<std::size_t>(i);
  };

  // 1. Base plane.
  const double tan_slope = std::tan(p.slope.angle_deg * kDegree);
  const Eigen::Vector2d uphill(std::cos(p.slope.uphill_direction_deg * kDegree),
                               std::sin(p.slope.uphill_direction_deg * kDegree));
  auto plane = [&](double x, double y) {
    return tan_slope * ((x - p.center_x) * uphill.x() + (y - p.center_y) * uphill.y());
  };

  // 2. Hills: relief above the plane.
  std::vector<double> relief(n, 0.0);
  std::optional<FractalNoise> hills;
  if (p.hills.amplitude > 0.0) {
    Rng rng(MixSeed(p.seed, kHillStream));
    hills.emplace(&rng, lo, hi, p.hills.wavelength,
                  ResolvedOctaves(p.hills.wavelength, p.hills.octaves, res), p.hills.persistence);
    hills->AddToGrid(lo.x(), lo.y(), res, nx, ny, p.hills.amplitude, relief.data());
  }

  // 3. Craters.
  {
    Rng rng(MixSeed(p.seed, kCraterStream));
    const double a2 = 1.0 / (p.craters.diameter_min * p.craters.diameter_min);
    const double b2 = 1.0 / (p.craters.diameter_max * p.craters.diameter_max);
    for (int c = 0; c < p.craters.count; ++c) {
      Crater crater;
      crater.diameter = 1.0 / std::sqrt(a2 - rng.Uniform() * (a2 - b2));  // N(>D) ~ D^-2
      crater.center = Eigen::Vector2d(rng.Uniform(lo.x(), hi.x()), rng.Uniform(lo.y(), hi.y()));
      const double freshness = rng.Uniform(0.6, 1.0);
      crater.depth = p.craters.depth_ratio * crater.diameter * freshness;
      crater.rim_height = p.craters.rim_ratio * crater.diameter * freshness;
      const double reach = 1.5 * crater.diameter;  // relief vanishes at 3 radii
      int i0, i1, j0, j1;
      SampleRange(lo.x(), res, nx, crater.center.x() - reach, crater.center.x() + reach, &i0, &i1);
      SampleRange(lo.y(), res, ny, crater.center.y() - reach, crater.center.y() + reach, &j0, &j1);
      for (int j = j0; j <= j1; ++j) {
        for (int i = i0; i <= i1; ++i) {
          relief[index(i, j)] += CraterRelief(crater, lo.x() + i * res, lo.y() + j * res);
        }
      }
      t.craters.push_back(crater);
    }
  }

  // 4. Keep-out disc: relief replaced by its value at the start (so the disc lies in the base
  //    plane), faded back in over the blend ring.
  const Eigen::Vector2d start(p.start.x, p.start.y);
  const double r_in = p.start.keep_out_radius, blend = p.start.blend_width;
  if (r_in > 0.0 || blend > 0.0) {
    double relief_start = hills ? p.hills.amplitude * (*hills)(start.x(), start.y()) : 0.0;
    for (const Crater& c : t.craters) relief_start += CraterRelief(c, start.x(), start.y());
    const double r_out = r_in + blend;
    int i0, i1, j0, j1;
    SampleRange(lo.x(), res, nx, start.x() - r_out, start.x() + r_out, &i0, &i1);
    SampleRange(lo.y(), res, ny, start.y() - r_out, start.y() + r_out, &j0, &j1);
    for (int j = j0; j <= j1; ++j) {
      for (int i = i0; i <= i1; ++i) {
        const double d = std::hypot(lo.x() + i * res - start.x(), lo.y() + j * res - start.y());
        if (d >= r_out) continue;
        const double w = blend > 0.0 ? Smoothstep((d - r_in) / blend) : (d >= r_in ? 1.0 : 0.0);
        double& r = relief[index(i, j)];
        r = relief_start + w * (r - relief_start);
      }
    }
  }
  for (int j = 0; j < ny; ++j) {
    const double y = lo.y() + j * res;
    for (int i = 0; i < nx; ++i) {
      bare.at(i, j) = static_cast<float>(plane(lo.x() + i * res, y) + relief[index(i, j)]);
    }
  }

  // 5. Soil patches.
  const std::size_t sand_cells =
      static_cast<std::size_t>(std::llround(p.soil.sand_fraction * static_cast<double>(n)));
  const std::size_t bedrock_cells =
      static_cast<std::size_t>(std::llround(p.soil.bedrock_fraction * static_cast<double>(n)));
  if (sand_cells > 0 || bedrock_cells > 0) {
    double mean = 0.0, sq = 0.0;
    for (double r : relief) mean += r;
    mean /= static_cast<double>(n);
    for (double r : relief) sq += (r - mean) * (r - mean);
    const double sd = std::sqrt(sq / static_cast<double>(n));
    const double bias = sd > 1e-9 ? kSoilReliefBias / sd : 0.0;
    const int octaves = ResolvedOctaves(p.soil.patch_scale, 3, res);
    Rng sand_rng(MixSeed(p.seed, kSandStream)), bed_rng(MixSeed(p.seed, kBedrockStream));
    const FractalNoise sand_noise(&sand_rng, lo, hi, p.soil.patch_scale, octaves, 0.5);
    const FractalNoise bed_noise(&bed_rng, lo, hi, p.soil.patch_scale, octaves, 0.5);
    std::vector<double> sand_field(n, 0.0), bed_field(n, 0.0);
    sand_noise.AddToGrid(lo.x(), lo.y(), res, nx, ny, 1.0 / sand_noise.max_abs(),
                         sand_field.data());
    bed_noise.AddToGrid(lo.x(), lo.y(), res, nx, ny, 1.0 / bed_noise.max_abs(), bed_field.data());
    std::vector<float> sand(n), bed(n);
    for (std::size_t c = 0; c < n; ++c) {
      const double rel = bias * (relief[c] - mean);
      sand[c] = static_cast<float>(sand_field[c] - rel);
      bed[c] = static_cast<float>(bed_field[c] + rel);
    }
    std::vector<bool> is_sand(n, false);
    if (sand_cells > 0) {
      const float thr = TopThreshold(sand, std::min(sand_cells, n));
      for (std::size_t c = 0; c < n; ++c) is_sand[c] = sand[c] >= thr;
    }
    if (bedrock_cells > 0) {
      std::vector<float> candidates;
      for (std::size_t c = 0; c < n; ++c) {
        if (!is_sand[c]) candidates.push_back(bed[c]);
      }
      const std::size_t count = std::min(bedrock_cells, candidates.size());
      if (count > 0) {
        const float thr = TopThreshold(std::move(candidates), count);
        for (int j = 0; j < ny; ++j) {
          for (int i = 0; i < nx; ++i) {
            if (!is_sand[index(i, j)] && bed[index(i, j)] >= thr) bare.soil(i, j) = Soil::kBedrock;
          }
        }
      }
    }
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        if (is_sand[index(i, j)]) bare.soil(i, j) = Soil::kLooseSand;
      }
    }
  }

  // 6. Rocks.
  const double k = p.rocks.EffectiveK();
  if (k > 0.0) {
    const double d_min = p.rocks.diameter_min, d_max = p.rocks.diameter_max;
    const double area = (hi.x() - lo.x()) * (hi.y() - lo.y());
    const auto count =
        static_cast<std::size_t>(std::llround(area * RockCountPerArea(k, d_min, d_max)));
    Rng size_rng(MixSeed(p.seed, kRockSizeStream));
    Rng pos_rng(MixSeed(p.seed, kRockPositionStream));
    Rng shape_rng(MixSeed(p.seed, kRockShapeStream));
    std::vector<double> diameters(count);
    for (double& d : diameters) d = SampleRockDiameter(k, d_min, d_max, &size_rng);
    std::sort(diameters.begin(), diameters.end(), std::greater<>());

    // Uniform bucket grid for overlap queries; a bucket is at least one largest diameter wide,
    // so two touching rocks are never more than one bucket apart.
    const double bucket = std::max(d_max, 4.0 * res);
    const int bx = static_cast<int>((hi.x() - lo.x()) / bucket) + 1;
    const int by = static_cast<int>((hi.y() - lo.y()) / bucket) + 1;
    std::vector<std::vector<int>> buckets(static_cast<std::size_t>(bx) *
                                          static_cast<std::size_t>(by));
    auto bucket_of = [&](double x, double y, int* ix, int* iy) {
      *ix = std::clamp(static_cast<int>((x - lo.x()) / bucket), 0, bx - 1);
      *iy = std::clamp(static_cast<int>((y - lo.y()) / bucket), 0, by - 1);
    };
    auto overlaps = [&](double x, double y, double radius) {
      int ix, iy;
      bucket_of(x, y, &ix, &iy);
      for (int qy = std::max(0, iy - 1); qy <= std::min(by - 1, iy + 1); ++qy) {
        for (int qx = std::max(0, ix - 1); qx <= std::min(bx - 1, ix + 1); ++qx) {
          for (int r : buckets[static_cast<std::size_t>(qy) * static_cast<std::size_t>(bx) +
                               static_cast<std::size_t>(qx)]) {
            const Rock& o = t.rocks[static_cast<std::size_t>(r)];
            const double dx = o.position.x() - x, dy = o.position.y() - y;
            const double reach = radius + 0.5 * o.diameter;
            if (dx * dx + dy * dy < reach * reach) return true;
          }
        }
      }
      return false;
    };
    auto in_keep_out = [&](double x, double y, double radius) {
      return r_in > 0.0 && std::hypot(x - start.x(), y - start.y()) < r_in + radius;
    };

    const double lo_ratio = p.rocks.height_ratio - p.rocks.height_ratio_spread;
    const double hi_ratio = p.rocks.height_ratio + p.rocks.height_ratio_spread;
    t.rocks.reserve(count);
    for (std::size_t c = 0; c < count; ++c) {
      const double d = diameters[c], radius = 0.5 * d;
      double x = pos_rng.Uniform(lo.x(), hi.x()), y = pos_rng.Uniform(lo.y(), hi.y());
      // Shape draws come first and always in the same number, so they do not depend on how
      // many positions were tried.
      Rock rock;
      const double ratio = shape_rng.Uniform(lo_ratio, hi_ratio);
      rock.elongation = shape_rng.Uniform(1.0, 1.6);
      rock.yaw = shape_rng.Uniform(0.0, std::numbers::pi);
      rock.bluntness = shape_rng.Uniform(0.3, 0.7);
      rock.lobe_amplitude = shape_rng.Uniform(0.0, 0.12);
      rock.lobe_phase = shape_rng.Uniform(0.0, 2.0 * std::numbers::pi);
      rock.texture_id =
          static_cast<int>(shape_rng.UniformInt(static_cast<std::uint64_t>(p.rocks.texture_count)));
      if (in_keep_out(x, y, radius)) continue;  // thinning: keeps the density elsewhere
      int attempts = 1;
      while (overlaps(x, y, radius) || in_keep_out(x, y, radius)) {
        if (++attempts > kMaxPlacementAttempts) {
          double placed = 0.0;
          for (const Rock& r : t.rocks) placed += 0.25 * std::numbers::pi * r.diameter * r.diameter;
          const std::string key =
              p.rocks.preset == RockPreset::kCustom ? "rocks.k" : "rocks.preset";
          return InvalidArgument(
              key + ": k = " + FormatNumber(k) + " is too dense to place: only " +
              std::to_string(t.rocks.size()) + " of " + std::to_string(count) +
              " rocks fit without overlap (rocks cover " + FormatNumber(100.0 * placed / area) +
              " % of the requested " + FormatNumber(100.0 * RockAreaFraction(k, d_min, d_max)) +
              " %); lower k or raise rocks.diameter_min");
        }
        x = pos_rng.Uniform(lo.x(), hi.x());
        y = pos_rng.Uniform(lo.y(), hi.y());
      }
      rock.id = t.next_rock_id++;
      rock.position = Eigen::Vector3d(x, y, bare.Height(x, y));
      rock.diameter = d;
      rock.height = ratio * d;
      int ix, iy;
      bucket_of(x, y, &ix, &iy);
      buckets[static_cast<std::size_t>(iy) * static_cast<std::size_t>(bx) +
              static_cast<std::size_t>(ix)]
          .push_back(static_cast<int>(t.rocks.size()));
      t.rocks.push_back(rock);
    }
  }

  RebuildHeights(&t);
  return t;
}

}  // namespace rover::sim::terrain
