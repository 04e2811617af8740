#include "rover/apl/roaman/options.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "rover/base/params.hpp"

namespace rover::apl::roaman {
namespace {

TEST(RoamanOptions, DefaultsAreFidosAndTheSimulatedRovers) {
  const RoamanOptions o;
  EXPECT_TRUE(o.Validate().ok()) << o.Validate().message();
  EXPECT_DOUBLE_EQ(o.cell_size, 0.05);  // FIDO: 5 cm cells
  EXPECT_DOUBLE_EQ(o.plan_width, 6.0);  // FIDO's Figure 3: 6 m x 12 m
  EXPECT_DOUBLE_EQ(o.plan_length, 12.0);
  EXPECT_DOUBLE_EQ(o.max_range, 12.0);
  EXPECT_NEAR(o.max_slope, 45.0 * kDegree, 1e-12);
  // Footprint 1.5 x 1.16 m (wheelbase 1.25 + 2 x 0.125; track 1.0 + 0.16), belly 0.35 m.
  EXPECT_NEAR(o.turn_radius(), 0.5 * std::hypot(1.5, 1.16), 1e-12);
  EXPECT_DOUBLE_EQ(o.leg_clearance(), 0.58);
  EXPECT_DOUBLE_EQ(o.body_clearance, 0.35);
  EXPECT_EQ(o.map_cells(), 600);
  EXPECT_EQ(o.normal_half_cells(), 2);  // 25 cm = 5 cells
  EXPECT_STREQ(AlgorithmName(Algorithm::kAStar), "astar");
}

TEST(RoamanOptions, ValidateNamesTheField) {
  RoamanOptions o;
  o.cell_size = 0.0;
  EXPECT_EQ(o.Validate().message(), "cell_size = 0 m is outside (0, 0.5]");
  o = {};
  o.map_size = 500.0;
  EXPECT_EQ(o.Validate().message(), "map_size = 500 m is outside (0, 200]");
  o = {};
  o.map_size = 150.0;
  EXPECT_EQ(o.Validate().message(),
            "map_size = 150 m at cell_size 0.05 m is 3000 cells across (allowed 16 to 2000)");
  o = {};
  o.plan_width = 1.5;
  EXPECT_EQ(o.Validate().message(),
            "plan_width = 1.5 m leaves no room to turn: it must exceed twice the turn radius "
            "0.948103 m plus a cell on each side");
  o = {};
  o.min_fit_cells = 26;  // a 5 x 5 window has 25 cells
  EXPECT_EQ(o.Validate().message(), "min_fit_cells = 26 is outside [3, 25]");
  o = {};
  o.max_slope = std::nan("");
  EXPECT_EQ(o.Validate().message(), "max_slope is nan (must be finite)");
}

TEST(RoamanOptions, EveryParameterIsBoundOnceWithADoc) {
  const auto bound = BoundParams<RoamanOptions>();
  std::set<std::string> keys;
  for (const auto& p : bound) {
    EXPECT_TRUE(keys.insert(p.key).second) << p.key;
    EXPECT_FALSE(p.doc.empty()) << p.key;
  }
  EXPECT_EQ(bound.size(), 37u);
  EXPECT_TRUE(keys.count("max_slope_deg"));
  EXPECT_TRUE(keys.count("algorithm"));
}

TEST(RoamanOptions, ReadsFromParametersInTheirUnits) {
  ParamSet p("apl-planner");
  DeclareParams<RoamanOptions>(p, "roaman.");
  ASSERT_TRUE(p.LoadYamlString("roaman:\n  max_slope_deg: 30\n  algorithm: astar\n"
                               "  cell_size_m: 0.1\n  normal_window_m: 0.5\n",
                               "planner.yaml")
                  .ok());
  auto o = ReadParams<RoamanOptions>(p, "roaman.");
  ASSERT_TRUE(o.ok()) << o.status().message();
  EXPECT_NEAR(o->max_slope, 30.0 * kDegree, 1e-12);
  EXPECT_EQ(o->algorithm, Algorithm::kAStar);
  EXPECT_DOUBLE_EQ(o->cell_size, 0.1);
}

TEST(RoamanOptions, ValidateErrorsFromParametersNameTheKeyAndLine) {
  ParamSet p("apl-planner");
  DeclareParams<RoamanOptions>(p, "roaman.");
  ASSERT_TRUE(p.LoadYamlString("roaman:\n  plan_width_m: 1.0\n", "planner.yaml").ok());
  auto o = ReadParams<RoamanOptions>(p, "roaman.");
  ASSERT_FALSE(o.ok());
  EXPECT_EQ(o.status().message(),
            "planner.yaml:2: key 'roaman.plan_width_m': plan_width = 1 m leaves no room to turn: "
            "it must exceed twice the turn radius 0.948103 m plus a cell on each side");

  ParamSet q;
  DeclareParams<RoamanOptions>(q, "roaman.");
  ASSERT_TRUE(q.SetFromString("roaman.algorithm=dstar").ok());
  EXPECT_FALSE(ReadParams<RoamanOptions>(q, "roaman.").ok());
}

}  // namespace
}  // namespace rover::apl::roaman
