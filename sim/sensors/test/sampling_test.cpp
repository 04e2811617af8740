#include "rover/sim/sensors/sampling.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::sim::sensors {
namespace {

TEST(NoiseRng, SameSeedSameSequenceDifferentSeedDifferent) {
  NoiseRng a(42), b(42), c(43);
  bool any_diff = false;
  for (int i = 0; i < 100; ++i) {
    const double x = a.Normal();
    EXPECT_EQ(x, b.Normal());
    any_diff |= (x != c.Normal());
  }
  EXPECT_TRUE(any_diff);
}

TEST(NoiseRng, NormalHasUnitVarianceAndZeroMean) {
  NoiseRng rng(7);
  const int n = 200000;
  double sum = 0.0, sum2 = 0.0;
  for (int i = 0; i < n; ++i) {
    const double x = rng.Normal(2.5);
    sum += x;
    sum2 += x * x;
  }
  const double mean = sum / n;
  const double sd = std::sqrt(sum2 / n - mean * mean);
  EXPECT_NEAR(mean, 0.0, 4.0 * 2.5 / std::sqrt(double{n}));
  EXPECT_NEAR(sd, 2.5, 0.01 * 2.5);
  EXPECT_EQ(rng.Normal(0.0), 0.0);
}

TEST(NoiseRng, UniformStaysInUnitInterval) {
  NoiseRng rng(3);
  for (int i = 0; i < 10000; ++i) {
    const double u = rng.Uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
  }
}

TEST(SensorSeed, StreamsAreDistinctAndDeterministic) {
  EXPECT_EQ(SensorSeed(1, 2), SensorSeed(1, 2));
  EXPECT_NE(SensorSeed(1, 2), SensorSeed(1, 3));
  EXPECT_NE(SensorSeed(1, 2), SensorSeed(2, 2));
}

TEST(SampleClock, ProducesTheConfiguredRate) {
  SampleClock clock(100.0);
  EXPECT_EQ(clock.period().count(), 10'000'000);
  int samples = 0;
  for (int ms = 0; ms < 1000; ++ms) samples += clock.Due(Time{std::int64_t{ms} * 1'000'000});
  EXPECT_EQ(samples, 100);

  SampleClock sun(2.0);
  int sun_samples = 0;
  for (int ms = 0; ms < 10000; ms += 3) sun_samples += sun.Due(Time{std::int64_t{ms} * 1'000'000});
  EXPECT_EQ(sun_samples, 20);
}

TEST(SampleClock, SteppingOverPeriodsSamplesOnceAndKeepsPhase) {
  SampleClock clock(10.0);  // 100 ms
  EXPECT_TRUE(clock.Due(Time{0}));
  EXPECT_FALSE(clock.Due(Time{50'000'000}));
  EXPECT_TRUE(clock.Due(Time{350'000'000}));   // 3 periods missed: one sample
  EXPECT_FALSE(clock.Due(Time{380'000'000}));  // next at 400 ms
  EXPECT_TRUE(clock.Due(Time{400'000'000}));
  clock.Reset();
  EXPECT_TRUE(clock.Due(Time{410'000'000}));
}

}  // namespace
}  // namespace rover::sim::sensors
