#include "rover/apl/gestalt/options.hpp"

#include <gtest/gtest.h>

#include <string>

#include <set>

#include "rover/base/param_binder.hpp"

namespace rover::apl::gestalt {
namespace {

TEST(GestaltOptions, DefaultsAreMersAndValid) {
  const GestaltOptions o;
  ASSERT_TRUE(o.Validate().ok()) << o.Validate().message();
  // Seed 002 Table 1 and seed 000's flight values.
  EXPECT_DOUBLE_EQ(o.cell_size, 0.2);
  EXPECT_EQ(o.grid_cells(), 50);  // 10 m x 10 m, 50 x 50 cells
  EXPECT_DOUBLE_EQ(o.rover_disc_diameter, 2.6);
  EXPECT_DOUBLE_EQ(o.rover_disc_radius_cells(), 6.5);
  EXPECT_DOUBLE_EQ(o.max_step, 0.20);
  EXPECT_EQ(o.num_forward_arcs, 23);
  EXPECT_EQ(o.num_backward_arcs, 23);
  EXPECT_EQ(o.unknown_goodness, 11);
  EXPECT_EQ(o.border_goodness, 250);
  EXPECT_EQ(o.min_allowed_goodness, 10);
  EXPECT_EQ(o.min_vote_goodness, 26);
  EXPECT_EQ(o.waypoint_certainty, 192);
  EXPECT_EQ(o.num_layers, 7);
  EXPECT_DOUBLE_EQ(o.step_sigma_k, 1.0);
  EXPECT_DOUBLE_EQ(o.arc_vote_variance, 3.2);
  EXPECT_NEAR(o.turn_vote_variance / (kDegree * kDegree), 97.0, 1e-9);
}

TEST(GestaltOptions, ValidateNamesTheField) {
  GestaltOptions o;
  o.step_safe = 0.3;
  EXPECT_EQ(o.Validate().message(), "step_safe = 0.3 m must be below max_step = 0.2 m");
  o = GestaltOptions{};
  o.step_disc_diameter = 3.0;
  EXPECT_EQ(o.Validate().message(), "step_disc_diameter = 3 m is outside (0, 2.6]");
  o = GestaltOptions{};
  o.path_half_width = 0.1;
  EXPECT_EQ(o.Validate().message(),
            "path_half_width = 0.1 m must be at least cell_size / sqrt(2) = 0.141421 m so that "
            "every point of a path lies on a path cell");
  o = GestaltOptions{};
  o.plan_max_dist = 6.0;
  EXPECT_EQ(o.Validate().message(),
            "plan_max_dist = 6 m reaches beyond the map (half of map_size = 5 m)");
  o = GestaltOptions{};
  o.num_layers = 0;
  EXPECT_EQ(o.Validate().message(), "num_layers = 0 is outside [1, 16]");
  o = GestaltOptions{};
  o.max_tilt = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(o.Validate().message(), "max_tilt is nan (must be finite)");
  o = GestaltOptions{};
  o.cost_to_go = true;  // without footprint_check
  EXPECT_NE(o.Validate().message().find("cost_to_go = true needs footprint_check"),
            std::string::npos)
      << o.Validate().message();
  o.footprint_check = true;
  EXPECT_TRUE(o.Validate().ok()) << o.Validate().message();
  o.footprint_max_y = -0.2;
  EXPECT_EQ(o.Validate().message().rfind("footprint_max_y", 0), 0u) << o.Validate().message();
}

TEST(GestaltOptions, EveryParameterIsBoundOnceWithADoc) {
  const auto bound = BoundParams<GestaltOptions>();
  std::set<std::string> keys;
  for (const auto& p : bound) {
    EXPECT_TRUE(keys.insert(p.key).second) << p.key;
    EXPECT_FALSE(p.doc.empty()) << p.key;
  }
  EXPECT_EQ(bound.size(), 59u);
  EXPECT_TRUE(keys.count("max_tilt_deg"));
  EXPECT_TRUE(keys.count("turn_vote_variance_deg2"));
}

TEST(GestaltOptions, ReadsFromParametersInTheirUnits) {
  ParamSet p("apl-mobility");
  DeclareParams<GestaltOptions>(p, "gestalt.");
  ASSERT_TRUE(p.LoadYamlString("gestalt:\n  max_tilt_deg: 25\n  turn_vote_variance_deg2: 100\n"
                               "  num_point_turns: 0\n",
                               "nav.yaml")
                  .ok());
  auto o = ReadParams<GestaltOptions>(p, "gestalt.");
  ASSERT_TRUE(o.ok()) << o.status().message();
  EXPECT_NEAR(o->max_tilt, 25.0 * kDegree, 1e-12);
  EXPECT_NEAR(o->turn_vote_variance, 100.0 * kDegree * kDegree, 1e-12);
  EXPECT_EQ(o->num_point_turns, 0);
}

TEST(GestaltOptions, ValidateErrorsFromParametersNameTheKeyAndLine) {
  ParamSet p("apl-mobility");
  DeclareParams<GestaltOptions>(p, "gestalt.");
  ASSERT_TRUE(
      p.LoadYamlString("gestalt:\n  max_step_m: 0.3\n  step_safe_m: 0.4\n", "nav.yaml").ok());
  auto o = ReadParams<GestaltOptions>(p, "gestalt.");
  ASSERT_FALSE(o.ok());
  EXPECT_EQ(
      o.status().message(),
      "nav.yaml:3: key 'gestalt.step_safe_m': step_safe = 0.4 m must be below max_step = 0.3 m");

  ParamSet q;
  DeclareParams<GestaltOptions>(q, "gestalt.");
  ASSERT_TRUE(q.SetFromString("gestalt.tilt_safe_deg=30").ok());
  auto r = ReadParams<GestaltOptions>(q, "gestalt.");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(),
            "--set gestalt.tilt_safe_deg=30: key 'gestalt.tilt_safe_deg': tilt_safe = 0.523599 rad "
            "must be below max_tilt = 0.349066 rad");

  ParamSet s;
  DeclareParams<GestaltOptions>(s, "gestalt.");
  ASSERT_TRUE(s.SetFromString("gestalt.min_vote_goodness=300").ok());
  EXPECT_EQ(ReadParams<GestaltOptions>(s, "gestalt.").status().message(),
            "--set gestalt.min_vote_goodness=300: key 'gestalt.min_vote_goodness': 300 is out of "
            "range [0, 255]");
}

}  // namespace
}  // namespace rover::apl::gestalt
