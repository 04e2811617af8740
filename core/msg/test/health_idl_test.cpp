#include "rover/msg/health_idl.hpp"

#include <gtest/gtest.h>

#include "rover/idl/access.hpp"

namespace rover::msg {
namespace {

TEST(HealthIdl, RoundTripsAndUnknownValuesAreErrors) {
  for (int i = 0; i < 4; ++i) {
    const auto h = static_cast<SensorHealth>(i);
    const rover_SensorHealth w = HealthToIdl(h);
    EXPECT_EQ(static_cast<int>(w), i);
    auto back = HealthFromIdl(w);
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(*back, h);
  }
  EXPECT_EQ(HealthToIdl(SensorHealth::kStale), rover_HEALTH_STALE);
  rover_SensorHealth bad{};
  idl::SetRawEnum(&bad, 9);  // as a corrupt sample could carry
  auto r = HealthFromIdl(bad, "ddl/imu health");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(), "ddl/imu health = 9 is not a SensorHealth (0..3)");
}

}  // namespace
}  // namespace rover::msg
