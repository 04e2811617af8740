#pragma once
/// @file
/// HeightTerrain: the ENav-class planner's terrain model, a nav_core::TerrainAssessor that
/// keeps a remembered site-frame height map (nav_core::HeightMap) instead of GESTALT's 10 m
/// goodness window.
///
/// Map: a square of options.map_size (40 m) in cells of options.cell_size (0.1 m), centred near
/// the rover; it scrolls by whole cells when the rover is more than recentre_distance (8 m) off
/// its centre, forgetting what falls off the far side. So what was seen 5-20 m back is still
/// known when a detour turns the rover round (GESTALT forgets it beyond 5 m).
///
/// Merging a scan: every valid point within max_point_distance (horizontal, from the rover at
/// capture) lands in its cell; per cell the scan gives the mean, lowest and highest height, the
/// point count and the mean range. The scan replaces the stored cell when the cell was unknown
/// or the stored data were not taken more than overwrite_range_slack closer (so a cell seen at
/// 1.5 m is not overwritten by a noisier look from 5 m, while pose drift does not smear old and
/// new data together).
///
/// Derived layers (recomputed on first use after a change):
///   ground(c) = the ground_quantile (0.2; 0 = the minimum) over known cells n within
///               ground_radius (a square window) of
///               z_mean(n) + step_noise_sigmas · sigma(n) / √count(n)  (noise would bias it low);
///               a quantile, not the minimum, because a stereo mismatch ranged too far makes a
///               hole below the ground (dl-stereo's HAZCAM images hold holes 0.1-0.3 m deep at
///               1.5-3 m), and as the minimum it turned the flat ground around it into steps
///   step(c)   = z_mean(c) - ground(c)
///   sigma(c)  = stereo_noise_coeff · range(c)²
///   hazard(c) ∋ class X  when step(c) - step_noise_sigmas · sigma(c) / √count(c) > limit_X
///               (or, with 4 points or more, z_max(c) - ground(c) - step_noise_sigmas · sigma(c)
///               does), with
///               limit_wheel  = wheel_step (rocks a wheel or a bogie link would touch),
///               limit_rocker = the rocker parts' clearance - clearance_margin,
///               limit_body   = the body's clearance (belly) - clearance_margin
///   distance_X(c) = [m] Euclidean distance from c's centre to the nearest class-X cell centre
///               (exact, Felzenszwalb-Huttenlocher), +inf when none
///   goodness (the apl/goodness_map, cells of cost_cell_size): 0 where a body hazard lies within
///               blocked_radius, else 255 · min(1, distance_wheel / hazard_cost_radius); known
///               when any of its height cells is.
/// Contact-part clearances come from options.contact_parts (core/hwconfig's ContactParts()).

#include <Eigen/Geometry>
#include <array>
#include <limits>
#include <vector>

#include "rover/apl/enav/options.hpp"
#include "rover/apl/nav_core/terrain_assessor.hpp"

namespace rover::apl::enav {

/// Index of a hazard class's distance field.
enum class HazardLayer { kWheel = 0, kRocker = 1, kBody = 2 };

class HeightTerrain : public nav_core::TerrainAssessor {
 public:
  /// Errors: InvalidArgument from options.Validate().
  static Result<HeightTerrain> Create(const EnavOptions& options);

  Result<nav_core::AssessmentStats> Update(const nav_core::RangeScan& scan) override;
  void Follow(const Eigen::Isometry3d& site_from_rover) override;
  const nav_core::GoodnessMap& goodness_map() const override;
  const nav_core::HeightMap* height_map() const override;
  void Clear() override;

  /// [m] distance field of a hazard class (height-map layout), valid until the next change.
  const std::vector<float>& distance(HazardLayer layer) const;
  /// [m] distance from site point xy to the nearest cell of `layer` (+inf off the map).
  float DistanceAt(HazardLayer layer, const Eigen::Vector2d& xy) const;
  /// The step limits of the three classes [m] (see the file comment).
  double limit(HazardLayer layer) const { return limits_[static_cast<int>(layer)]; }
  const EnavOptions& options() const { return options_; }

 private:
  explicit HeightTerrain(const EnavOptions& options);
  void Centre(const Eigen::Vector2d& xy);
  void Derive() const;

  // One scan's sums for one cell (Update's scratch).
  struct ScanCell {
    double sum = 0.0, range = 0.0;
    float lo = std::numeric_limits<float>::infinity();
    float hi = -std::numeric_limits<float>::infinity();
    int n = 0;
  };

  EnavOptions options_;
  std::array<double, 3> limits_{};
  std::vector<ScanCell> scratch_;
  mutable nav_core::HeightMap map_;
  mutable nav_core::GoodnessMap goodness_;
  mutable std::array<std::vector<float>, 3> distance_;
  mutable bool dirty_ = true;
};

/// Squared Euclidean distance transform in cells² of a width x height grid (row-major): each
/// cell's squared distance to the nearest cell with `mask` nonzero (+inf when none).
std::vector<float> SquaredDistanceTransform(const std::vector<std::uint8_t>& mask, int width,
                                            int height);

}  // namespace rover::apl::enav
