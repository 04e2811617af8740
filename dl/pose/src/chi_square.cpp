#include "rover/dl/pose/chi_square.hpp"

#include <cmath>
#include <limits>

#include "rover/base/check.hpp"

namespace rover::dl::pose {
namespace {

constexpr double kEps = 1e-15;
constexpr int kMaxIterations = 10000;

double SeriesP(double a, double x) {
  double term = 1.0 / a;
  double sum = term;
  for (int n = 1; n < kMaxIterations; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * kEps) break;
  }
  return sum * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Q(a, x) = 1 - P(a, x) by the continued fraction (modified Lentz).
double ContinuedFractionQ(double a, double x) {
  constexpr double kTiny = std::numeric_limits<double>::min() / kEps;
  double b = x + 1.0 - a;
  double c = 1.0 / kTiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < kMaxIterations; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < kEps) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}

}  // namespace

double RegularizedGammaP(double a, double x) {
  ROVER_DEMAND(a > 0.0 && x >= 0.0);
  if (x == 0.0) return 0.0;
  if (x < a + 1.0) return SeriesP(a, x);
  return 1.0 - ContinuedFractionQ(a, x);
}

double ChiSquareCdf(double x, int dof) {
  ROVER_DEMAND(dof >= 1);
  if (!(x > 0.0)) return 0.0;
  if (std::isinf(x)) return 1.0;
  return RegularizedGammaP(0.5 * dof, 0.5 * x);
}

double ChiSquareQuantile(double p, int dof) {
  ROVER_DEMAND(p > 0.0 && p < 1.0 && dof >= 1);
  double lo = 0.0;
  double hi = static_cast<double>(dof) + 10.0;
  while (ChiSquareCdf(hi, dof) < p) {
    lo = hi;
    hi *= 2.0;
  }
  for (int i = 0; i < 200 && hi - lo > 1e-13 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    if (ChiSquareCdf(mid, dof) < p) {
      lo = mid;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

}  // namespace rover::dl::pose
