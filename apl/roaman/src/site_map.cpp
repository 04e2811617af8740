#include "rover/apl/roaman/site_map.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "rover/base/format.hpp"
#include "rover/base/range_check.hpp"

namespace rover::apl::roaman {
namespace {

bool Finite(const Eigen::Vector2d& p) { return std::isfinite(p.x()) && std::isfinite(p.y()); }

// The geometry of a grid of `cells` x `cells` whose centre is the cell corner nearest to xy.
GridGeometry CenteredOn(const Eigen::Vector2d& xy, double cell, int cells) {
  GridGeometry g;
  g.cell = cell;
  g.width = cells;
  g.height = cells;
  const double half = 0.5 * cells * cell;
  g.origin_x = cell * std::round((xy.x() - half) / cell);
  g.origin_y = cell * std::round((xy.y() - half) / cell);
  return g;
}

}  // namespace

double CellStats::variance() const {
  const double m = mean();
  return std::max(0.0, sum_sq / count - m * m);
}

SiteMap::SiteMap(const RoamanOptions& options) : options_(options) {
  ROVER_DEMAND(options.Validate().ok());
  geometry_ = CenteredOn(Eigen::Vector2d::Zero(), options.cell_size, options.map_cells());
  cells_ = Layer<CellStats>(geometry_.width, geometry_.height);
  blocked_ = Layer<std::uint8_t>(geometry_.width, geometry_.height, 0);
}

Eigen::Vector2d SiteMap::center() const {
  return {geometry_.origin_x + 0.5 * geometry_.width * geometry_.cell,
          geometry_.origin_y + 0.5 * geometry_.height * geometry_.cell};
}

Result<ScanStats> SiteMap::AddScan(const nav_core::RangeScan& scan) {
  const std::string name =
      "RangeScan '" + (scan.camera.empty() ? std::string("?") : scan.camera) + "'";
  const Status shape = scan.Validate();
  if (!shape.ok()) return InvalidArgument(name + ": " + shape.message());

  ScanStats stats;
  stats.pixels = scan.pixel_count();
  const Eigen::Vector2d rover_xy = scan.site_from_rover.translation().head<2>();
  std::vector<Eigen::Vector3d> points;
  points.reserve(stats.pixels / 2);
  const double max_range2 = options_.max_range * options_.max_range;
  for (int v = 0; v < scan.height; ++v) {
    for (int u = 0; u < scan.width; ++u) {
      if (!scan.is_valid(u, v)) continue;
      ++stats.valid;
      const Eigen::Vector3d p = scan.point(u, v);
      if (!p.allFinite()) {
        ++stats.non_finite;
        continue;
      }
      if (p.head<2>().squaredNorm() > max_range2) {
        ++stats.out_of_range;
        continue;
      }
      points.push_back(scan.site_from_rover * p);
    }
  }

  // Where the grid will be for this scan: decided before anything changes, so that a scan
  // with no usable point leaves the map as it was.
  const bool recentre =
      data_cells_ == 0 || (rover_xy - center()).norm() > options_.recenter_distance;
  const GridGeometry target =
      recentre ? CenteredOn(rover_xy, geometry_.cell, geometry_.width) : geometry_;
  std::size_t on_map = 0;
  for (const Eigen::Vector3d& p : points) {
    int i = 0, j = 0;
    target.CellOf(p.x(), p.y(), &i, &j);
    if (target.Contains(i, j)) ++on_map;
  }
  stats.off_map = points.size() - on_map;
  if (on_map == 0) {
    return InvalidArgument(name + " has no usable point: " + std::to_string(stats.valid) + " of " +
                           std::to_string(stats.pixels) + " pixels valid, " +
                           std::to_string(stats.non_finite) + " of them non-finite (NaN/inf), " +
                           std::to_string(stats.out_of_range) + " beyond max_range " +
                           FormatNumber(options_.max_range) + " m, " +
                           std::to_string(stats.off_map) + " off the map");
  }

  if (has_last_scan_ && (rover_xy - last_scan_xy_).norm() > options_.new_panorama_distance) {
    BeginPanorama();
  }
  has_last_scan_ = true;
  last_scan_xy_ = rover_xy;
  if (recentre) {
    Recenter(rover_xy);
    stats.recentred = true;
  }
  for (const Eigen::Vector3d& p : points) AddPoint(p);
  stats.used = on_map;
  stats.panorama = panorama_;
  ++revision_;
  return stats;
}

ScanStats SiteMap::AddPoints(std::span<const Eigen::Vector3d> site_points,
                             const Eigen::Vector2d& rover_xy) {
  ScanStats stats;
  stats.pixels = site_points.size();
  stats.valid = site_points.size();
  const double max_range2 = options_.max_range * options_.max_range;
  for (const Eigen::Vector3d& p : site_points) {
    if (!p.allFinite()) {
      ++stats.non_finite;
      continue;
    }
    if ((p.head<2>() - rover_xy).squaredNorm() > max_range2) {
      ++stats.out_of_range;
      continue;
    }
    int i = 0, j = 0;
    geometry_.CellOf(p.x(), p.y(), &i, &j);
    if (!geometry_.Contains(i, j)) {
      ++stats.off_map;
      continue;
    }
    AddPoint(p);
    ++stats.used;
  }
  stats.panorama = panorama_;
  if (stats.used > 0) ++revision_;
  return stats;
}

void SiteMap::AddPoint(const Eigen::Vector3d& p) {
  int i = 0, j = 0;
  geometry_.CellOf(p.x(), p.y(), &i, &j);
  if (!geometry_.Contains(i, j)) return;
  CellStats& c = cells_.at(i, j);
  if (c.count > 0 && c.panorama < static_cast<std::uint32_t>(panorama_)) {
    c = CellStats{};  // a newer panorama replaces the cell: it is counted again below
    --data_cells_;
  }
  if (c.count == 0) ExtendBounds(i, j);
  const float z = static_cast<float>(p.z());
  c.panorama = static_cast<std::uint32_t>(panorama_);
  ++c.count;
  c.sum += p.z();
  c.sum_sq += p.z() * p.z();
  c.min = std::min(c.min, z);
  c.max = std::max(c.max, z);
}

void SiteMap::Recenter(const Eigen::Vector2d& xy) {
  const GridGeometry target = CenteredOn(xy, geometry_.cell, geometry_.width);
  const int di =
      static_cast<int>(std::lround((target.origin_x - geometry_.origin_x) / geometry_.cell));
  const int dj =
      static_cast<int>(std::lround((target.origin_y - geometry_.origin_y) / geometry_.cell));
  if (di == 0 && dj == 0) return;
  Layer<CellStats> moved(geometry_.width, geometry_.height);
  for (int j = 0; j < geometry_.height; ++j) {
    const int sj = j + dj;
    if (sj < 0 || sj >= geometry_.height) continue;
    for (int i = 0; i < geometry_.width; ++i) {
      const int si = i + di;
      if (si >= 0 && si < geometry_.width) moved.at(i, j) = cells_.at(si, sj);
    }
  }
  cells_ = std::move(moved);
  // Keep the origin an exact multiple of the old one's offset (no drift from re-rounding).
  geometry_.origin_x += di * geometry_.cell;
  geometry_.origin_y += dj * geometry_.cell;
  RecomputeBounds();
  RasterizeBlocked();
  ++revision_;
}

void SiteMap::ExtendBounds(int i, int j) {
  if (data_cells_++ == 0) {
    bound_i0_ = bound_i1_ = i;
    bound_j0_ = bound_j1_ = j;
    return;
  }
  bound_i0_ = std::min(bound_i0_, i);
  bound_i1_ = std::max(bound_i1_, i);
  bound_j0_ = std::min(bound_j0_, j);
  bound_j1_ = std::max(bound_j1_, j);
}

void SiteMap::RecomputeBounds() {
  data_cells_ = 0;
  bound_i0_ = bound_j0_ = 0;
  bound_i1_ = bound_j1_ = -1;
  for (int j = 0; j < geometry_.height; ++j) {
    for (int i = 0; i < geometry_.width; ++i) {
      if (cells_.at(i, j).count > 0) ExtendBounds(i, j);
    }
  }
}

bool SiteMap::DataBounds(int* i0, int* j0, int* i1, int* j1) const {
  if (data_cells_ == 0) return false;
  *i0 = bound_i0_;
  *j0 = bound_j0_;
  *i1 = bound_i1_;
  *j1 = bound_j1_;
  return true;
}

Result<int> SiteMap::MarkBlocked(const Eigen::Vector2d& from, const Eigen::Vector2d& to,
                                 double half_width) {
  if (!Finite(from)) {
    return InvalidArgument("blocked corridor: from = (" + FormatNumber(from.x()) + ", " +
                           FormatNumber(from.y()) + ") (must be finite)");
  }
  if (!Finite(to)) {
    return InvalidArgument("blocked corridor: to = (" + FormatNumber(to.x()) + ", " +
                           FormatNumber(to.y()) + ") (must be finite)");
  }
  ROVER_RETURN_IF_ERROR(CheckRange("blocked corridor: half_width", half_width,
                                   Bounds::OpenLow(0.0, options_.map_size), "m"));
  corridors_.push_back({from, to, half_width});
  RasterizeBlocked();
  ++revision_;
  int n = 0;
  ForEachCorridorCell(corridors_.back(), [&n](int, int) { ++n; });
  return n;
}

template <class F>
void SiteMap::ForEachCorridorCell(const BlockedCorridor& c, F&& f) const {
  const double lo_x = std::min(c.from.x(), c.to.x()) - c.half_width;
  const double hi_x = std::max(c.from.x(), c.to.x()) + c.half_width;
  const double lo_y = std::min(c.from.y(), c.to.y()) - c.half_width;
  const double hi_y = std::max(c.from.y(), c.to.y()) + c.half_width;
  int i0 = 0, j0 = 0, i1 = 0, j1 = 0;
  geometry_.CellOf(lo_x, lo_y, &i0, &j0);
  geometry_.CellOf(hi_x, hi_y, &i1, &j1);
  i0 = std::max(i0, 0);
  j0 = std::max(j0, 0);
  i1 = std::min(i1, geometry_.width - 1);
  j1 = std::min(j1, geometry_.height - 1);
  for (int j = j0; j <= j1; ++j) {
    for (int i = i0; i <= i1; ++i) {
      if (DistanceToSegment(geometry_.Center(i, j), c.from, c.to) <= c.half_width) f(i, j);
    }
  }
}

void SiteMap::RasterizeBlocked() {
  blocked_.Fill(0);
  for (const BlockedCorridor& c : corridors_) {
    ForEachCorridorCell(c, [this](int i, int j) { blocked_.at(i, j) = 1; });
  }
}

void SiteMap::ClearBlocked() {
  corridors_.clear();
  blocked_.Fill(0);
  ++revision_;
}

void SiteMap::Clear() {
  cells_.Fill(CellStats{});
  corridors_.clear();
  blocked_.Fill(0);
  panorama_ = 1;
  has_last_scan_ = false;
  data_cells_ = 0;
  bound_i0_ = bound_j0_ = 0;
  bound_i1_ = bound_j1_ = -1;
  ++revision_;
}

}  // namespace rover::apl::roaman
