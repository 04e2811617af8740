#include "rover/apl/gestalt/cost_to_go.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "test_maps.hpp"

namespace rover::apl::gestalt {
namespace {

using nav_core::GoodnessMap;
using testing::KnownMap;  // 10 m, centred on the origin, all known and perfect

void MarkHazard(GoodnessMap* m, double x, double y) {
  int i = 0, j = 0;
  m->CellOf(x, y, &i, &j);
  m->flags[m->Index(i, j)] |= nav_core::kCellHazard;
}

TEST(CostToGo, OpenGroundCostIsTheDistance) {
  const GoodnessMap m = KnownMap();
  const CostToGo ctg(m, {3.0, 0.0}, CostToGoOptions{});
  ASSERT_TRUE(ctg.any_reachable());
  EXPECT_NEAR(ctg.Cost(3.0, 0.0), 0.0, 1e-6);
  // 8-connected: straight runs exact, diagonals within the octile bound of the Euclidean.
  EXPECT_NEAR(ctg.Cost(-1.0, 0.0), 4.0, 0.21);
  const double diag = ctg.Cost(0.0, 3.0);
  EXPECT_GE(diag, std::hypot(3.0, 3.0) - 0.2);
  EXPECT_LE(diag, std::hypot(3.0, 3.0) * 1.09);
}

TEST(CostToGo, HazardBlocksItsClearanceAndTheWayGoesAround) {
  GoodnessMap m = KnownMap();
  // A wall across x = 1 from y = -4 to 1: the way from (0, 0) to (2, 0) goes over its end.
  for (double y = -4.0; y <= 1.0; y += 0.2) MarkHazard(&m, 1.0, y);
  CostToGoOptions o;
  o.clearance = 0.7;
  const CostToGo ctg(m, {2.0, 0.0}, o);
  EXPECT_TRUE(ctg.Blocked(1.0, 0.0));
  EXPECT_TRUE(ctg.Blocked(1.6, 0.0));   // within the clearance
  EXPECT_FALSE(ctg.Blocked(1.0, 2.0));  // past the wall's end
  EXPECT_TRUE(std::isinf(ctg.Cost(1.0, 0.0)));
  // Around the end at y ~ 1.8: at least 2 x hypot(1, 1.8) from (0, 0).
  EXPECT_GT(ctg.Cost(0.0, 0.0), 2.0 * std::hypot(1.0, 1.8) - 0.2);
  EXPECT_LT(ctg.Cost(0.0, 0.0), 2.0 * std::hypot(1.0, 1.8) * 1.25);
}

TEST(CostToGo, StraddleBlocksOnlyTallHazardsAndChargesNearLowOnes) {
  GoodnessMap m = KnownMap();
  // A low wall across the whole map: with straddle it no longer blocks, it costs
  // straddle_cost_factor.
  for (double y = -4.9; y <= 4.9; y += 0.2) MarkHazard(&m, 1.0, y);
  CostToGoOptions o;
  o.clearance = 0.7;
  o.straddle = true;
  o.straddle_cost_factor = 3.0;
  const CostToGo low(m, {2.0, 0.0}, o);
  EXPECT_FALSE(low.Blocked(1.0, 0.0));
  // Straight through: 0.6 m at factor 1 outside the 1.4 m band, the band at 3 (to within a
  // cell at its edges).
  EXPECT_NEAR(low.Cost(0.0, 0.0), 0.6 + 1.4 * 3.0, 0.45);
  o.straddle = false;
  EXPECT_FALSE(CostToGo(m, {2.0, 0.0}, o).any_reachable() &&
               std::isfinite(CostToGo(m, {2.0, 0.0}, o).Cost(0.0, 0.0)));
  o.straddle = true;
  // A tall cell blocks as before.
  int i = 0, j = 0;
  m.CellOf(1.0, 0.0, &i, &j);
  m.flags[m.Index(i, j)] |= nav_core::kCellTall;
  const CostToGo tall(m, {2.0, 0.0}, o);
  EXPECT_TRUE(tall.Blocked(1.0, 0.0));
  EXPECT_TRUE(tall.Blocked(1.6, 0.0));
  EXPECT_FALSE(tall.Blocked(1.0, 1.4));  // near the low cells only
}

TEST(CostToGo, PoorAndUnknownCellsCostMore) {
  GoodnessMap poor = KnownMap(55);  // goodness 55 of 255
  const CostToGo open(KnownMap(), {3.0, 0.0}, CostToGoOptions{});
  const CostToGo rough(poor, {3.0, 0.0}, CostToGoOptions{});
  EXPECT_NEAR(rough.Cost(0.0, 0.0), open.Cost(0.0, 0.0) * (1.0 + 200.0 / 255.0), 1e-3);
  GoodnessMap unknown = KnownMap();
  for (std::size_t k = 0; k < unknown.cell_count(); ++k) {
    unknown.flags[k] = 0;
    unknown.goodness[k] = 255;
  }
  const CostToGo blind(unknown, {3.0, 0.0}, CostToGoOptions{});
  EXPECT_NEAR(blind.Cost(0.0, 0.0), 1.5 * open.Cost(0.0, 0.0), 1e-3);
}

TEST(CostToGo, GoalOffTheMapSeedsTheEdgeByDistance) {
  const GoodnessMap m = KnownMap();
  const CostToGo ctg(m, {30.0, 0.0}, CostToGoOptions{});
  ASSERT_TRUE(ctg.any_reachable());
  // From the origin: 5 m to the edge plus ~25 m beyond it.
  EXPECT_NEAR(ctg.Cost(0.0, 0.0), 30.0, 0.3);
  EXPECT_LT(ctg.Cost(2.0, 0.0), ctg.Cost(0.0, 0.0));
  EXPECT_TRUE(std::isinf(ctg.Cost(20.0, 0.0)));  // off the map
}

TEST(CostToGo, NoWayLeavesEverythingUnreachable) {
  GoodnessMap m = KnownMap();
  // A ring of hazards around the goal.
  for (int a = 0; a < 72; ++a) {
    const double t = a * 5.0 * M_PI / 180.0;
    MarkHazard(&m, 2.0 + 1.5 * std::cos(t), 1.5 * std::sin(t));
  }
  CostToGoOptions o;
  o.clearance = 0.5;
  const CostToGo ctg(m, {2.0, 0.0}, o);
  EXPECT_TRUE(std::isinf(ctg.Cost(-2.0, 0.0)));
  EXPECT_TRUE(std::isfinite(ctg.Cost(2.2, 0.0)));
}

}  // namespace
}  // namespace rover::apl::gestalt
