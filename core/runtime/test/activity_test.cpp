#include "rover/runtime/activity.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rover::runtime {
namespace {

TEST(ActivityLogTest, SumsWallTimeAndCountsPerName) {
  ActivityLog log;
  log.Add("physics", std::chrono::milliseconds(10));
  log.Add("render", std::chrono::milliseconds(250));
  log.Add("physics", std::chrono::milliseconds(30));
  ASSERT_EQ(log.entries().size(), 2u);
  EXPECT_EQ(log.entries()[0].name, "physics");
  EXPECT_NEAR(log.entries()[0].wall_s, 0.040, 1e-12);
  EXPECT_EQ(log.entries()[0].count, 2u);
  EXPECT_EQ(log.entries()[1].name, "render");
  EXPECT_EQ(log.entries()[1].count, 1u);
}

TEST(ActivityLogTest, NegativeDurationsCountAsZeroAndLongNamesAreCut) {
  ActivityLog log;
  log.Add("a", -std::chrono::milliseconds(5));
  EXPECT_EQ(log.entries()[0].wall_s, 0.0);
  EXPECT_EQ(log.entries()[0].count, 1u);
  const std::string long_name(40, 'x');
  log.Add(long_name, std::chrono::milliseconds(1));
  EXPECT_EQ(log.entries()[1].name.size(), ActivityLog::kMaxNameLength);
  log.Add(long_name, std::chrono::milliseconds(1));  // the same, cut the same way
  EXPECT_EQ(log.entries().size(), 2u);
  EXPECT_EQ(log.entries()[1].count, 2u);
}

TEST(ActivityLogTest, NamesBeyondTheLimitGoToOther) {
  ActivityLog log;
  for (std::size_t i = 0; i < ActivityLog::kMaxActivities + 5; ++i) {
    log.Add("activity" + std::to_string(i), std::chrono::milliseconds(1));
  }
  EXPECT_EQ(log.entries().size(), ActivityLog::kMaxActivities);
  EXPECT_EQ(log.entries().back().name, "other");
  EXPECT_EQ(log.entries().back().count, 6u);
}

TEST(ActivityLogTest, ScopedActivityAddsItsLifetime) {
  ActivityLog log;
  { ScopedActivity a(log, "stereo"); }
  ASSERT_EQ(log.entries().size(), 1u);
  EXPECT_EQ(log.entries()[0].name, "stereo");
  EXPECT_GE(log.entries()[0].wall_s, 0.0);
  EXPECT_EQ(log.entries()[0].count, 1u);
}

TEST(ActivityLogTest, ProcessCpuTimeMoves) {
  const double a = ProcessCpuSeconds();
  volatile double x = 0;
  const double b = ThreadCpuSeconds();
  for (int i = 0; i < 20'000'000; ++i) x = x + 1e-9 * i;
  EXPECT_GT(ProcessCpuSeconds(), a);
  EXPECT_GT(ThreadCpuSeconds(), b);
}

}  // namespace
}  // namespace rover::runtime
