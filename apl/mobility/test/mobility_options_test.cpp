#include "rover/apl/mobility/mobility_options.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

namespace rover::apl::mobility {
namespace {

TEST(MobilityOptions, DefaultsAreValid) { EXPECT_TRUE(MobilityOptions{}.Validate().ok()); }

TEST(MobilityOptions, ValidateNamesTheField) {
  MobilityOptions o;
  o.step_length = 0.0;
  Status s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("step_length"), std::string::npos) << s.message();
  o = MobilityOptions{};
  o.guard_min_goodness = 300;
  s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("guard_min_goodness"), std::string::npos);
  o = MobilityOptions{};
  o.pose_stale_s = std::nan("");
  EXPECT_FALSE(o.Validate().ok());
}

TEST(MobilityOptions, EveryParameterBoundOnceAndReadBack) {
  const auto bound = BoundParams<MobilityOptions>();
  std::set<std::string> keys;
  for (const auto& p : bound) EXPECT_TRUE(keys.insert(p.key).second) << p.key;
  EXPECT_GE(keys.size(), 30u);
  ParamSet params;
  DeclareParams<MobilityOptions>(params, "mobility.");
  auto read = ReadParams<MobilityOptions>(params, "mobility.");
  ASSERT_TRUE(read.ok()) << read.status().message();
  EXPECT_DOUBLE_EQ(read->step_length, 0.5);
  EXPECT_NEAR(read->max_tilt, 0.5236, 1e-4);
  EXPECT_TRUE(read->drive_while_thinking);
}

TEST(MobilityOptions, AnInvalidParameterNamesItsKey) {
  ParamSet params;
  DeclareParams<MobilityOptions>(params, "mobility.");
  ASSERT_TRUE(params.SetFromString("mobility.step_length_m=0").ok());
  auto read = ReadParams<MobilityOptions>(params, "mobility.");
  ASSERT_FALSE(read.ok());
  EXPECT_NE(read.status().message().find("mobility.step_length_m"), std::string::npos)
      << read.status().message();
}

}  // namespace
}  // namespace rover::apl::mobility
