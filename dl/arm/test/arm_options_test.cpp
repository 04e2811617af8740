#include "rover/dl/arm/arm_options.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rover/base/param_binder.hpp"
#include "rover/base/params.hpp"

namespace rover::dl::arm {
namespace {

TEST(ArmOptions, DefaultsAreValid) {
  const ArmOptions o;
  EXPECT_TRUE(o.Validate().ok());
  EXPECT_DOUBLE_EQ(o.speed, 0.25);
  EXPECT_DOUBLE_EQ(o.descent_speed, 0.01);
  EXPECT_DOUBLE_EQ(o.hover_height, 0.06);
  EXPECT_DOUBLE_EQ(o.overdrive, 0.03);
  EXPECT_DOUBLE_EQ(o.tolerance, 0.01);
}

TEST(ArmOptions, ValidateNamesTheField) {
  const auto expect_field = [](const ArmOptions& o, const std::string& field) {
    const Status s = o.Validate();
    ASSERT_FALSE(s.ok()) << field;
    EXPECT_EQ(s.message().rfind(field, 0), 0u) << s.message();
  };
  ArmOptions o;
  o.speed = 0.0;
  expect_field(o, "speed");
  o = ArmOptions{};
  o.descent_speed = 0.5;
  expect_field(o, "descent_speed");
  o = ArmOptions{};
  o.hover_height = -0.01;
  expect_field(o, "hover_height");
  o = ArmOptions{};
  o.overdrive = std::nan("");
  expect_field(o, "overdrive");
  o = ArmOptions{};
  o.tolerance = 0.0;
  expect_field(o, "tolerance");
  o = ArmOptions{};
  o.timeout_s = o.max_timeout_s + 1.0;
  expect_field(o, "timeout_s");
  o = ArmOptions{};
  o.joint_stale_s = 0.0;
  expect_field(o, "joint_stale_s");
  o = ArmOptions{};
  o.check_rate_hz = 0.0;
  expect_field(o, "check_rate_hz");
  o = ArmOptions{};
  o.status_rate_hz = o.check_rate_hz * 2.0;
  expect_field(o, "status_rate_hz");
}

TEST(ArmOptions, ParametersRoundTrip) {
  ParamSet p;
  DeclareParams<ArmOptions>(p, "arm.");
  ASSERT_TRUE(p.SetFromString("arm.descent_speed=0.005").ok());
  ASSERT_TRUE(p.SetFromString("arm.hover_height=0.1").ok());
  auto o = ReadParams<ArmOptions>(p, "arm.");
  ASSERT_TRUE(o.ok()) << o.status().message();
  EXPECT_DOUBLE_EQ(o->descent_speed, 0.005);
  EXPECT_DOUBLE_EQ(o->hover_height, 0.1);
  EXPECT_DOUBLE_EQ(o->overdrive, 0.03);  // untouched default
  EXPECT_DOUBLE_EQ(o->max_timeout_s, 600.0);
}

TEST(ArmOptions, InvalidCombinationIsReportedAgainstItsKey) {
  ParamSet p;
  DeclareParams<ArmOptions>(p, "arm.");
  ASSERT_TRUE(p.SetFromString("arm.status_rate_hz=20").ok());  // above check_rate_hz = 8
  auto o = ReadParams<ArmOptions>(p, "arm.");
  ASSERT_FALSE(o.ok());
  EXPECT_NE(o.status().message().find("arm.status_rate_hz"), std::string::npos)
      << o.status().message();
}

}  // namespace
}  // namespace rover::dl::arm
