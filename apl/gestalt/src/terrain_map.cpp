#include "rover/apl/gestalt/terrain_map.hpp"

#include <algorithm>
#include <cmath>

#include "rover/apl/gestalt/fov_edge.hpp"

namespace rover::apl::gestalt {
namespace {

using nav_core::AssessmentStats;
using nav_core::RangeScan;

}  // namespace

Result<TerrainMap> TerrainMap::Create(const GestaltOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate());
  return TerrainMap(options);
}

TerrainMap::TerrainMap(const GestaltOptions& options)
    : options_(options),
      assessor_(options),
      edge_margin_disc_(options.fov_edge_margin_cells),
      cells_(options.grid_cells()) {
  Clear();
}

void TerrainMap::Clear() {
  anchored_ = false;
  i0_ = j0_ = 0;
  moment_origin_.setZero();
  moments_ = Grid<Moments>(cells_, cells_);
  assessments_ = Grid<CellAssessment>(cells_, cells_);
  layers_ = LayeredGoodness(cells_, cells_, options_.num_layers);
  edge_merged_ = Grid<std::uint8_t>(cells_, cells_, 0);
  scan_moments_ = Grid<Moments>(cells_, cells_);
  scan_edge_ = Grid<std::uint8_t>(cells_, cells_, 0);
  touched_ = Grid<std::uint8_t>(cells_, cells_, 0);
  touched_list_.clear();
  dirty_ = Grid<std::uint8_t>(cells_, cells_, 0);
  conservative_ = Grid<std::uint8_t>(cells_, cells_, 0);
  cell_stats_ = Grid<CellStats>(cells_, cells_);
  covered_ = Grid<int>(cells_, cells_, 0);
  fresh_ = Grid<std::int16_t>(cells_, cells_, LayeredGoodness::kAbsent);
  map_ = nav_core::GoodnessMap{};
  map_.resolution = options_.cell_size;
  map_.width = map_.height = cells_;
  map_.goodness.assign(map_.cell_count(), static_cast<std::uint8_t>(options_.unknown_goodness));
  map_.certainty.assign(map_.cell_count(), static_cast<std::uint8_t>(options_.unknown_certainty));
  map_.flags.assign(map_.cell_count(), 0);
  map_.unknown_goodness = options_.unknown_goodness;
  map_.unknown_certainty = options_.unknown_certainty;
}

bool TerrainMap::Recentre(const Eigen::Vector2d& rover_xy) {
  const double r = options_.cell_size;
  const int i0 = static_cast<int>(std::floor(rover_xy.x() / r)) - cells_ / 2;
  const int j0 = static_cast<int>(std::floor(rover_xy.y() / r)) - cells_ / 2;
  if (!anchored_) {
    anchored_ = true;
    i0_ = i0;
    j0_ = j0;
    map_.origin_x = i0_ * r;
    map_.origin_y = j0_ * r;
    return true;
  }
  const int di = i0 - i0_, dj = j0 - j0_;
  if (di == 0 && dj == 0) return false;
  moments_.Shift(di, dj, Moments{});
  assessments_.Shift(di, dj, CellAssessment{});
  layers_.Shift(di, dj);
  edge_merged_.Shift(di, dj, 0);
  scan_edge_.Fill(0);
  i0_ = i0;
  j0_ = j0;
  map_.origin_x = i0_ * r;
  map_.origin_y = j0_ * r;
  return true;
}

bool TerrainMap::ForgetFar(const Eigen::Vector2d& rover_xy) {
  Grid<std::uint8_t> far(cells_, cells_, 0);
  bool any = false;
  const double r2 = options_.forget_radius * options_.forget_radius;
  for (int j = 0; j < cells_; ++j) {
    for (int i = 0; i < cells_; ++i) {
      const Eigen::Vector2d c = map_.CellCenter(i, j);
      if ((c - rover_xy).squaredNorm() <= r2) continue;
      const std::size_t k = moments_.Index(i, j);
      if (moments_[k].empty() && layers_.layer(0)[k] == LayeredGoodness::kAbsent &&
          !assessments_[k].known()) {
        continue;
      }
      far[k] = 1;
      moments_[k] = Moments{};
      assessments_[k] = CellAssessment{};
      edge_merged_[k] = 0;
      any = true;
    }
  }
  if (any) layers_.Forget(far);
  return any;
}

