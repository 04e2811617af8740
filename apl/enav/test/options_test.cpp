#include "rover/apl/enav/options.hpp"

#include <gtest/gtest.h>

#include "rover/base/param_binder.hpp"

namespace rover::apl::enav {
namespace {

TEST(EnavOptions, DefaultsAreValid) {
  EXPECT_TRUE(EnavOptions{}.Validate().ok());
  EXPECT_EQ(EnavOptions{}.map_cells(), 400);
}

TEST(EnavOptions, BadValuesNameTheField) {
  EnavOptions o;
  o.cost_cell_size = 0.15;  // not a multiple of 0.1
  Status s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("cost_cell_size"), std::string::npos) << s.message();
  o = EnavOptions{};
  o.recentre_distance = 15.0;  // 15 + 6 + 1 > 20
  s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("recentre_distance"), std::string::npos) << s.message();
  o = EnavOptions{};
  o.route_margin = -0.01;
  s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("route_margin"), std::string::npos) << s.message();
  o = EnavOptions{};
  o.route_backward_factor = 0.5;  // backing cheaper than driving forward
  s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("route_backward_factor"), std::string::npos) << s.message();
  o = EnavOptions{};
  o.sample_spacing = 2.0;  // longer than the first segment
  s = o.Validate();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("sample_spacing"), std::string::npos) << s.message();
}

TEST(EnavOptions, ReadsKeysAndTheRoverDescription) {
  ParamSet params("test");
  DeclareParams<EnavOptions>(params, "enav.");
  DeclareParams<hwconfig::RoverDescription>(params, "geometry.");
  ASSERT_TRUE(params.SetFromString("enav.planar_margin_m=0.12", "test").ok());
  ASSERT_TRUE(params.SetFromString("geometry.min_turn_radius=2.0", "test").ok());
  ASSERT_TRUE(params.Validate().ok());
  auto o = ReadEnavOptionsForRover(params);
  ASSERT_TRUE(o.ok()) << o.status().message();
  EXPECT_DOUBLE_EQ(o->planar_margin, 0.12);
  EXPECT_DOUBLE_EQ(o->rover.MaxCurvature(), 0.5);
  EXPECT_EQ(o->contact_parts.size(), 11u);
  // Out of range: the binder names the key.
  ParamSet bad("test");
  DeclareParams<EnavOptions>(bad, "enav.");
  const Status s = bad.SetFromString("enav.max_tilt_deg=95", "cli");
  const Status v = s.ok() ? bad.Validate() : s;
  ASSERT_FALSE(v.ok());
  EXPECT_NE(v.message().find("enav.max_tilt_deg"), std::string::npos) << v.message();
}

}  // namespace
}  // namespace rover::apl::enav
