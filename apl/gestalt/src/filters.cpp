#include "rover/apl/gestalt/filters.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "rover/base/check.hpp"

namespace rover::apl::gestalt {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::uint8_t Byte(int v) { return static_cast<std::uint8_t>(std::clamp(v, 0, 255)); }

}  // namespace

int RampGoodness(double value, double safe, double limit) {
  if (!(value > safe)) return 255;  // also NaN-safe for value == safe
  if (value >= limit) return 0;
  return static_cast<int>(std::lround(255.0 * (limit - value) / (limit - safe)));
}

CellStats StatsOf(const Moments& m, int min_points) {
  CellStats s;
  if (m.n < static_cast<double>(min_points) || m.empty()) return s;
  s.covered = true;
  s.x = m.sx / m.n;
  s.y = m.sy / m.n;
  s.z = m.sz / m.n;
  const Eigen::Matrix3d c = m.Covariance();
  s.vxx = c(0, 0);
  s.vyy = c(1, 1);
  s.vzz = c(2, 2);
  s.vxy = c(0, 1);
  s.vxz = c(0, 2);
  s.vyz = c(1, 2);
  s.n = m.n;
  s.noise_var = std::max(0.0, m.NoiseVariance());
  return s;
}

double CellStats::SpreadAbove(double b, double c) const {
  const double v =
      vzz + b * b * vxx + c * c * vyy - 2.0 * b * vxz - 2.0 * c * vyz + 2.0 * b * c * vxy;
  return std::sqrt(std::max(0.0, v - noise_var));
}

DiscAssessor::DiscAssessor(const GestaltOptions& options)
    : options_(options),
      rover_disc_(options.rover_disc_radius_cells()),
      step_disc_(options.step_disc_radius_cells()) {
  const int side = 2 * rover_disc_.radius() + 1;
  const std::size_t n = static_cast<std::size_t>(side) * side;
  top_.assign(n, -kInf);
  bottom_.assign(n, kInf);
  int max_w = 0;
  for (int dy = -step_disc_.radius(); dy <= step_disc_.radius(); ++dy) {
    max_w = std::max(max_w, step_disc_.half_width(dy));
  }
  top_rows_.assign(static_cast<std::size_t>(max_w + 1), std::vector<double>(n, -kInf));
  bottom_rows_.assign(static_cast<std::size_t>(max_w + 1), std::vector<double>(n, kInf));
}

