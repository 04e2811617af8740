#include "rover/sim/terrain/rock_model.hpp"

#include <cmath>
#include <numbers>

#include "rover/base/check.hpp"

namespace rover::sim::terrain {
namespace {

// Composite Simpson over ln D (the integrands vary over decades of D). 2000 panels give
// relative errors far below 1e-8 for the smooth integrands used here.
template <class F>
double IntegrateLog(double d0, double d1, F f) {
  if (!(d1 > d0) || d0 <= 0.0) return 0.0;
  constexpr int kPanels = 2000;
  const double l0 = std::log(d0), h = (std::log(d1) - l0) / kPanels;
  double s = 0.0;
  for (int i = 0; i <= kPanels; ++i) {
    const double d = std::exp(l0 + i * h);
    const double w = (i == 0 || i == kPanels) ? 1.0 : (i % 2 == 1 ? 4.0 : 2.0);
    s += w * f(d) * d;  // dD = D d(ln D)
  }
  return s * h / 3.0;
}

}  // namespace

double RockExponent(double k) {
  ROVER_DEMAND(k > 0.0);
  return 1.79 + 0.152 / k;
}

double RockCumulativeArea(double k, double d) {
  if (k <= 0.0) return 0.0;
  return k * std::exp(-RockExponent(k) * d);
}

double RockAreaFraction(double k, double d0, double d1) {
  return RockCumulativeArea(k, d0) - RockCumulativeArea(k, d1);
}

double RockNumberDensity(double k, double d) {
  if (k <= 0.0 || d <= 0.0) return 0.0;
  const double q = RockExponent(k);
  return 4.0 * k * q * std::exp(-q * d) / (std::numbers::pi * d * d);
}

double RockCountPerArea(double k, double d0, double d1) {
  if (k <= 0.0) return 0.0;
  return IntegrateLog(d0, d1, [k](double d) { return RockNumberDensity(k, d); });
}

double RockAreaFractionVariance(double k, double d0, double d1, double area) {
  ROVER_DEMAND(area > 0.0);
  if (k <= 0.0) return 0.0;
  const double q = RockExponent(k);
  // n(D) a(D)^2 = k q exp(-qD) * pi D^2 / 4.
  const double integral = IntegrateLog(
      d0, d1, [k, q](double d) { return k * q * std::exp(-q * d) * std::numbers::pi * d * d / 4; });
  return integral / area;
}

double SampleRockDiameter(double k, double d_min, double d_max, Rng* rng) {
  ROVER_DEMAND(k > 0.0 && d_min > 0.0 && d_max > d_min && rng != nullptr);
  const double q = RockExponent(k);
  const double inv_min = 1.0 / d_min, inv_max = 1.0 / d_max;
  while (true) {
    // Envelope density proportional to 1/D^2 on [d_min, d_max]: 1/D is uniform.
    const double d = 1.0 / (inv_min - rng->Uniform() * (inv_min - inv_max));
    if (rng->Uniform() < std::exp(-q * (d - d_min))) return d;
  }
}

}  // namespace rover::sim::terrain
