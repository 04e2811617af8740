#include "rover/dl/mast/mast_options.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "rover/base/param_binder.hpp"
#include "rover/base/params.hpp"

namespace rover::dl::mast {
namespace {

TEST(MastOptions, DefaultsAreValid) { EXPECT_TRUE(MastOptions{}.Validate().ok()); }

TEST(MastOptions, ValidateNamesTheField) {
  MastOptions o;
  o.pan_max = o.pan_min - 0.1;
  Status s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message().rfind("pan_max", 0), 0u) << s.message();

  o = MastOptions{};
  o.tolerance = 0.0;
  s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message().rfind("tolerance", 0), 0u) << s.message();

  o = MastOptions{};
  o.timeout_s = o.max_timeout_s + 1.0;
  s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message().rfind("timeout_s", 0), 0u) << s.message();

  o = MastOptions{};
  o.status_rate_hz = o.check_rate_hz * 2.0;
  s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message().rfind("status_rate_hz", 0), 0u) << s.message();

  o = MastOptions{};
  o.speed = std::nan("");
  EXPECT_FALSE(o.Validate().ok());
}

TEST(MastOptions, ParametersRoundTripInDegrees) {
  ParamSet p;
  DeclareParams<MastOptions>(p, "mast.");
  ASSERT_TRUE(p.SetFromString("mast.tilt_min_deg=-45").ok());
  ASSERT_TRUE(p.SetFromString("mast.speed=0.3").ok());
  auto o = ReadParams<MastOptions>(p, "mast.");
  ASSERT_TRUE(o.ok()) << o.status().message();
  EXPECT_NEAR(o->tilt_min, -45.0 * kDegree, 1e-12);
  EXPECT_DOUBLE_EQ(o->speed, 0.3);
  EXPECT_NEAR(o->pan_max, 175.0 * kDegree, 1e-12);
}

TEST(MastOptions, InvalidCombinationIsReportedAgainstItsKey) {
  ParamSet p;
  DeclareParams<MastOptions>(p, "mast.");
  ASSERT_TRUE(p.SetFromString("mast.tilt_max_deg=-85").ok());
  auto o = ReadParams<MastOptions>(p, "mast.");
  ASSERT_FALSE(o.ok());
  EXPECT_NE(o.status().message().find("mast.tilt_max_deg"), std::string::npos)
      << o.status().message();
}

}  // namespace
}  // namespace rover::dl::mast
