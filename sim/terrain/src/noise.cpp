#include "rover/sim/terrain/noise.hpp"

#include <algorithm>
#include <cmath>

#include "rover/base/check.hpp"

namespace rover::sim::terrain {

ValueNoise::ValueNoise(Rng* rng, const Eigen::Vector2d& min, const Eigen::Vector2d& max,
                       double wavelength)
    : wavelength_(wavelength), inv_wavelength_(1.0 / wavelength) {
  ROVER_DEMAND(rng != nullptr && wavelength > 0.0 && max.x() >= min.x() && max.y() >= min.y());
  // Random sub-cell shift so that octaves (and fields) do not share lattice lines.
  const double sx = rng->Uniform(), sy = rng->Uniform();
  origin_ = min - Eigen::Vector2d(1.0 + sx, 1.0 + sy) * wavelength;
  nx_ = static_cast<int>(std::ceil((max.x() - origin_.x()) * inv_wavelength_)) + 2;
  ny_ = static_cast<int>(std::ceil((max.y() - origin_.y()) * inv_wavelength_)) + 2;
  values_.resize(static_cast<std::size_t>(nx_) * static_cast<std::size_t>(ny_));
  for (float& v : values_) v = static_cast<float>(rng->Uniform(-1.0, 1.0));
}

double ValueNoise::Lattice(int i, int j) const {
  i = std::clamp(i, 0, nx_ - 1);
  j = std::clamp(j, 0, ny_ - 1);
  return values_[static_cast<std::size_t>(j) * static_cast<std::size_t>(nx_) +
                 static_cast<std::size_t>(i)];
}

double ValueNoise::operator()(double x, double y) const {
  const double fx = (x - origin_.x()) * inv_wavelength_;
  const double fy = (y - origin_.y()) * inv_wavelength_;
  const double flx = std::floor(fx), fly = std::floor(fy);
  const int i = static_cast<int>(flx), j = static_cast<int>(fly);
  const double u = QuinticFade(fx - flx), v = QuinticFade(fy - fly);
  const double a = Lattice(i, j), b = Lattice(i + 1, j);
  const double c = Lattice(i, j + 1), d = Lattice(i + 1, j + 1);
  return (a + (b - a) * u) * (1.0 - v) + (c + (d - c) * u) * v;
}

void ValueNoise::AddToGrid(double x0, double y0, double step, int nx, int ny, double weight,
                           double* out) const {
  ROVER_DEMAND(out != nullptr && nx >= 0 && ny >= 0);
  // Per column: lattice indices (clamped as in Lattice()) and fade weight, computed exactly as
  // operator() does so both give identical numbers.
  std::vector<int> i0(static_cast<std::size_t>(nx)), i1(static_cast<std::size_t>(nx));
  std::vector<double> u(static_cast<std::size_t>(nx));
  for (int i = 0; i < nx; ++i) {
    const double fx = (x0 + i * step - origin_.x()) * inv_wavelength_;
    const double flx = std::floor(fx);
    const int li = static_cast<int>(flx);
    i0[static_cast<std::size_t>(i)] = std::clamp(li, 0, nx_ - 1);
    i1[static_cast<std::size_t>(i)] = std::clamp(li + 1, 0, nx_ - 1);
    u[static_cast<std::size_t>(i)] = QuinticFade(fx - flx);
  }
  for (int j = 0; j < ny; ++j) {
    const double fy = (y0 + j * step - origin_.y()) * inv_wavelength_;
    const double fly = std::floor(fy);
    const int lj = static_cast<int>(fly);
    const double v = QuinticFade(fy - fly);
    const float* r0 = &values_[static_cast<std::size_t>(std::clamp(lj, 0, ny_ - 1)) *
                               static_cast<std::size_t>(nx_)];
    const float* r1 = &values_[static_cast<std::size_t>(std::clamp(lj + 1, 0, ny_ - 1)) *
                               static_cast<std::size_t>(nx_)];
    double* o = out + static_cast<std::size_t>(j) * static_cast<std::size_t>(nx);
    for (int i = 0; i < nx; ++i) {
      const std::size_t k = static_cast<std::size_t>(i);
      const double a = r0[i0[k]], b = r0[i1[k]], c = r1[i0[k]], d = r1[i1[k]];
      o[i] += weight * ((a + (b - a) * u[k]) * (1.0 - v) + (c + (d - c) * u[k]) * v);
    }
  }
}

FractalNoise::FractalNoise(Rng* rng, const Eigen::Vector2d& min, const Eigen::Vector2d& max,
                           double wavelength, int octaves, double persistence) {
  ROVER_DEMAND(wavelength > 0.0 && octaves >= 1 && persistence > 0.0);
  double w = 1.0, lambda = wavelength;
  for (int o = 0; o < octaves; ++o) {
    layers_.emplace_back(rng, min, max, lambda);
    weights_.push_back(w);
    max_abs_ += w;
    w *= persistence;
    lambda *= 0.5;
  }
}

double FractalNoise::operator()(double x, double y) const {
  double s = 0.0;
  for (std::size_t o = 0; o < layers_.size(); ++o) s += weights_[o] * layers_[o](x, y);
  return s;
}

}  // namespace rover::sim::terrain

namespace rover::sim::terrain {

void FractalNoise::AddToGrid(double x0, double y0, double step, int nx, int ny, double scale,
                             double* out) const {
  for (std::size_t o = 0; o < layers_.size(); ++o) {
    layers_[o].AddToGrid(x0, y0, step, nx, ny, scale * weights_[o], out);
  }
}

}  // namespace rover::sim::terrain
