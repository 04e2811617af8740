#include "rover/sim/sensors/encoder_model.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rover::sim::sensors {
namespace {

TEST(EncoderModel, CountsPerRadFollowGearAndEncoder) {
  const HardwareConfig config;
  const EncoderModel drive(config.motors[hw::kDriveLF]);
  const EncoderModel steer(config.motors[hw::kSteerLF]);
  EXPECT_NEAR(drive.counts_per_rad(), 64.0 * 1500.0 / (2.0 * M_PI), 1e-9);
  EXPECT_NEAR(steer.counts_per_rad(), 64.0 * 2500.0 / (2.0 * M_PI), 1e-9);
  EXPECT_EQ(drive.Counts(2.0 * M_PI), 96000);  // one wheel turn
  EXPECT_EQ(drive.Counts(-2.0 * M_PI), -96000);
}

TEST(EncoderModel, QuantisationErrorIsAtMostHalfACount) {
  const EncoderModel e(HardwareConfig().motors[hw::kMastPan]);
  for (double a = -3.0; a <= 3.0; a += 0.01237) {
    const double back = static_cast<double>(e.Counts(a)) / e.counts_per_rad();
    EXPECT_LE(std::abs(back - a), 0.5 / e.counts_per_rad() + 1e-15) << a;
  }
}

TEST(EncoderModel, RegisterWrapsButDeltasAccumulateWrapFree) {
  const EncoderModel e(HardwareConfig().motors[hw::kDriveRM]);
  // 2^31 counts is 140,000 rad (~22,000 wheel turns): drive past it in 100 rad steps.
  std::int64_t accumulated = e.RegisterCounts(140000.0);
  std::int32_t last = e.RegisterCounts(140000.0);
  for (double a = 140100.0; a <= 141000.0; a += 100.0) {
    const std::int32_t now = e.RegisterCounts(a);
    accumulated += hw::CounterDelta(now, last);
    last = now;
  }
  EXPECT_LT(static_cast<std::int64_t>(last), 0);  // the register wrapped negative
  EXPECT_EQ(accumulated - e.RegisterCounts(140000.0), e.Counts(141000.0) - e.Counts(140000.0));
}

TEST(EncoderModel, RatesSaturateAndNonFiniteGivesZero) {
  const EncoderModel e(HardwareConfig().motors[hw::kDriveLF]);
  EXPECT_EQ(e.RateCounts(0.5), std::llround(0.5 * e.counts_per_rad()));
  EXPECT_EQ(e.RateCounts(1e12), std::numeric_limits<std::int32_t>::max());
  EXPECT_EQ(e.RateCounts(-1e12), std::numeric_limits<std::int32_t>::min());
  EXPECT_EQ(e.RateCounts(std::nan("")), 0);
  EXPECT_EQ(e.Counts(std::numeric_limits<double>::infinity()), 0);
}

}  // namespace
}  // namespace rover::sim::sensors
