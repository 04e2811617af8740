#include "rover/sim/terrain/random.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace rover::sim::terrain {
namespace {

TEST(Rng, EngineIsTheStandardMt19937_64) {
  // The standard fixes mt19937_64's output: with the default seed 5489 the 10000th number is
  // 9981545732273789042 ([rand.predef]). Our Rng must be that engine, untouched.
  Rng rng(5489);
  std::uint64_t x = 0;
  for (int i = 0; i < 10000; ++i) x = rng.Bits();
  EXPECT_EQ(x, 9981545732273789042ull);
}

TEST(Rng, SameSeedSameSequenceDifferentSeedDifferent) {
  Rng a(7), b(7), c(8);
  int differ = 0;
  for (int i = 0; i < 100; ++i) {
    const double va = a.Uniform(), vb = b.Uniform(), vc = c.Uniform();
    EXPECT_EQ(va, vb);
    differ += va != vc;
  }
  EXPECT_GT(differ, 95);
}

TEST(Rng, UniformAndNormalMoments) {
  Rng rng(123);
  constexpr int kN = 200000;
  double su = 0, su2 = 0, sn = 0, sn2 = 0;
  for (int i = 0; i < kN; ++i) {
    const double u = rng.Uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
    su += u;
    su2 += u * u;
    const double n = rng.Normal();
    sn += n;
    sn2 += n * n;
  }
  // Standard errors: uniform mean 0.29/sqrt(N) = 6.5e-4, normal mean 1/sqrt(N) = 2.2e-3,
  // normal variance sqrt(2/N) = 3.2e-3. Tolerances are 5 standard errors.
  EXPECT_NEAR(su / kN, 0.5, 3.3e-3);
  EXPECT_NEAR(su2 / kN - 0.25, 1.0 / 12.0, 2e-3);
  EXPECT_NEAR(sn / kN, 0.0, 0.011);
  EXPECT_NEAR(sn2 / kN, 1.0, 0.016);
}

TEST(Rng, UniformIntCoversRangeEvenly) {
  Rng rng(99);
  std::vector<int> counts(7, 0);
  constexpr int kN = 70000;
  for (int i = 0; i < kN; ++i) ++counts[rng.UniformInt(7)];
  // Each count is Binomial(70000, 1/7): mean 10000, sd 92.6; allow 5 sd.
  for (int c : counts) EXPECT_NEAR(c, 10000, 463);
  EXPECT_EQ(rng.UniformInt(1), 0u);
  EXPECT_GT(rng.UniformPositive(), 0.0);
}

TEST(MixSeed, StreamsDiffer) {
  EXPECT_NE(MixSeed(1, 1), MixSeed(1, 2));
  EXPECT_NE(MixSeed(1, 1), MixSeed(2, 1));
  EXPECT_EQ(MixSeed(5, 3), MixSeed(5, 3));
}

}  // namespace
}  // namespace rover::sim::terrain
