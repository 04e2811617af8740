#include "rover/apl/roaman/planning_grid.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "scenes.hpp"

namespace rover::apl::roaman {
namespace {

using testing::ClassMap;
using testing::Paint;

TEST(GoalFrame, AlongTowardTheGoalAcrossToItsLeft) {
  const GoalFrame f = GoalFrame::Toward({1.0, 1.0}, {1.0, 5.0});  // goal due west
  EXPECT_NEAR(f.u.y(), 1.0, 1e-12);
  EXPECT_NEAR(f.w.x(), -1.0, 1e-12);  // left of west is south
  const Eigen::Vector2d p = f.ToSite(2.0, 0.5);
  EXPECT_NEAR(p.x(), 0.5, 1e-12);
  EXPECT_NEAR(p.y(), 3.0, 1e-12);
  EXPECT_NEAR((f.ToFrame(p) - Eigen::Vector2d(2.0, 0.5)).norm(), 0.0, 1e-12);
}

TEST(PlanningGrid, RowsRunAcrossTheGoalDirection) {
  const TraversabilityMap t = ClassMap(-5, -5, 15, 15, 0.05, CellClass::kSafe);
  RoamanOptions o;
  const PlanningGrid g = BuildPlanningGrid(t, {0.0, 0.0}, {6.0, 8.0}, 11.5, o);
  EXPECT_EQ(g.width, 120);   // 6 m across
  EXPECT_EQ(g.height, 260);  // from -1.5 m to 11.5 m along
  EXPECT_NEAR(g.across0, -3.0, 1e-12);
  EXPECT_NEAR(g.along0, -1.5, 1e-12);
  // Moving along a row (i) moves across the goal direction; along a column (j) toward it.
  const Eigen::Vector2d u(0.6, 0.8);
  EXPECT_NEAR((g.Center(61, 100) - g.Center(60, 100)).dot(u), 0.0, 1e-12);
  EXPECT_NEAR((g.Center(60, 101) - g.Center(60, 100)).dot(u), 0.05, 1e-12);
  int i = 0, j = 0;
  ASSERT_TRUE(g.CellOf(g.Center(17, 203), &i, &j));
  EXPECT_EQ(i, 17);
  EXPECT_EQ(j, 203);
  EXPECT_FALSE(g.CellOf({-20.0, 0.0}, &i, &j));
}

TEST(PlanningGrid, ResamplingNeverLosesAHazardCell) {
  // Single hazard cells scattered on the site map; a grid rotated by 37°.
  TraversabilityMap t = ClassMap(-5, -5, 15, 15, 0.05, CellClass::kSafe);
  std::vector<Eigen::Vector2d> hazards;
  for (int k = 0; k < 40; ++k) {
    const Eigen::Vector2d p(1.0 + 0.21 * k, -1.0 + 0.137 * k);
    int i = 0, j = 0;
    t.geometry.CellOf(p.x(), p.y(), &i, &j);
    t.cls.at(i, j) = CellClass::kStep;
    hazards.push_back(t.geometry.Center(i, j));
  }
  RoamanOptions o;
  o.plan_width = 8.0;
  const PlanningGrid g = BuildPlanningGrid(
      t, {0.0, 0.0}, {8.0 * std::cos(37.0 * kDegree), 8.0 * std::sin(37.0 * kDegree)}, 12.0, o);
  for (const Eigen::Vector2d& h : hazards) {
    // The planning cell containing the hazard cell's centre is a hazard.
    EXPECT_EQ(g.ClassAt(h), CellClass::kStep) << h.transpose();
  }
}

TEST(PlanningGrid, TheGroundUnderTheRoverCountsAsSafe) {
  TraversabilityMap t = ClassMap(-5, -5, 15, 15, 0.05, CellClass::kMissing);
  Paint(&t, {0.5, 0.5}, {0.5, 0.5}, 0.1, CellClass::kStep);
  RoamanOptions o;
  const PlanningGrid g = BuildPlanningGrid(t, {0.0, 0.0}, {8.0, 0.0}, 9.5, o);
  EXPECT_EQ(g.ClassAt({0.0, 0.0}), CellClass::kSafe);
  EXPECT_EQ(g.ClassAt({-0.9, 1.3}), CellClass::kSafe);  // within start_clear_radius 2 m
  EXPECT_EQ(g.ClassAt({2.2, 0.0}), CellClass::kMissing);
  EXPECT_EQ(g.ClassAt({0.5, 0.5}), CellClass::kStep);  // real hazards stay
}

TEST(PlanningGrid, ClearanceIsTheDistanceToHazardsAndTheEdge) {
  TraversabilityMap t = ClassMap(-5, -5, 15, 15, 0.05, CellClass::kSafe);
  RoamanOptions o;
  o.plan_width = 4.0;
  const PlanningGrid open = BuildPlanningGrid(t, {0.0, 0.0}, {5.0, 0.0}, 6.5, o);
  // Column 40 of 80 has its centre 0.025 m left of the centre line: 1.975 m from the edge.
  EXPECT_NEAR(open.clearance.at(40, 100), 2.0 - 0.025, 1e-6);
  EXPECT_NEAR(open.ClearanceAt({-1.5 + 0.025, 0.0}), 0.025, 1e-6);  // the back row
  Paint(&t, {3.0, -0.05}, {3.0, 0.05}, 0.03, CellClass::kStep);
  const PlanningGrid g = BuildPlanningGrid(t, {0.0, 0.0}, {5.0, 0.0}, 6.5, o);
  // The step's cells are 2.975 to 3.025 m ahead; resampling may add the planning cell just in
  // front (its bilinear support touches them), so from (2.025, 0.025) the clearance is 0.925 m
  // or 0.875 m.
  const Eigen::Vector2d p(2.0, 0.025);
  EXPECT_NEAR(g.ClearanceAt(p), 0.9, 0.026);
  EXPECT_TRUE(g.SegmentClear({0.0, 0.5}, {5.0, 0.5}, 0.4));
  EXPECT_FALSE(g.SegmentClear({0.0, 0.5}, {5.0, 0.5}, 0.6));
  EXPECT_NEAR(g.MinClearanceAlong({0.0, 0.5}, {5.0, 0.5}), 0.475, 0.03);
  EXPECT_EQ(g.ClearanceAt({-10.0, 0.0}), 0.0);
}

}  // namespace
}  // namespace rover::apl::roaman
