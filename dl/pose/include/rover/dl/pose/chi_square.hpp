#pragma once
/// @file
/// Chi-square distribution for Mahalanobis gating and consistency tests.
///
///   P(a, x) = gamma(a, x) / Gamma(a)          (regularised lower incomplete gamma)
///   F(x; k) = P(k / 2, x / 2)                 (chi-square CDF with k degrees of freedom)
///   Q(p; k) = x such that F(x; k) = p         (quantile, by bracketing and bisection)
/// P is evaluated by its power series for x < a + 1 and by the continued fraction of the upper
/// function otherwise (modified Lentz), to ~1e-14 relative accuracy.

namespace rover::dl::pose {

/// Preconditions: a > 0, x >= 0 (ROVER_DEMAND).
double RegularizedGammaP(double a, double x);
/// Preconditions: dof >= 1. Returns 0 for x <= 0.
double ChiSquareCdf(double x, int dof);
/// Preconditions: 0 < p < 1, dof >= 1.
double ChiSquareQuantile(double p, int dof);

}  // namespace rover::dl::pose
