#include "rover/hwconfig/hw_bus.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <string>

namespace rover::hw {
namespace {

TEST(HwBus, NamesFollowTheIdlOrder) {
  EXPECT_EQ(std::string(MotorName(kDriveLF)), "drive_lf");
  EXPECT_EQ(std::string(MotorName(kSteerRR)), "steer_rr");
  EXPECT_EQ(std::string(MotorName(kMastTilt)), "mast_tilt");
  EXPECT_EQ(std::string(MotorName(kArmAzimuth)), "arm_azimuth");
  EXPECT_EQ(std::string(MotorName(kArmWrist)), "arm_wrist");
  EXPECT_EQ(std::string(MotorName(16)), "?");
  EXPECT_EQ(std::string(MotorName(-1)), "?");
  EXPECT_EQ(std::string(PotName(kRightBogie)), "right_bogie");
  EXPECT_EQ(std::string(MotorModeName(MotorMode::kBrake)), "brake");
}

TEST(HwBus, CounterWrapsLikeA32BitRegister) {
  EXPECT_EQ(WrapCounter(0), 0);
  EXPECT_EQ(WrapCounter(-5), -5);
  EXPECT_EQ(WrapCounter(std::int64_t{1} << 31), std::numeric_limits<std::int32_t>::min());
  EXPECT_EQ(WrapCounter((std::int64_t{1} << 32) + 7), 7);
  EXPECT_EQ(WrapCounter(-(std::int64_t{1} << 32) - 3), -3);
}

TEST(HwBus, CounterDeltaUnwrapsAcrossTheInt32Boundary) {
  // Accumulating deltas of the wrapped counter recovers the unbounded count exactly.
  std::int64_t truth = std::numeric_limits<std::int32_t>::max() - 1000;
  std::int32_t last = WrapCounter(truth);
  std::int64_t accumulated = truth;
  for (int k = 0; k < 100; ++k) {
    truth += (k % 3 == 0) ? 997 : -13;  // crosses +2^31 going up
    const std::int32_t now = WrapCounter(truth);
    accumulated += CounterDelta(now, last);
    last = now;
  }
  EXPECT_EQ(accumulated, truth);
  EXPECT_GT(truth, std::int64_t{std::numeric_limits<std::int32_t>::max()});
  EXPECT_EQ(CounterDelta(std::numeric_limits<std::int32_t>::min(),
                         std::numeric_limits<std::int32_t>::max()),
            1);
  EXPECT_EQ(CounterDelta(-10, 10), -20);
}

}  // namespace
}  // namespace rover::hw
