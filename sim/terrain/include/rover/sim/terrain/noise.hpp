#pragma once
/// @file
/// Seeded value noise and its fractal sum (fBm), used for hills, soil patches and (later)
/// renderer textures.
///
/// ValueNoise: random values v_ij uniform in [-1, 1] on a square lattice of spacing lambda
/// (the wavelength) whose origin is shifted by a random fraction of a cell; between lattice
/// points the value is interpolated with the C2 quintic fade f(t) = 6t^5 - 15t^4 + 10t^3, so
/// heights built from it have continuous slopes and curvature. |value| <= 1.
///
/// FractalNoise: sum over octaves o = 0..n-1 of p^o * ValueNoise(lambda / 2^o), p = persistence
/// (0.5 gives a fractal surface whose roughness amplitude is proportional to wavelength).
/// |value| <= sum_o p^o.
///
/// Lattices cover a given rectangle (plus margin) and are filled in a fixed order from an Rng,
/// so the same seed gives the same field. Outside the rectangle the lattice index is clamped.

#include <Eigen/Core>
#include <vector>

#include "rover/sim/terrain/random.hpp"

namespace rover::sim::terrain {

class ValueNoise {
 public:
  ValueNoise() = default;
  /// Preconditions: wavelength > 0, max >= min (componentwise).
  ValueNoise(Rng* rng, const Eigen::Vector2d& min, const Eigen::Vector2d& max, double wavelength);

  double operator()(double x, double y) const;
  /// out[j * nx + i] += weight * value(x0 + i * step, y0 + j * step): the same numbers as
  /// operator(), several times faster on a grid (per-column lattice indices precomputed).
  void AddToGrid(double x0, double y0, double step, int nx, int ny, double weight,
                 double* out) const;
  double wavelength() const { return wavelength_; }

 private:
  double Lattice(int i, int j) const;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();
  double wavelength_ = 1.0;
  double inv_wavelength_ = 1.0;
  int nx_ = 0;
  int ny_ = 0;
  std::vector<float> values_;
};

class FractalNoise {
 public:
  FractalNoise() = default;
  /// Preconditions: wavelength > 0, octaves >= 1, persistence > 0.
  FractalNoise(Rng* rng, const Eigen::Vector2d& min, const Eigen::Vector2d& max, double wavelength,
               int octaves, double persistence);

  double operator()(double x, double y) const;
  /// out[j * nx + i] += scale * value(x0 + i * step, y0 + j * step) (see ValueNoise).
  void AddToGrid(double x0, double y0, double step, int nx, int ny, double scale,
                 double* out) const;
  /// Bound on |value|: sum of the octave weights.
  double max_abs() const { return max_abs_; }
  int octaves() const { return static_cast<int>(layers_.size()); }

 private:
  std::vector<ValueNoise> layers_;
  std::vector<double> weights_;
  double max_abs_ = 0.0;
};

/// The quintic fade 6t^5 - 15t^4 + 10t^3 (t in [0, 1]).
inline double QuinticFade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

}  // namespace rover::sim::terrain
