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

}  // namespace
}  // namespace rover::msg