double DiscAssessor::Step(int i, int j, const PlaneFit& plane, const Grid<CellStats>& cells,
                          double* cell_height) const {
  const int R = rover_disc_.radius();
  const int side = 2 * R + 1;
  auto at = [side](int x, int y) { return static_cast<std::size_t>(y) * side + x; };
  // Local elevations of the disc's covered cells relative to the plane.
  const double grad_x = -plane.normal.x() / plane.normal.z();
  const double grad_y = -plane.normal.y() / plane.normal.z();
  std::fill(top_.begin(), top_.end(), -kInf);
  std::fill(bottom_.begin(), bottom_.end(), kInf);
  for (int dy = -R; dy <= R; ++dy) {
    const int jj = j + dy;
    if (jj < 0 || jj >= cells.height()) continue;
    const int w = rover_disc_.half_width(dy);
    for (int dx = -w; dx <= w; ++dx) {
      const int ii = i + dx;
      if (ii < 0 || ii >= cells.width()) continue;
      const CellStats& c = cells.at(ii, jj);
      if (!c.covered) continue;
      const double e = c.z - plane.HeightAt(c.x, c.y);
      // A cell's mean is only known to within its noise: the step counts what lies beyond.
      const double u = options_.step_noise_sigmas * c.MeanNoise();
      bottom_[at(dx + R, dy + R)] = e + u;
      top_[at(dx + R, dy + R)] = e - u + options_.step_sigma_k * c.SpreadAbove(grad_x, grad_y);
    }
  }
  // Sliding max / min along rows, one level per half-width: level w covers [x - w, x + w].
  const std::size_t levels = top_rows_.size();
  top_rows_[0] = top_;
  bottom_rows_[0] = bottom_;
  for (std::size_t w = 1; w < levels; ++w) {
    const std::vector<double>& tp = top_rows_[w - 1];
    const std::vector<double>& bp = bottom_rows_[w - 1];
    std::vector<double>& t = top_rows_[w];
    std::vector<double>& b = bottom_rows_[w];
    for (int y = 0; y < side; ++y) {
      for (int x = 0; x < side; ++x) {
        double tm = w == 1 ? tp[at(x, y)] : -kInf;
        double bm = w == 1 ? bp[at(x, y)] : kInf;
        if (x > 0) {
          tm = std::max(tm, tp[at(x - 1, y)]);
          bm = std::min(bm, bp[at(x - 1, y)]);
        }
        if (x + 1 < side) {
          tm = std::max(tm, tp[at(x + 1, y)]);
          bm = std::min(bm, bp[at(x + 1, y)]);
        }
        t[at(x, y)] = tm;
        b[at(x, y)] = bm;
      }
    }
  }
  // Belly discs centred on every cell of the rover disc.
  const int r = step_disc_.radius();
  double step = 0.0;
  for (int sy = -R; sy <= R; ++sy) {
    const int w = rover_disc_.half_width(sy);
    for (int sx = -w; sx <= w; ++sx) {
      double hi = -kInf, lo = kInf;
      for (int dy = -r; dy <= r; ++dy) {
        const int y = sy + dy + R;
        if (y < 0 || y >= side) continue;
        const std::size_t level = static_cast<std::size_t>(step_disc_.half_width(dy));
        const std::size_t k = at(sx + R, y);
        hi = std::max(hi, top_rows_[level][k]);
        lo = std::min(lo, bottom_rows_[level][k]);
      }
      if (hi > -kInf && lo < kInf) step = std::max(step, hi - lo);
      if (sx == 0 && sy == 0 && cell_height != nullptr) {
        const double top = top_[at(R, R)];
        // Above the belly disc's lowest ground, or above the plane where the belly disc lies
        // wholly on a large rock.
        *cell_height = top > -kInf && lo < kInf ? std::max({0.0, top - lo, top}) : 0.0;
      }
    }
  }
  return step;
}

CellAssessment DiscAssessor::Assess(int i, int j, const Moments& disc_sum, int covered,
                                    const Grid<CellStats>& cells) const {
  CellAssessment a;
  a.coverage = static_cast<float>(static_cast<double>(covered) / rover_disc_.cell_count());
  if (a.coverage < options_.min_coverage) return a;
  const PlaneFit fit = FitPlane(disc_sum, options_.eigen_ratio);
  if (!fit.ok) return a;
  a.tilt = static_cast<float>(fit.tilt);
  // The fit residual less the expected noise (the disc's mean noise variance).
  const double residual = std::sqrt(
      std::max(0.0, fit.residual * fit.residual - std::max(0.0, disc_sum.NoiseVariance())));
  a.roughness = static_cast<float>(residual);
  if (!fit.planar) {
    if (fit.residual < options_.max_roughness) return a;  // orientation undetermined: unknown
    a.status = AssessStatus::kNotPlanar;
    return a;  // all goodness 0
  }
  a.status = AssessStatus::kAssessed;
  const int g_tilt = RampGoodness(fit.tilt, options_.tilt_safe, options_.max_tilt);
  const int g_rough = RampGoodness(residual, options_.roughness_safe, options_.max_roughness);
  // A plane too steep to express as a height field is an obstacle by tilt already.
  double cell_height = 0.0;
  const double step = fit.normal.z() > 1e-3 ? Step(i, j, fit, cells, &cell_height) : kInf;
  a.step = static_cast<float>(std::min(step, 1e3));
  a.cell_height = static_cast<float>(std::min(cell_height, 1e3));
  const int g_step = RampGoodness(step, options_.step_safe, options_.max_step);
  a.tilt_goodness = Byte(g_tilt);
  a.roughness_goodness = Byte(g_rough);
  a.step_goodness = Byte(g_step);
  a.goodness = options_.footprint_check
                   ? Byte(std::min(g_tilt, std::max(options_.min_allowed_goodness,
                                                    std::min(g_rough, g_step))))
                   : Byte(std::min({g_tilt, g_rough, g_step}));
  return a;
}

}  // namespace rover::apl::gestalt