bool TerrainMap::Move(const Eigen::Isometry3d& site_from_rover) {
  const Eigen::Vector2d xy = site_from_rover.translation().head<2>();
  if (!xy.allFinite()) return false;
  if (!anchored_) moment_origin_ = site_from_rover.translation();
  const bool moved = Recentre(xy);
  const bool forgot = ForgetFar(xy);
  return moved || forgot;
}

void TerrainMap::Follow(const Eigen::Isometry3d& site_from_rover) {
  if (Move(site_from_rover)) Publish();
}

Result<AssessmentStats> TerrainMap::Update(const RangeScan& scan) {
  if (Status s = scan.Validate(); !s.ok()) {
    return Status(s.code(),
                  s.message() + (scan.camera.empty() ? "" : " (camera " + scan.camera + ")"));
  }
  const Eigen::Isometry3d& pose = scan.site_from_rover;
  const Eigen::Vector2d rover_xy = pose.translation().head<2>();
  (void)Move(pose);  // published below with the new data

  AssessmentStats stats;
  scan_edge_.Fill(0);
  const std::size_t npx = scan.pixel_count();
  used_px_.assign(npx, 0);
  cell_of_px_.assign(npx, -1);
  point_of_px_.resize(npx);
  noise_of_px_.resize(npx);
  const double r = options_.cell_size;
  const double max_d2 = options_.max_point_distance * options_.max_point_distance;
  const Eigen::Matrix3d rot = pose.linear();
  const Eigen::Vector3d t = pose.translation();
  for (std::size_t k = 0; k < npx; ++k) {
    if (scan.valid[k] == 0) continue;
    ++stats.points_total;
    const Eigen::Vector3d p_r(scan.xyz[3 * k], scan.xyz[3 * k + 1], scan.xyz[3 * k + 2]);
    if (!p_r.allFinite()) continue;
    const Eigen::Vector3d p = rot * p_r + t;
    const double d2 = (p.head<2>() - rover_xy).squaredNorm();
    if (d2 > max_d2) continue;
    const int i = static_cast<int>(std::floor(p.x() / r)) - i0_;
    const int j = static_cast<int>(std::floor(p.y() / r)) - j0_;
    if (!moments_.Contains(i, j)) continue;
    used_px_[k] = 1;
    cell_of_px_[k] = static_cast<std::int32_t>(moments_.Index(i, j));
    point_of_px_[k] = p - moment_origin_;
    // Height noise sigma = coeff d² (the options' stereo noise model): variance coeff² d⁴.
    noise_of_px_[k] = options_.stereo_noise_coeff * options_.stereo_noise_coeff * d2 * d2;
    ++stats.points_used;
  }
  FindFovEdgePixels(scan.width, scan.height, used_px_, options_.fov_edge_band_px, &edge_px_);

  // The scan's moments per cell.
  touched_list_.clear();
  for (std::size_t k = 0; k < npx; ++k) {
    if (used_px_[k] == 0) continue;
    const std::size_t c = static_cast<std::size_t>(cell_of_px_[k]);
    if (touched_[c] == 0) {
      touched_[c] = 1;
      touched_list_.push_back(c);
    }
    scan_moments_[c].Add(point_of_px_[k], noise_of_px_[k]);
    if (edge_px_[k] != 0) scan_edge_[c] = 1;
  }
  stats.cells_touched = static_cast<int>(touched_list_.size());

  // New data overrides old, except that a partly seen cell adds to what it had.
  for (std::size_t c : touched_list_) {
    if (scan_edge_[c] != 0) {
      ++stats.cells_fov_edge;
      if (!moments_[c].empty()) {
        moments_[c] += scan_moments_[c];
        continue;
      }
    }
    moments_[c] = scan_moments_[c];
  }

  // Cells whose rover disc holds a touched cell are re-assessed.
  Grid<std::uint8_t>& dirty = dirty_;
  DilateMask(touched_, assessor_.rover_disc(), &dirty);
  const Grid<Moments>& source = options_.fit_from_scan_only ? scan_moments_ : moments_;
  Grid<CellStats>& cell_stats = cell_stats_;
  Grid<int>& covered = covered_;
  for (std::size_t k = 0; k < source.size(); ++k) {
    cell_stats[k] = StatsOf(source[k], options_.min_cell_points);
    covered[k] = cell_stats[k].covered ? 1 : 0;
  }
  RowPrefix<Moments>& moment_sums = moment_sums_;
  moment_sums.Build(source);
  RowPrefix<int>& covered_sums = covered_sums_;
  covered_sums.Build(covered);
  Grid<std::int16_t>& fresh = fresh_;
  fresh.Fill(LayeredGoodness::kAbsent);
  for (int j = 0; j < cells_; ++j) {
    for (int i = 0; i < cells_; ++i) {
      if (dirty.at(i, j) == 0) continue;
      const Moments sum = moment_sums.DiscSum(i, j, assessor_.rover_disc());
      const int n_covered = covered_sums.DiscSum(i, j, assessor_.rover_disc());
      const CellAssessment a = assessor_.Assess(i, j, sum, n_covered, cell_stats);
      assessments_.at(i, j) = a;
      ++stats.cells_assessed;
      if (!a.known()) {
        ++stats.cells_unknown;
        continue;
      }
      if (a.goodness == 0) ++stats.cells_obstacle;
      fresh.at(i, j) = a.goodness;
    }
  }

  // Conservative merge around the edge of the field of view.
  Grid<std::uint8_t>& conservative = conservative_;
  DilateMask(scan_edge_, edge_margin_disc_, &conservative);
  layers_.Merge(fresh, conservative);
  for (std::size_t k = 0; k < fresh.size(); ++k) {
    if (fresh[k] != LayeredGoodness::kAbsent) edge_merged_[k] = conservative[k];
  }

  // Reset the scratch for the next scan (only what was touched).
  for (std::size_t c : touched_list_) {
    scan_moments_[c] = Moments{};
    touched_[c] = 0;
  }
  // scan_edge_ is kept until the next update for diagnostics (fov_edge_cells()).
  map_.stamp = scan.capture_time;
  Publish();
  return stats;
}

