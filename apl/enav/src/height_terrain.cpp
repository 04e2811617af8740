#include "rover/apl/enav/height_terrain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "rover/base/check.hpp"

namespace rover::apl::enav {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr int kMinPointsForMax = 4;

// 1-D squared distance transform of f (Felzenszwalb & Huttenlocher 2012, lower envelope of
// parabolas); f holds 0 at sites and +inf elsewhere. Writes d; v, z are scratch.
void Edt1d(const float* f, int n, float* d, std::vector<int>& v, std::vector<float>& z) {
  v.resize(n);
  z.resize(n + 1);
  int k = -1;
  for (int q = 0; q < n; ++q) {
    if (f[q] == kInf) continue;  // not a site
    if (k < 0) {
      k = 0;
      v[0] = q;
      z[0] = -kInf;
      z[1] = kInf;
      continue;
    }
    auto meet = [&](int p) {
      return ((f[q] + static_cast<float>(q) * q) - (f[p] + static_cast<float>(p) * p)) /
             (2.0F * static_cast<float>(q - p));
    };
    float s = meet(v[k]);
    while (s <= z[k]) {  // z[0] = -inf ends the loop at k = 0
      --k;
      s = meet(v[k]);
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = kInf;
  }
  if (k < 0) {
    std::fill(d, d + n, kInf);
    return;
  }
  int j = 0;
  for (int q = 0; q < n; ++q) {
    while (z[j + 1] < static_cast<float>(q)) ++j;
    const float dq = static_cast<float>(q - v[j]);
    d[q] = dq * dq + f[v[j]];
  }
}

// Sliding minimum over a window of radius r along one axis, NaN (unknown) ignored.
void MinFilter1d(const float* in, int n, int stride, int r, float* out) {
  for (int q = 0; q < n; ++q) {
    float m = kInf;
    for (int t = std::max(0, q - r); t <= std::min(n - 1, q + r); ++t) {
      const float v = in[static_cast<std::size_t>(t) * stride];
      if (v < m) m = v;  // NaN compares false
    }
    out[static_cast<std::size_t>(q) * stride] = m;
  }
}

template <class T>
void ShiftVector(std::vector<T>& cells, int width, int height, int di, int dj, const T& fill) {
  if (di == 0 && dj == 0) return;
  std::vector<T> moved(cells.size(), fill);
  if (std::abs(di) < width && std::abs(dj) < height) {
    for (int j = std::max(0, -dj); j < std::min(height, height - dj); ++j) {
      for (int i = std::max(0, -di); i < std::min(width, width - di); ++i) {
        moved[static_cast<std::size_t>(j) * width + i] =
            cells[static_cast<std::size_t>(j + dj) * width + (i + di)];
      }
    }
  }
  cells.swap(moved);
}

}  // namespace

std::vector<float> SquaredDistanceTransform(const std::vector<std::uint8_t>& mask, int width,
                                            int height) {
  ROVER_DEMAND(mask.size() == static_cast<std::size_t>(width) * height);
  std::vector<float> out(mask.size(), kInf);
  std::vector<float> col(static_cast<std::size_t>(std::max(width, height)));
  std::vector<float> res(col.size());
  std::vector<int> v;
  std::vector<float> z;
  // Columns (along j) first, then rows.
  for (int i = 0; i < width; ++i) {
    for (int j = 0; j < height; ++j) {
      col[j] = mask[static_cast<std::size_t>(j) * width + i] != 0 ? 0.0F : kInf;
    }
    Edt1d(col.data(), height, res.data(), v, z);
    for (int j = 0; j < height; ++j) out[static_cast<std::size_t>(j) * width + i] = res[j];
  }
  for (int j = 0; j < height; ++j) {
    float* row = out.data() + static_cast<std::size_t>(j) * width;
    std::copy(row, row + width, col.begin());
    Edt1d(col.data(), width, row, v, z);
  }
  return out;
}

Result<HeightTerrain> HeightTerrain::Create(const EnavOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  return HeightTerrain(options);
}

HeightTerrain::HeightTerrain(const EnavOptions& options) : options_(options) {
  double rocker = 0.0, body = 0.0;
  bool have_rocker = false, have_body = false;
  const std::vector<hwconfig::ContactPart> parts =
      options.contact_parts.empty() ? options.rover.ContactParts() : options.contact_parts;
  for (const hwconfig::ContactPart& p : parts) {
    if (p.name.rfind("rocker", 0) == 0) {
      rocker = have_rocker ? std::min(rocker, p.clearance) : p.clearance;
      have_rocker = true;
    } else if (p.name == "body") {
      body = p.clearance;
      have_body = true;
    }
  }
  if (!have_body) body = options.rover.BellyClearance();
  if (!have_rocker) rocker = body;
  limits_ = {options.wheel_step, std::max(options.wheel_step, rocker - options.clearance_margin),
             std::max(options.wheel_step, body - options.clearance_margin)};
  const int n = options.map_cells();
  map_.resolution = options.cell_size;
  map_.width = n;
  map_.height = n;
  map_.origin_x = -0.5 * n * options.cell_size;
  map_.origin_y = -0.5 * n * options.cell_size;
  Clear();
}

void HeightTerrain::Clear() {
  const std::size_t cells = map_.cell_count();
  map_.z_mean.assign(cells, kNaN);
  map_.z_min.assign(cells, kNaN);
  map_.z_max.assign(cells, kNaN);
  map_.count.assign(cells, 0);
  map_.range.assign(cells, kInf);
  map_.step.assign(cells, kNaN);
  map_.hazard.assign(cells, 0);
  map_.revision += 1;
  dirty_ = true;
}

void HeightTerrain::Centre(const Eigen::Vector2d& xy) {
  const double half = 0.5 * map_.width * map_.resolution;
  const Eigen::Vector2d centre(map_.origin_x + half, map_.origin_y + half);
  if ((xy - centre).cwiseAbs().maxCoeff() <= options_.recentre_distance) return;
  const int di = static_cast<int>(std::lround((xy.x() - centre.x()) / map_.resolution));
  const int dj = static_cast<int>(std::lround((xy.y() - centre.y()) / map_.resolution));
  const int w = map_.width, h = map_.height;
  ShiftVector(map_.z_mean, w, h, di, dj, kNaN);
  ShiftVector(map_.z_min, w, h, di, dj, kNaN);
  ShiftVector(map_.z_max, w, h, di, dj, kNaN);
  ShiftVector(map_.count, w, h, di, dj, std::uint16_t{0});
  ShiftVector(map_.range, w, h, di, dj, kInf);
  map_.origin_x += di * map_.resolution;
  map_.origin_y += dj * map_.resolution;
  map_.revision += 1;
  dirty_ = true;
}

void HeightTerrain::Follow(const Eigen::Isometry3d& site_from_rover) {
  Centre(site_from_rover.translation().head<2>());
}

Result<nav_core::AssessmentStats> HeightTerrain::Update(const nav_core::RangeScan& scan) {
  ROVER_RETURN_IF_ERROR(scan.Validate());
  Centre(scan.site_from_rover.translation().head<2>());
  nav_core::AssessmentStats stats;
  // Per-cell sums of this scan, in a scratch grid kept between scans (only touched cells are
  // reset afterwards: a scan touches a few thousand of the map's 160,000 cells).
  std::vector<ScanCell>& acc = scratch_;
  if (acc.size() != map_.cell_count()) acc.assign(map_.cell_count(), ScanCell{});
  std::vector<std::size_t> touched;
  const Eigen::Vector2d rover_xy = scan.site_from_rover.translation().head<2>();
  const double max_d2 = options_.max_point_distance * options_.max_point_distance;
  hwconfig::Footprint self = options_.rover.GroundFootprint();
  self.min_x -= options_.self_margin;
  self.max_x += options_.self_margin;
  self.min_y -= options_.self_margin;
  self.max_y += options_.self_margin;
  for (int v = 0; v < scan.height; ++v) {
    for (int u = 0; u < scan.width; ++u) {
      if (!scan.is_valid(u, v)) continue;
      stats.points_total += 1;
      const Eigen::Vector3d p_rover = scan.point(u, v);
      if (!p_rover.allFinite()) continue;
      if (options_.drop_self_points && p_rover.x() >= self.min_x && p_rover.x() <= self.max_x && p_rover.y() >= self.min_y &&
          p_rover.y() <= self.max_y) {
        continue;  // the rover itself, or ground it hides
      }
      const Eigen::Vector3d p = scan.site_from_rover * p_rover;
      const double d2 = (p.head<2>() - rover_xy).squaredNorm();
      if (d2 > max_d2) continue;
      int i = 0, j = 0;
      map_.CellOf(p.x(), p.y(), &i, &j);
      if (!map_.Contains(i, j)) continue;
      stats.points_used += 1;
      const std::size_t k = map_.Index(i, j);
      ScanCell& a = acc[k];
      if (a.n == 0) touched.push_back(k);
      a.n += 1;
      a.sum += p.z();
      a.range += std::sqrt(d2);
      a.lo = std::min(a.lo, static_cast<float>(p.z()));
      a.hi = std::max(a.hi, static_cast<float>(p.z()));
    }
  }
  for (const std::size_t k : touched) {
    const ScanCell& a = acc[k];
    if (a.n < options_.min_cell_points) continue;
    stats.cells_touched += 1;
    const float range = static_cast<float>(a.range / a.n);
    if (map_.count[k] > 0 && range > map_.range[k] + options_.overwrite_range_slack) continue;
    map_.z_mean[k] = static_cast<float>(a.sum / a.n);
    map_.z_min[k] = a.lo;
    map_.z_max[k] = a.hi;
    map_.count[k] = static_cast<std::uint16_t>(std::min(a.n, 65535));
    map_.range[k] = range;
    stats.cells_assessed += 1;
  }
  for (const std::size_t k : touched) acc[k] = ScanCell{};
  map_.stamp = std::max(map_.stamp, scan.capture_time);
  map_.revision += 1;
  dirty_ = true;
  Derive();
  for (const std::size_t k : touched) {
    if ((map_.hazard[k] & nav_core::kHazardWheel) != 0) stats.cells_obstacle += 1;
  }
  return stats;
}

void HeightTerrain::Derive() const {
  if (!dirty_) return;
  dirty_ = false;
  const int w = map_.width, h = map_.height;
  const std::size_t cells = map_.cell_count();
  // Ground: a low quantile (or, with ground_quantile 0, the minimum: a separable square min
  // filter) of z_mean over a square window (unknown ignored).
  const int r = std::max(1, static_cast<int>(std::ceil(options_.ground_radius / map_.resolution)));
  // The ground is the lowest neighbour mean lifted by its own noise allowance: the minimum of
  // noisy means sits below the true ground by about that much, which would read as a step.
  std::vector<float> tmp(cells), ground(cells), lifted(map_.z_mean);
  for (std::size_t k = 0; k < cells; ++k) {
    if (map_.count[k] == 0) continue;
    lifted[k] += static_cast<float>(options_.step_noise_sigmas * options_.stereo_noise_coeff *
                                    map_.range[k] * map_.range[k] /
                                    std::sqrt(static_cast<double>(map_.count[k])));
  }
  if (options_.ground_quantile <= 0.0) {
    for (int j = 0; j < h; ++j) {
      MinFilter1d(lifted.data() + static_cast<std::size_t>(j) * w, w, 1, r,
                  tmp.data() + static_cast<std::size_t>(j) * w);
    }
    for (int i = 0; i < w; ++i) MinFilter1d(tmp.data() + i, h, w, r, ground.data() + i);
  } else {
    // A quantile of the window's known means: stereo holes below the ground are ignored.
    std::vector<float> window;
    for (int j = 0; j < h; ++j) {
      for (int i = 0; i < w; ++i) {
        const std::size_t k = map_.Index(i, j);
        if (map_.count[k] == 0) continue;
        window.clear();
        for (int q = std::max(0, j - r); q <= std::min(h - 1, j + r); ++q) {
          for (int p = std::max(0, i - r); p <= std::min(w - 1, i + r); ++p) {
            const std::size_t n = map_.Index(p, q);
            if (map_.count[n] > 0) window.push_back(lifted[n]);
          }
        }
        const auto at = static_cast<std::ptrdiff_t>(
            std::floor(options_.ground_quantile * static_cast<double>(window.size() - 1)));
        std::nth_element(window.begin(), window.begin() + at, window.end());
        ground[k] = window[static_cast<std::size_t>(at)];
      }
    }
  }
  std::array<std::vector<std::uint8_t>, 3> masks;
  for (auto& m : masks) m.assign(cells, 0);
  for (std::size_t k = 0; k < cells; ++k) {
    map_.hazard[k] = 0;
    if (map_.count[k] == 0) {
      map_.step[k] = kNaN;
      continue;
    }
    const float step = map_.z_mean[k] - ground[k];
    map_.step[k] = step;
    // The step of the mean (noise of a mean of count points) or of the highest point (noise of
    // one point), whichever says more: a rock's top is its highest point, not its cell's mean.
    const double sigma_point = options_.stereo_noise_coeff * map_.range[k] * map_.range[k];
    const double sigma_mean = sigma_point / std::sqrt(static_cast<double>(map_.count[k]));
    // (The highest point only with kMinPointsForMax points: one stereo mismatch is no rock.)
    double s = step - options_.step_noise_sigmas * sigma_mean;
    if (map_.count[k] >= kMinPointsForMax) {
      s = std::max(s, map_.z_max[k] - ground[k] - options_.step_noise_sigmas * sigma_point);
    }
    static constexpr std::uint8_t kBits[3] = {nav_core::kHazardWheel, nav_core::kHazardRocker,
                                              nav_core::kHazardBody};
    for (int c = 0; c < 3; ++c) {
      if (s > limits_[c]) {
        map_.hazard[k] |= kBits[c];
        masks[c][k] = 1;
      }
    }
  }
  // Grow each class (breadth first, 4-connected) over `into` cells, at most `reach` cells.
  std::vector<std::size_t> front, next;
  auto grow = [&](const std::vector<std::uint8_t>& into, int reach) {
    for (int c = 0; c < 3 && reach > 0; ++c) {
      std::vector<std::uint8_t>& m = masks[c];
      front.clear();
      for (std::size_t k = 0; k < cells; ++k) {
        if (m[k] != 0) front.push_back(k);
      }
      for (int d = 0; d < reach && !front.empty(); ++d) {
        next.clear();
        for (const std::size_t k : front) {
          const int i = static_cast<int>(k % w), j = static_cast<int>(k / w);
          const int ni[4] = {i + 1, i - 1, i, i};
          const int nj[4] = {j, j, j + 1, j - 1};
          for (int n = 0; n < 4; ++n) {
            if (ni[n] < 0 || nj[n] < 0 || ni[n] >= w || nj[n] >= h) continue;
            const std::size_t q = static_cast<std::size_t>(nj[n]) * w + ni[n];
            if (m[q] != 0 || into[q] == 0) continue;
            m[q] = 1;
            next.push_back(q);
          }
        }
        front.swap(next);
      }
    }
  };
  // Over the flanks (at most flank_reach).
  const int reach = static_cast<int>(std::floor(options_.flank_reach / map_.resolution + 1e-9));
  if (reach > 0) {
    std::vector<std::uint8_t> flank(cells, 0);
    for (std::size_t k = 0; k < cells; ++k) {
      if (map_.count[k] == 0) continue;
      const double sigma = options_.stereo_noise_coeff * map_.range[k] * map_.range[k] /
                           std::sqrt(static_cast<double>(map_.count[k]));
      flank[k] = map_.step[k] - options_.step_noise_sigmas * sigma > options_.flank_step ? 1 : 0;
    }
    grow(flank, reach);
  }
  // Into the unseen cells beside a hazard (at most shadow_reach): the side of a rock the
  // cameras have not seen yet is more likely rock than ground.
  const int shadow = static_cast<int>(std::floor(options_.shadow_reach / map_.resolution + 1e-9));
  if (shadow > 0) {
    std::vector<std::uint8_t> unseen(cells, 0);
    for (std::size_t k = 0; k < cells; ++k) unseen[k] = map_.count[k] == 0 ? 1 : 0;
    grow(unseen, shadow);
  }
  for (std::size_t k = 0; k < cells; ++k) {
    map_.hazard[k] = static_cast<std::uint8_t>((masks[0][k] != 0 ? nav_core::kHazardWheel : 0) |
                                               (masks[1][k] != 0 ? nav_core::kHazardRocker : 0) |
                                               (masks[2][k] != 0 ? nav_core::kHazardBody : 0));
  }
  const float res = static_cast<float>(map_.resolution);
  for (int c = 0; c < 3; ++c) {
    distance_[c] = SquaredDistanceTransform(masks[c], w, h);
    for (float& d : distance_[c]) d = std::sqrt(d) * res;
  }
  // Goodness at cost_cell_size.
  const int f = static_cast<int>(std::lround(options_.cost_cell_size / map_.resolution));
  goodness_.resolution = map_.resolution * f;
  goodness_.origin_x = map_.origin_x;
  goodness_.origin_y = map_.origin_y;
  goodness_.width = w / f;
  goodness_.height = h / f;
  goodness_.unknown_goodness = 0;
  goodness_.unknown_certainty = 0;
  const std::size_t gcells = goodness_.cell_count();
  goodness_.goodness.assign(gcells, 0);
  goodness_.certainty.assign(gcells, 0);
  goodness_.flags.assign(gcells, 0);
  for (int gj = 0; gj < goodness_.height; ++gj) {
    for (int gi = 0; gi < goodness_.width; ++gi) {
      bool known = false;
      float dw = kInf, db = kInf;
      for (int dj = 0; dj < f; ++dj) {
        for (int di = 0; di < f; ++di) {
          const std::size_t k = map_.Index(gi * f + di, gj * f + dj);
          known = known || map_.count[k] > 0;
          dw = std::min(dw, distance_[0][k]);
          db = std::min(db, distance_[2][k]);
        }
      }
      const std::size_t g = goodness_.Index(gi, gj);
      if (!known) continue;
      goodness_.flags[g] = nav_core::kCellKnown;
      goodness_.certainty[g] = 255;
      int value = 255;
      if (db < options_.blocked_radius) {
        value = 0;
      } else if (options_.hazard_cost_radius > 0.0 && dw < options_.hazard_cost_radius) {
        value = static_cast<int>(std::lround(255.0 * dw / options_.hazard_cost_radius));
      }
      if ((map_.hazard[map_.Index(gi * f, gj * f)] & nav_core::kHazardWheel) != 0) {
        goodness_.flags[g] |= nav_core::kCellHazard;
      }
      goodness_.goodness[g] = static_cast<std::uint8_t>(std::clamp(value, 0, 255));
    }
  }
  goodness_.stamp = map_.stamp;
  goodness_.revision = map_.revision;
}

const nav_core::GoodnessMap& HeightTerrain::goodness_map() const {
  Derive();
  return goodness_;
}

const nav_core::HeightMap* HeightTerrain::height_map() const {
  Derive();
  return &map_;
}

const std::vector<float>& HeightTerrain::distance(HazardLayer layer) const {
  Derive();
  return distance_[static_cast<int>(layer)];
}

float HeightTerrain::DistanceAt(HazardLayer layer, const Eigen::Vector2d& xy) const {
  Derive();
  int i = 0, j = 0;
  map_.CellOf(xy.x(), xy.y(), &i, &j);
  if (!map_.Contains(i, j)) return kInf;
  return distance_[static_cast<int>(layer)][map_.Index(i, j)];
}

}  // namespace rover::apl::enav
