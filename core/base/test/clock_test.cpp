#include "rover/base/clock.hpp"

#include <gtest/gtest.h>

namespace rover {
namespace {

TEST(Time, Arithmetic) {
  const Time t = Time::FromSeconds(1.5);
  EXPECT_EQ(t.ns, 1'500'000'000);
  EXPECT_EQ((t + Seconds(0.5)).seconds(), 2.0);
  EXPECT_EQ(ToSeconds(Time::FromSeconds(3) - t), 1.5);
  EXPECT_LT(t, Time::FromSeconds(2));
}

TEST(Clock, WallClockIsUnixTime) {
  WallClock c;
  EXPECT_TRUE(c.valid());
  EXPECT_FALSE(c.simulated());
  // After 2020-01-01 and monotone enough between two reads.
  const Time a = c.Now();
  EXPECT_GT(a.ns, 1'577'836'800LL * 1'000'000'000LL);
  EXPECT_GE(c.Now(), a);
}

TEST(Clock, ManualClockStartsInvalidWhenAskedAndFollowsSets) {
  ManualClock c(Time{0}, false);
  EXPECT_FALSE(c.valid());
  EXPECT_TRUE(c.simulated());
  c.Set(Time::FromSeconds(10));
  EXPECT_TRUE(c.valid());
  c.Advance(Seconds(0.25));
  EXPECT_EQ(c.Now(), Time::FromSeconds(10.25));
  c.Set(Time{0});  // a simulator reset moves time back
  EXPECT_EQ(c.Now().ns, 0);
}

TEST(Clock, MonotonicNowAdvances) {
  const Time a = MonotonicNow();
  EXPECT_GE(MonotonicNow(), a);
}

}  // namespace
}  // namespace rover
