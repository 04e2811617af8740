#pragma once
/// @file
/// GESTALT's traversability filters for one rover-sized disc (seed 000 "Terrain Assessment",
/// seed 002 step 3). The goodness of a cell is how safe the rover would be with its centre on
/// the cell, in any heading; the rover is modelled by its turn-in-place disc (2.6 m).
///
/// Given the summed moments M of the disc's cells (moments.hpp) and the plane fitted to them
/// (centroid m, unit normal n with n_z >= 0, residual r = sqrt(λ0)):
///
///   ramp(v; safe, limit) = 255 if v <= safe, 0 if v >= limit, else 255 (limit - v) / (limit -
///   safe)
///                          (rounded to the nearest integer)
///   tilt       θ = acos(n_z)                       g_tilt  = ramp(θ; tilt_safe, max_tilt)
///   roughness  r = sqrt(λ0)                        g_rough = ramp(r; roughness_safe,
///   max_roughness) step       s = max over belly discs B centred on the disc's cells of
///                  max_{c in B} top_c - min_{c in B} bottom_c,
///              bottom_c = z̄_c - z_plane(x̄_c, ȳ_c),  top_c = bottom_c + k σ_c
///                                                  g_step  = ramp(s; step_safe, max_step)
///   goodness   g = min(g_tilt, g_rough, g_step), certainty 255
///              (footprint_check: g = min(g_tilt, max(min_allowed_goodness, min(g_rough,
///              g_step))): rocks are the footprint check's, tilt still forbids)
///
/// where (x̄_c, ȳ_c, z̄_c) is the mean of cell c's points, z_plane(x, y) = m_z - (n_x (x - m_x) +
/// n_y (y - m_y)) / n_z = m_z + b (x - m_x) + c (y - m_y) the plane's height, σ_c the standard
/// deviation of the cell's heights above the plane, z - b x - c y (from the cell's moments:
/// var_z + b² var_x + c² var_y - 2 b cov_xz - 2 c cov_yz + 2 b c cov_xy; so a uniform slope
/// inside a cell adds no spread), and only cells
/// with at least min_cell_points points enter (B is clipped to the rover disc). Using the mean
/// plus k σ as a cell's top makes a tall thin rock that fills little of its cell still count
/// (seed 000 "Tall Thin Obstacles"); measuring steps inside the belly-sized disc B rather than
/// across the whole rover disc lets the rover climb low "pitcher's mound" hills whose elevation
/// differs across 2.6 m more than a rock would but never under the belly (seed 000 "Pitchers
/// Mounds"). Elevations are taken relative to the rover disc's plane so that a uniform slope is
/// no step.
///
/// A disc is assessed only when at least min_coverage of its cells are covered and the fit has 3
/// points; a fit that is not planar (λ1 < eigen_ratio λ0) is an obstacle when its residual is
/// at or above max_roughness and unknown otherwise (its orientation is undetermined).

#include <cstdint>
#include <vector>

#include "rover/apl/gestalt/disc.hpp"
#include "rover/apl/gestalt/grid.hpp"
#include "rover/apl/gestalt/moments.hpp"
#include "rover/apl/gestalt/options.hpp"

namespace rover::apl::gestalt {

/// The ramp of the file comment. Preconditions: safe < limit.
int RampGoodness(double value, double safe, double limit);

/// What the step filter needs of one cell.
struct CellStats {
  bool covered = false;              ///< at least min_cell_points points
  double x = 0.0, y = 0.0, z = 0.0;  ///< [m] mean of the cell's points
  /// [m²] population covariance of the cell's points
  double vxx = 0.0, vyy = 0.0, vzz = 0.0, vxy = 0.0, vxz = 0.0, vyz = 0.0;
  double n = 0.0;          ///< points
  double noise_var = 0.0;  ///< [m²] mean expected height-noise variance of the points

  /// [m] standard deviation of the heights above a plane of gradient (b, c), of z - b x - c y,
  /// less the expected noise: sqrt(max(0, var(z - b x - c y) - noise_var)).
  double SpreadAbove(double b, double c) const;
  /// [m] standard error of the mean height from noise alone, sqrt(noise_var / n).
  double MeanNoise() const { return n > 0.0 ? std::sqrt(noise_var / n) : 0.0; }
};
/// Stats of a cell's moments (`covered` when n >= min_points).
CellStats StatsOf(const Moments& m, int min_points);

enum class AssessStatus : std::uint8_t {
  kUnknown = 0,  ///< not enough data for a fit
  kAssessed = 1,
  kNotPlanar = 2,  ///< fit failed the eigen-ratio test with a residual at the obstacle level
};

/// The result for one cell, with each filter's measure and goodness (for diagnostics and tests).
struct CellAssessment {
  AssessStatus status = AssessStatus::kUnknown;
  std::uint8_t goodness = 0;
  std::uint8_t tilt_goodness = 0;
  std::uint8_t roughness_goodness = 0;
  std::uint8_t step_goodness = 0;
  float tilt = 0.0f;       ///< [rad]
  float roughness = 0.0f;  ///< [m]
  float step = 0.0f;       ///< [m]
  /// [m] the centre cell's own top above the lowest bottom of the belly disc about it, or
  /// above the disc's plane if that is more (a belly disc wholly on a large rock); both
  /// relative to the plane, noise taken off as for the step: the height of what stands on
  /// this cell. A hazard cell of the footprint check when >= max_step.
  float cell_height = 0.0f;
  float coverage = 0.0f;   ///< share of the disc's cells covered
  bool known() const { return status != AssessStatus::kUnknown; }
};

/// Runs the filters over discs of a grid. Holds scratch space: not thread-safe.
class DiscAssessor {
 public:
  /// Preconditions: options.Validate() is ok.
  explicit DiscAssessor(const GestaltOptions& options);

  const DiscSpans& rover_disc() const { return rover_disc_; }
  const DiscSpans& step_disc() const { return step_disc_; }

  /// Assesses the rover disc about cell (i, j) of `cells`: `disc_sum` is the sum of the disc's
  /// cell moments and `covered` the number of its covered cells.
  CellAssessment Assess(int i, int j, const Moments& disc_sum, int covered,
                        const Grid<CellStats>& cells) const;
  /// [m] the step of the file comment for the disc about (i, j) relative to `plane`; with
  /// `cell_height`, also CellAssessment::cell_height of cell (i, j) (0 when it is not covered).
  /// Preconditions: plane.ok and plane.normal.z() > 0.
  double Step(int i, int j, const PlaneFit& plane, const Grid<CellStats>& cells,
              double* cell_height = nullptr) const;

 private:
  GestaltOptions options_;
  DiscSpans rover_disc_;
  DiscSpans step_disc_;
  // Scratch for Step(): local window of side 2R + 1 about the disc centre, one sliding-max /
  // sliding-min level per belly-disc half-width.
  mutable std::vector<double> top_, bottom_;
  mutable std::vector<std::vector<double>> top_rows_, bottom_rows_;
};

}  // namespace rover::apl::gestalt
