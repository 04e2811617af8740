// Step 3 of the traversability map: surface normals from plane fits over each cell and its
// neighbours, with the moments summed over the window from summed-area tables.
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "rover/apl/roaman/traversability.hpp"

namespace rover::apl::roaman {
namespace {

// Moments of the cells with a height: 1, i, j, i^2, i j, j^2, z, i z, j z, z^2 (cell indices,
// z relative to a reference height for precision).
constexpr int kMoments = 10;

}  // namespace

NormalMap FitNormals(const ElevationMap& map, const RoamanOptions& options) {
  const int w = map.geometry.width, h = map.geometry.height;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  NormalMap out;
  out.normal = Layer<Eigen::Vector3f>(w, h, Eigen::Vector3f::Zero());
  out.slope = Layer<float>(w, h, nan);
  out.residual = Layer<float>(w, h, nan);
  if (w == 0 || h == 0) return out;

  double z_ref = 0.0;
  int n_ref = 0;
  for (std::size_t k = 0; k < map.mean.size(); ++k) {
    if (map.source[k] != HeightSource::kNone) {
      z_ref += map.mean[k];
      ++n_ref;
    }
  }
  if (n_ref == 0) return out;
  z_ref /= n_ref;

  // Summed-area tables, (w + 1) x (h + 1): sat[(j + 1) (w + 1) + (i + 1)] sums cells [0, i] x
  // [0, j].
  const int sw = w + 1;
  std::vector<std::array<double, kMoments>> sat(static_cast<std::size_t>(sw) * (h + 1));
  for (auto& s : sat) s.fill(0.0);
  for (int j = 0; j < h; ++j) {
    std::array<double, kMoments> row{};
    for (int i = 0; i < w; ++i) {
      if (map.source.at(i, j) != HeightSource::kNone) {
        const double z = map.mean.at(i, j) - z_ref;
        const double x = i, y = j;
        const double m[kMoments] = {1.0, x, y, x * x, x * y, y * y, z, x * z, y * z, z * z};
        for (int q = 0; q < kMoments; ++q) row[q] += m[q];
      }
      const auto& above = sat[static_cast<std::size_t>(j) * sw + (i + 1)];
      auto& cur = sat[static_cast<std::size_t>(j + 1) * sw + (i + 1)];
      for (int q = 0; q < kMoments; ++q) cur[q] = above[q] + row[q];
    }
  }

  const int half = options.normal_half_cells();
  const double cell = map.geometry.cell;
  for (int j = 0; j < h; ++j) {
    const int j0 = std::max(0, j - half), j1 = std::min(h - 1, j + half);
    for (int i = 0; i < w; ++i) {
      if (map.source.at(i, j) == HeightSource::kNone) continue;
      const int i0 = std::max(0, i - half), i1 = std::min(w - 1, i + half);
      const auto& a = sat[static_cast<std::size_t>(j1 + 1) * sw + (i1 + 1)];
      const auto& b = sat[static_cast<std::size_t>(j0) * sw + (i1 + 1)];
      const auto& c = sat[static_cast<std::size_t>(j1 + 1) * sw + i0];
      const auto& d = sat[static_cast<std::size_t>(j0) * sw + i0];
      double s[kMoments];
      for (int q = 0; q < kMoments; ++q) s[q] = a[q] - b[q] - c[q] + d[q];
      const double n = s[0];
      if (n < options.min_fit_cells) continue;
      // Central moments.
      const double sxx = s[3] - s[1] * s[1] / n;
      const double sxy = s[4] - s[1] * s[2] / n;
      const double syy = s[5] - s[2] * s[2] / n;
      const double sxz = s[7] - s[1] * s[6] / n;
      const double syz = s[8] - s[2] * s[6] / n;
      const double szz = s[9] - s[6] * s[6] / n;
      const double det = sxx * syy - sxy * sxy;
      // Collinear cells (a line of heights) leave the cross-slope undetermined.
      if (det <= 1e-6 * std::max(1.0, sxx * syy)) continue;
      const double ga = (syy * sxz - sxy * syz) / det;  // dz per cell along i
      const double gb = (sxx * syz - sxy * sxz) / det;  // dz per cell along j
      const double gx = ga / cell, gy = gb / cell;       // dz / dx, dz / dy
      const double rss = std::max(0.0, szz - ga * sxz - gb * syz);
      const Eigen::Vector3d nrm = Eigen::Vector3d(-gx, -gy, 1.0).normalized();
      out.normal.at(i, j) = nrm.cast<float>();
      out.slope.at(i, j) = static_cast<float>(std::atan(std::hypot(gx, gy)));
      out.residual.at(i, j) = static_cast<float>(std::sqrt(rss / n));
    }
  }
  return out;
}

}  // namespace rover::apl::roaman
