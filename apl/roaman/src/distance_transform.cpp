#include "rover/apl/roaman/distance_transform.hpp"

#include <cmath>
#include <limits>
#include <vector>

namespace rover::apl::roaman {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// 1-D squared distance transform of f (n samples) into d: d[q] = min_p (q - p)^2 + f[p].
// v, z are scratch of sizes n and n + 1.
void Transform1D(const double* f, int n, double* d, int* v, double* z) {
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[q] == kInf) continue;
    if (k < 0) {
      k = 0;
      v[0] = q;
      z[0] = -kInf;
      z[1] = kInf;
      continue;
    }
    double s = 0.0;
    while (true) {
      const int p = v[k];
      s = ((f[q] + static_cast<double>(q) * q) - (f[p] + static_cast<double>(p) * p)) /
          (2.0 * (q - p));
      if (s > z[k]) break;
      if (--k < 0) break;
    }
    ++k;
    v[k] = q;
    z[k] = k == 0 ? -kInf : s;
    z[k + 1] = kInf;
  }
  if (k < 0) {
    for (int q = 0; q < n; ++q) d[q] = kInf;
    return;
  }
  int j = 0;
  for (int q = 0; q < n; ++q) {
    while (z[j + 1] < q) ++j;
    const double dq = q - v[j];
    d[q] = dq * dq + f[v[j]];
  }
}

}  // namespace

Layer<float> DistanceTransform(const Layer<std::uint8_t>& feature) {
  const int w = feature.width(), h = feature.height();
  Layer<float> out(w, h, std::numeric_limits<float>::infinity());
  if (w == 0 || h == 0) return out;
  const int n = std::max(w, h);
  std::vector<double> f(n), d(n), z(n + 1);
  std::vector<int> v(n);
  std::vector<double> cols(static_cast<std::size_t>(w) * h);
  // Along j (columns) first: squared distance to the nearest feature in the same column.
  for (int i = 0; i < w; ++i) {
    for (int j = 0; j < h; ++j) f[j] = feature.at(i, j) ? 0.0 : kInf;
    Transform1D(f.data(), h, d.data(), v.data(), z.data());
    for (int j = 0; j < h; ++j) cols[static_cast<std::size_t>(j) * w + i] = d[j];
  }
  // Then along i (rows).
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) f[i] = cols[static_cast<std::size_t>(j) * w + i];
    Transform1D(f.data(), w, d.data(), v.data(), z.data());
    for (int i = 0; i < w; ++i) {
      out.at(i, j) = d[i] == kInf ? std::numeric_limits<float>::infinity()
                                  : static_cast<float>(std::sqrt(d[i]));
    }
  }
  return out;
}

}  // namespace rover::apl::roaman
