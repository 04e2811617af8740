#include "rover/ddl/driver_support/driver_health.hpp"

#include <gtest/gtest.h>

namespace rover::ddl::driver_support {
namespace {

Time T(double s) { return Time::FromSeconds(s); }

TEST(InputMonitor, StaleUntilFirstSampleAndAfterTheTimeout) {
  InputMonitor m("hw/imu", 0.1, 1.0);
  EXPECT_TRUE(m.Stale(T(5)));
  EXPECT_EQ(m.StaleReason(T(5)), "hw/imu: no sample yet");
  ASSERT_TRUE(m.Accept(T(5).ns, T(5)).ok());
  EXPECT_FALSE(m.Stale(T(5.1)));
  EXPECT_EQ(m.StaleReason(T(5.1)), "");
  EXPECT_TRUE(m.Stale(T(5.11)));
  EXPECT_EQ(m.StaleReason(T(5.11)), "hw/imu: no sample for more than 0.1 s");
  EXPECT_EQ(m.StaleReason(T(9)), m.StaleReason(T(5.11)));  // stable text
  m.Reset();
  EXPECT_EQ(m.StaleReason(T(5.05)), "hw/imu: no sample yet");
}

TEST(InputMonitor, JudgesArrivalNotTheStamp) {
  InputMonitor m("hw/imu", 0.1, 1.0);
  // An old stamp that arrives now keeps the stream fresh: freshness is about arrival.
  ASSERT_TRUE(m.Accept(T(1).ns, T(10)).ok());
  EXPECT_FALSE(m.Stale(T(10.05)));
}

TEST(InputMonitor, RejectsFutureAndNegativeStampsWithoutRecordingThem) {
  InputMonitor m("hw/sun_sensor", 1.0, 0.5);
  const Status s = m.Accept(T(12).ns, T(10));
  EXPECT_EQ(s.code(), StatusCode::kOutOfRange);
  EXPECT_NE(s.message().find("hw/sun_sensor"), std::string::npos) << s.message();
  EXPECT_EQ(m.Accept(-5, T(10)).code(), StatusCode::kOutOfRange);
  EXPECT_TRUE(m.Stale(T(10)));
  EXPECT_EQ(m.rejected(), 2u);
  ASSERT_TRUE(m.Accept(T(10.4).ns, T(10)).ok());  // within max_future_s
  // While the run clock is not valid (sim/clock not heard yet) the future check is off.
  ASSERT_TRUE(m.Accept(T(100).ns, Time{0}, /*clock_valid=*/false).ok());
  EXPECT_EQ(m.accepted(), 2u);
}

TEST(ClockJumpDetector, SeesOnlyBackwardSteps) {
  ClockJumpDetector d;
  EXPECT_FALSE(d.WentBack(T(1)));
  EXPECT_FALSE(d.WentBack(T(1)));
  EXPECT_FALSE(d.WentBack(T(2)));
  EXPECT_FALSE(d.WentBack(Time{0}, /*clock_valid=*/false));
  EXPECT_TRUE(d.WentBack(T(0.5)));
  EXPECT_FALSE(d.WentBack(T(0.6)));
}

TEST(HealthSummary, KeepsTheWorstAndItsFirstReason) {
  HealthSummary h;
  h.Worsen(msg::SensorHealth::kOk, "fine");
  EXPECT_EQ(h.health, msg::SensorHealth::kOk);
  EXPECT_EQ(h.reason, "");
  h.Worsen(msg::SensorHealth::kDegraded, "a");
  h.Worsen(msg::SensorHealth::kDegraded, "b");
  EXPECT_EQ(h.reason, "a");
  h.Worsen(msg::SensorHealth::kFailed, "c");
  h.Worsen(msg::SensorHealth::kStale, "d");
  EXPECT_EQ(h.health, msg::SensorHealth::kFailed);
  EXPECT_EQ(h.reason, "c");
}

TEST(IsLogWorthy, PowersOfTen) {
  int n = 0;
  for (std::uint64_t i = 0; i <= 100000; ++i) n += IsLogWorthy(i) ? 1 : 0;
  EXPECT_EQ(n, 6);  // 1, 10, 100, 1000, 10000, 100000
  EXPECT_TRUE(IsLogWorthy(1000));
  EXPECT_FALSE(IsLogWorthy(0));
  EXPECT_FALSE(IsLogWorthy(20));
}

}  // namespace
}  // namespace rover::ddl::driver_support
