#include "rover/sim/terrain/rock_model.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace rover::sim::terrain {
namespace {

// Independent brute-force midpoint integration (linear in D).
template <class F>
double Midpoint(double a, double b, F f, int n = 400000) {
  const double h = (b - a) / n;
  double s = 0;
  for (int i = 0; i < n; ++i) s += f(a + (i + 0.5) * h);
  return s * h;
}

TEST(RockModel, GolombekRappFormulas) {
  EXPECT_NEAR(RockExponent(0.069), 1.79 + 0.152 / 0.069, 1e-12);
  EXPECT_NEAR(RockExponent(0.176), 2.6536, 1e-3);
  EXPECT_DOUBLE_EQ(RockCumulativeArea(0.1, 0.0), 0.1);
  EXPECT_NEAR(RockCumulativeArea(0.1, 0.5), 0.1 * std::exp(-(1.79 + 1.52) * 0.5), 1e-15);
  EXPECT_EQ(RockCumulativeArea(0.0, 0.3), 0.0);
  EXPECT_NEAR(RockAreaFraction(0.2, 0.1, 2.0),
              RockCumulativeArea(0.2, 0.1) - RockCumulativeArea(0.2, 2.0), 1e-15);
}

TEST(RockModel, NumberDensityIntegratesToTheAreaFraction) {
  // integral n(D) a(D) dD over [d0, d1] must equal F(d0) - F(d1).
  for (double k : {0.069, 0.176, 0.4}) {
    const double area = Midpoint(
        0.1, 2.0, [k](double d) { return RockNumberDensity(k, d) * std::numbers::pi * d * d / 4; });
    EXPECT_NEAR(area, RockAreaFraction(k, 0.1, 2.0), 1e-9) << k;
    const double count = Midpoint(0.1, 2.0, [k](double d) { return RockNumberDensity(k, d); });
    EXPECT_NEAR(RockCountPerArea(k, 0.1, 2.0), count, 1e-6 * count) << k;
  }
  // VL-1 with D in [0.1, 2] m: about 1.4 rocks per square metre (regression value, checked
  // against the brute-force integral above).
  EXPECT_NEAR(RockCountPerArea(0.069, 0.1, 2.0), 1.368, 0.001);
}

TEST(RockModel, SamplerFollowsTheAreaWeightedDistribution) {
  const double k = 0.176, d0 = 0.1, d1 = 2.0;
  Rng rng(2024);
  constexpr int kN = 200000;
  std::vector<double> d(kN);
  for (double& x : d) {
    x = SampleRockDiameter(k, d0, d1, &rng);
    ASSERT_GE(x, d0);
    ASSERT_LE(x, d1);
  }
  // Number CDF: P(D >= x) = N(>=x) / N(>=d0). Kolmogorov-Smirnov 99.9 % critical value for
  // 200000 samples is 1.95 / sqrt(N) = 0.0044.
  const double total = RockCountPerArea(k, d0, d1);
  std::sort(d.begin(), d.end());
  double worst = 0;
  for (double x : {0.12, 0.15, 0.2, 0.3, 0.5, 0.8, 1.2}) {
    const double model = RockCountPerArea(k, x, d1) / total;
    const double frac = static_cast<double>(d.end() - std::lower_bound(d.begin(), d.end(), x)) / kN;
    worst = std::max(worst, std::abs(frac - model));
  }
  EXPECT_LT(worst, 0.0044);
}

TEST(RockModel, PoissonVarianceMatchesClosedForm) {
  // integral_{d0}^{inf} D^2 e^{-qD} dD = e^{-q d0} (d0^2/q + 2 d0/q^2 + 2/q^3).
  const double k = 0.069, q = RockExponent(k), d0 = 0.3, area = 100.0;
  const double closed = std::exp(-q * d0) * (d0 * d0 / q + 2 * d0 / (q * q) + 2 / (q * q * q));
  const double expected = k * q * std::numbers::pi / 4 * closed / area;
  EXPECT_NEAR(RockAreaFractionVariance(k, d0, 50.0, area), expected, 1e-6 * expected);
}

}  // namespace
}  // namespace rover::sim::terrain
