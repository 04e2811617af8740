#include "rover/sim/sensors/pot_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::sim::sensors {
namespace {

TEST(SuspensionPotModel, IdealRoundTripWithinHalfACount) {
  const PotSpec spec;
  SuspensionPotModel model(spec, {}, 0.0, 1);
  for (double a = -0.55; a <= 0.55; a += 0.01) {
    const auto p = model.Sample({a, -a, 0.7 * a, -0.5 * a}, Time{});
    const double expect[4] = {a, -a, 0.7 * a, -0.5 * a};
    for (int i = 0; i < hw::kNumPots; ++i) {
      const auto k = static_cast<std::size_t>(i);
      EXPECT_NEAR(spec.AngleFromCounts(i, p.adc[k]), expect[k],
                  0.5 / std::abs(spec.gain_counts_per_rad[k]) + 1e-12);
    }
  }
}

TEST(SuspensionPotModel, SaturatesAtTheAdcRails) {
  const PotSpec spec;
  SuspensionPotModel model(spec, {}, 3.0, 2);
  const auto high = model.Sample({10.0, 10.0, -10.0, -10.0}, Time{});
  EXPECT_EQ(high.adc[0], hw::kAdcMax);
  EXPECT_EQ(high.adc[1], 0);  // mirrored pot
  EXPECT_EQ(high.adc[2], 0);
  EXPECT_EQ(high.adc[3], hw::kAdcMax);
  const auto nan = model.Sample({std::nan(""), 0.0, 0.0, 0.0}, Time{});
  EXPECT_LE(nan.adc[0], hw::kAdcMax);
}

TEST(SuspensionPotModel, NoiseMatchesTheConfiguredSigma) {
  PotSpec spec;
  spec.noise_counts = 3.0;
  SuspensionPotModel model(spec, {}, 1.0, 1234);
  double sum = 0.0, sum2 = 0.0;
  const int n = 20000;
  const double truth = model.TrueCounts(hw::kLeftBogie, 0.1);
  for (int k = 0; k < n; ++k) {
    const double e = model.Sample({0.0, 0.0, 0.1, 0.0}, Time{}).adc[2] - truth;
    sum += e;
    sum2 += e * e;
  }
  const double mean = sum / n;
  EXPECT_NEAR(std::sqrt(sum2 / n - mean * mean), std::sqrt(9.0 + 1.0 / 12.0), 0.03 * 3.0);
  EXPECT_NEAR(mean, 0.0, 0.1);
}

TEST(SuspensionPotModel, TrueErrorsMakeTheNominalInverseWrong) {
  const PotSpec spec;
  PotErrors errors;
  errors.offset_error_counts[0] = 20.0;
  errors.gain_error[0] = 0.02;
  SuspensionPotModel model(spec, errors, 0.0, 1);
  const auto p = model.Sample({0.3, 0.0, 0.0, 0.0}, Time{});
  const double nominal = spec.AngleFromCounts(0, p.adc[0]);
  EXPECT_NEAR(nominal, 0.3 * 1.02 + 20.0 / 690.0, 1e-3);
}

}  // namespace
}  // namespace rover::sim::sensors