void TerrainMap::Publish() {
  const Grid<std::int16_t>& g = layers_.combined();
  auto known = [&](int i, int j) {
    return g.Contains(i, j) && g.at(i, j) != LayeredGoodness::kAbsent;
  };
  for (int j = 0; j < cells_; ++j) {
    for (int i = 0; i < cells_; ++i) {
      const std::size_t k = g.Index(i, j);
      if (!known(i, j)) {
        map_.goodness[k] = static_cast<std::uint8_t>(options_.unknown_goodness);
        map_.certainty[k] = static_cast<std::uint8_t>(options_.unknown_certainty);
        map_.flags[k] = 0;
        continue;
      }
      bool border = false;
      for (int dj = -1; dj <= 1 && !border; ++dj) {
        for (int di = -1; di <= 1; ++di) {
          if ((di != 0 || dj != 0) && !known(i + di, j + dj)) {
            border = true;
            break;
          }
        }
      }
      int value = g[k];
      int certainty = 255;
      std::uint8_t flags = nav_core::kCellKnown;
      if (border) {
        value = std::min(value, options_.border_goodness);
        certainty = options_.border_certainty;
        flags |= nav_core::kCellBorder;
      }
      if (edge_merged_[k] != 0) flags |= nav_core::kCellFovEdge;
      if (options_.footprint_check && assessments_[k].known() &&
          assessments_[k].cell_height >= options_.footprint_hazard_height) {
        flags |= nav_core::kCellHazard;
        if (assessments_[k].cell_height >= options_.footprint_tall_height) {
          flags |= nav_core::kCellTall;
        }
      }
      map_.goodness[k] = static_cast<std::uint8_t>(value);
      map_.certainty[k] = static_cast<std::uint8_t>(certainty);
      map_.flags[k] = flags;
    }
  }
  ++map_.revision;
}

}  // namespace rover::apl::gestalt
