#include "rover/apl/mobility/navigation.hpp"

#include <gtest/gtest.h>

namespace rover::apl::mobility {
namespace {

ParamSet Params(const std::string& planner) {
  ParamSet p("apl-mobility");
  DeclareNavigationParams(p);
  EXPECT_TRUE(p.SetFromString("nav.planner=" + planner).ok());
  return p;
}

// A flat 2 x 2 m patch of ground points from 1 to 3 m ahead of a rover at the origin.
nav_core::RangeScan FlatPatch() {
  nav_core::RangeScan s;
  s.width = 40;
  s.height = 40;
  s.camera = "test";
  for (int v = 0; v < s.height; ++v) {
    for (int u = 0; u < s.width; ++u) {
      s.xyz.insert(s.xyz.end(), {1.0F + 0.05F * v, -1.0F + 0.05F * u, 0.0F});
      s.valid.push_back(1);
    }
  }
  return s;
}

TEST(MakeMobilityManager, BuildsTheChosenPlanner) {
  for (const std::string planner : {"gestalt", "enav"}) {
    auto m = MakeMobilityManager(Params(planner));
    ASSERT_TRUE(m.ok()) << planner << ": " << m.status().message();
    EXPECT_EQ(m->selector().ChecksDriveLength(), planner == "enav") << planner;
    EXPECT_EQ(m->selector().ChecksTurns(), planner == "enav") << planner;
  }
}

TEST(MakeMobilityManager, MergesPriorScansIntoTheMapBeforeHandingItOver) {
  for (const std::string planner : {"gestalt", "enav"}) {
    auto blank = MakeMobilityManager(Params(planner));
    auto m = MakeMobilityManager(Params(planner), {FlatPatch()});
    ASSERT_TRUE(blank.ok() && m.ok()) << planner << ": " << m.status().message();
    EXPECT_GT(m->assessor().goodness_map().revision, blank->assessor().goodness_map().revision)
        << planner;
  }
  auto m = MakeMobilityManager(Params("enav"), {FlatPatch()});
  ASSERT_TRUE(m.ok());
  const nav_core::HeightMap* h = m->assessor().height_map();
  ASSERT_NE(h, nullptr);
  int i = 0, j = 0;
  h->CellOf(2.0, 0.0, &i, &j);
  ASSERT_TRUE(h->Contains(i, j));
  EXPECT_GT(h->count[h->Index(i, j)], 0) << "the patch's ground is known";
  h->CellOf(-2.0, 0.0, &i, &j);
  EXPECT_EQ(h->count[h->Index(i, j)], 0) << "ground behind the rover was never seen";
}

TEST(MakeMobilityManager, ABadPriorScanIsRefusedByItsIndex) {
  nav_core::RangeScan bad = FlatPatch();
  bad.valid.pop_back();  // one flag short of the pixels
  auto m = MakeMobilityManager(Params("enav"), {FlatPatch(), bad});
  ASSERT_FALSE(m.ok());
  EXPECT_NE(m.status().message().find("prior scan 1"), std::string::npos)
      << m.status().message();
}

}  // namespace
}  // namespace rover::apl::mobility
