#include "rover/msg/health.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rover::msg {
namespace {

TEST(Health, OrderingAndNames) {
  EXPECT_EQ(WorseHealth(SensorHealth::kOk, SensorHealth::kDegraded), SensorHealth::kDegraded);
  EXPECT_EQ(WorseHealth(SensorHealth::kStale, SensorHealth::kDegraded), SensorHealth::kStale);
  EXPECT_EQ(WorseHealth(SensorHealth::kStale, SensorHealth::kFailed), SensorHealth::kFailed);
  EXPECT_EQ(WorseHealth(SensorHealth::kOk, SensorHealth::kOk), SensorHealth::kOk);
  EXPECT_EQ(std::string(SensorHealthName(SensorHealth::kStale)), "stale");
  EXPECT_EQ(std::string(SensorHealthName(static_cast<SensorHealth>(9))), "?");
}

TEST(Health, OkAndDegradedAreUsable) {
  EXPECT_TRUE(IsUsable(SensorHealth::kOk));
  EXPECT_TRUE(IsUsable(SensorHealth::kDegraded));
  EXPECT_FALSE(IsUsable(SensorHealth::kFailed));
  EXPECT_FALSE(IsUsable(SensorHealth::kStale));
}

TEST(Health, FreshnessOfAnInput) {
  const Time now = Time::FromSeconds(10.0);
  EXPECT_EQ(FreshnessReport("dl/pose", std::nullopt, now, 1.0, ": waiting"),
            (HealthReport{SensorHealth::kDegraded, "no dl/pose received yet: waiting"}));
  EXPECT_EQ(FreshnessReport("dl/pose", Time::FromSeconds(9.5), now, 1.0), HealthReport{});
  EXPECT_EQ(FreshnessReport("dl/pose", Time::FromSeconds(7.5), now, 1.0, "", ": paused"),
            (HealthReport{SensorHealth::kDegraded, "dl/pose is stale (2.5 s old): paused"}));
}

TEST(HealthLatch, KeepsTheProblemWithItsDetailsUntilCleared) {
  HealthLatch latch;
  EXPECT_FALSE(latch.latched());
  const HealthReport stale{SensorHealth::kDegraded, "dl/pose is stale"};
  EXPECT_EQ(latch.Report(), HealthReport{});
  EXPECT_EQ(latch.Report(stale), stale);
  latch.Latch("ddl/stereo_frame dropped",
              {{"range_request_id", 7}, {"camera", "navcam"}, {"reason", "short image"}},
              {"reason", "range_request_id"});
  ASSERT_TRUE(latch.latched());
  EXPECT_EQ(latch.problem(), "ddl/stereo_frame dropped range_request_id=7 reason=short image");
  // The latched problem wins over what the inputs say.
  EXPECT_EQ(latch.Report(stale), (HealthReport{SensorHealth::kDegraded, latch.problem()}));
  latch.Latch("timed out");
  EXPECT_EQ(latch.problem(), "timed out");
  latch.Clear();
  EXPECT_FALSE(latch.latched());
  EXPECT_EQ(latch.Report(stale), stale);
}

}  // namespace
}  // namespace rover::msg
