#include "rover/ddl/joints/rate_estimator.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::ddl::joints {
namespace {

TEST(RateEstimator, RecoversAConstantRateFromQuantisedCounts) {
  const double cpr = 15278.87;
  RateEstimator est(0.2, cpr);
  EXPECT_EQ(est.Rate(), 0.0);
  for (int k = 0; k <= 100; ++k) {
    const double t = k * 0.01;
    est.Add(std::llround(t * 1e9), std::llround(0.37 * t * cpr));
  }
  EXPECT_EQ(est.size(), 21u);  // 0.2 s window at 100 Hz
  // Count rounding bounds the error well below 1e-3 rad/s.
  EXPECT_NEAR(est.Rate(), 0.37, 2e-4);
}

TEST(RateEstimator, FollowsARateChangeWithinOneWindow) {
  const double cpr = 1000.0;
  RateEstimator est(0.2, cpr);
  double pos = 0.0;
  for (int k = 0; k <= 200; ++k) {
    const double rate = k < 100 ? 0.5 : -0.2;
    if (k > 0) pos += rate * 0.01;
    est.Add(k * 10'000'000LL, std::llround(pos * cpr));
    if (k == 99) {
      EXPECT_NEAR(est.Rate(), 0.5, 0.01);
    }
  }
  EXPECT_NEAR(est.Rate(), -0.2, 0.01);
}

TEST(RateEstimator, IgnoresReorderedAndDuplicateSamples) {
  RateEstimator est(1.0, 100.0);
  EXPECT_TRUE(est.Add(10, 0));
  EXPECT_TRUE(est.Add(20, 100));
  EXPECT_FALSE(est.Add(20, 5000));
  EXPECT_FALSE(est.Add(15, 5000));
  EXPECT_EQ(est.size(), 2u);
  EXPECT_NEAR(est.Rate(), 100.0 / 10e-9 / 100.0, 1e-3);
}

}  // namespace
}  // namespace rover::ddl::joints
