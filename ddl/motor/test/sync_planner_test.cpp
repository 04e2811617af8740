#include "rover/ddl/motor/sync_planner.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::ddl::motor {
namespace {

TEST(SyncPlanner, ProfileDurationTrapezoidAndTriangle) {
  EXPECT_DOUBLE_EQ(ProfileDuration(2.0, 0.5, 2.0), 2.0 / 0.5 + 0.5 / 2.0);
  EXPECT_DOUBLE_EQ(ProfileDuration(0.02, 0.5, 2.0), 2.0 * std::sqrt(0.02 / 2.0));
  EXPECT_DOUBLE_EQ(ProfileDuration(0.0, 0.5, 2.0), 0.0);
}

TEST(SyncPlanner, ProfilePositionIsContinuousAndEndsAtTheDistance) {
  for (double d : {0.02, 0.5, 3.0}) {
    const double v = 0.4, a = 2.0;
    const double total = ProfileDuration(d, v, a);
    EXPECT_NEAR(ProfilePosition(d, v, a, total), d, 1e-12);
    EXPECT_NEAR(ProfilePosition(d, v, a, total + 1.0), d, 1e-12);
    EXPECT_EQ(ProfilePosition(d, v, a, -1.0), 0.0);
    double last = 0.0;
    for (double t = 0.0; t <= total; t += 1e-3) {
      const double p = ProfilePosition(d, v, a, t);
      EXPECT_GE(p, last - 1e-12);
      EXPECT_LE(p - last, v * 1e-3 + 1e-9);  // never faster than the rate limit
      last = p;
    }
  }
  EXPECT_NEAR(RampPosition(0.5, 2.0, 0.25), 0.0625, 1e-12);
  EXPECT_NEAR(RampPosition(0.5, 2.0, 1.25), 0.0625 + 0.5, 1e-12);
}

TEST(SyncPlanner, AllAxesFinishTogether) {
  const std::vector<AxisMove> axes = {
      {1.0, 0.5, 2.0}, {0.3, 0.9, 2.0}, {0.05, 0.4, 2.0}, {0.8, 1.0, 3.0}, {0.0, 0.5, 2.0}};
  const SyncPlan plan = PlanSynchronisedMove(axes);
  // The slowest is axis 0 at its limit.
  EXPECT_NEAR(plan.duration_s, 1.0 / 0.5 + 0.5 / 2.0, 1e-12);
  EXPECT_NEAR(plan.rates[0], 0.5, 1e-12);
  for (std::size_t i = 0; i < axes.size(); ++i) {
    EXPECT_LE(plan.rates[i], axes[i].max_rate + 1e-12);
    if (axes[i].distance > 0.0) {
      EXPECT_NEAR(ProfileDuration(axes[i].distance, plan.rates[i], axes[i].acceleration),
                  plan.duration_s, 1e-9)
          << i;
    }
  }
  EXPECT_EQ(plan.rates[4], 0.0);
}

TEST(SyncPlanner, TriangleLimitedAxisSetsTheDuration) {
  // Short move with low acceleration: triangular at its own limit.
  const std::vector<AxisMove> axes = {{0.01, 1.0, 0.1}, {0.5, 1.0, 5.0}};
  const SyncPlan plan = PlanSynchronisedMove(axes);
  EXPECT_NEAR(plan.duration_s, std::max(2.0 * std::sqrt(0.01 / 0.1), 0.5 + 0.2), 1e-12);
  EXPECT_NEAR(ProfileDuration(0.5, plan.rates[1], 5.0), plan.duration_s, 1e-9);
}

}  // namespace
}  // namespace rover::ddl::motor
