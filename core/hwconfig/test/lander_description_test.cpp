#include "rover/hwconfig/lander_description.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <set>
#include <utility>

namespace rover::hwconfig {
namespace {

using ::testing::HasSubstr;

TEST(LanderDescriptionTest, DefaultsAreValid) { EXPECT_TRUE(LanderDescription{}.Validate().ok()); }

TEST(LanderDescriptionTest, CodesTellRampAndStripeApart) {
  // Unique widths within a ramp; every ordered neighbour pair unique over both ramps.
  std::set<std::pair<int, int>> pairs;
  for (const auto& codes : kRampStripeCodes) {
    EXPECT_EQ(std::set<int>(codes.begin(), codes.end()).size(), codes.size());
    for (std::size_t i = 0; i + 1 < codes.size(); ++i) {
      EXPECT_TRUE(pairs.insert({codes[i], codes[i + 1]}).second) << codes[i] << "," << codes[i + 1];
    }
  }
}

TEST(LanderDescriptionTest, StripesAreCentredGappedAndInsideTheRamp) {
  const LanderDescription d;
  for (int r = 0; r < 2; ++r) {
    const StripeLayout low = d.Stripe(r, 0), high = d.Stripe(r, kStripesPerRamp - 1);
    // The block is centred on the ramp surface: its ends are symmetric about u = 0.
    EXPECT_NEAR(low.u - 0.5 * low.width, -(high.u + 0.5 * high.width), 1e-12);
    EXPECT_NEAR(high.u + 0.5 * high.width - (low.u - 0.5 * low.width), d.StripeBlockLength(),
                1e-12);
    for (int s = 0; s + 1 < kStripesPerRamp; ++s) {
      const StripeLayout a = d.Stripe(r, s), b = d.Stripe(r, s + 1);
      EXPECT_NEAR((b.u - 0.5 * b.width) - (a.u + 0.5 * a.width), d.stripe_gap, 1e-12);
      EXPECT_DOUBLE_EQ(a.width, a.code * d.stripe_unit);
      EXPECT_NEAR(a.length, d.ramp_width - 2 * kStripeMargin, 1e-12);
    }
  }
  EXPECT_NEAR(d.Apothem(), 1.5 * 0.8660254037844386, 1e-12);
}

TEST(LanderDescriptionTest, RejectsBadFieldsNamingThem) {
  LanderDescription d;
  d.deck_height = -1;
  EXPECT_THAT(d.Validate().message(), HasSubstr("lander.deck_height = -1 m is outside"));
  d = {};
  d.ramp_width = 2.0;
  EXPECT_THAT(d.Validate("target.").message(), HasSubstr("target.ramp_width = 2 m"));
  d = {};
  d.stripe_unit = 0.3;
  EXPECT_THAT(d.Validate().message(), HasSubstr("lander.stripe_unit: the six stripes need"));
  d = {};
  d.stripe_gap = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(d.Validate().message(), HasSubstr("lander.stripe_gap is nan"));
}

}  // namespace
}  // namespace rover::hwconfig
