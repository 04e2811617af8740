// Plan requests checked against the map: typed failures that name what is wrong.
#include "rover/apl/roaman/problem.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "scenes.hpp"

namespace rover::apl::roaman {
namespace {

using testing::ClassMap;
using testing::Paint;

nav_core::PlanRequest Request(Eigen::Vector2d goal, double tolerance = 0.0, bool partial = false) {
  nav_core::PlanRequest r;
  r.goal = goal;
  r.goal_tolerance = tolerance;
  r.allow_partial = partial;
  return r;
}

bool Contains(const Status& s, const std::string& text) {
  return s.message().find(text) != std::string::npos;
}

TEST(Problem, ValidateRequestNamesTheField) {
  nav_core::PlanRequest r = Request({5.0, 0.0});
  EXPECT_TRUE(ValidateRequest(r).ok());
  r.goal.x() = std::nan("");
  EXPECT_EQ(ValidateRequest(r).message(), "PlanRequest.goal.x is nan (must be finite)");
  r = Request({5.0, 0.0});
  r.start.y() = INFINITY;
  EXPECT_EQ(ValidateRequest(r).message(), "PlanRequest.start.y is inf (must be finite)");
  r = Request({5.0, 0.0}, -1.0);
  EXPECT_EQ(ValidateRequest(r).message(), "PlanRequest.goal_tolerance = -1 m is outside [0, 1000]");
}

TEST(Problem, GoalsOnTheGridGetAnAnchor) {
  const TraversabilityMap t = ClassMap(-5, -5, 15, 15, 0.05, CellClass::kSafe);
  PlanFailure f = PlanFailure::kNone;
  auto p = PreparePlan(t, Request({6.0, 1.0}), RoamanOptions{}, &f);
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_EQ(f, PlanFailure::kNone);
  EXPECT_TRUE(p->goal_on_grid);
  EXPECT_EQ(p->goal_anchor, Eigen::Vector2d(6.0, 1.0));
  EXPECT_EQ(p->start_anchor, Eigen::Vector2d(0.0, 0.0));
  EXPECT_NEAR(p->turn_clearance, RoamanOptions{}.turn_radius(), 1e-12);
}

TEST(Problem, AGoalOffTheMapIsAnErrorUnlessPartialPlansAreAllowed) {
  const TraversabilityMap t = ClassMap(-5, -5, 15, 15, 0.05, CellClass::kSafe);
  PlanFailure f = PlanFailure::kNone;
  auto p = PreparePlan(t, Request({25.0, 0.0}), RoamanOptions{}, &f);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(f, PlanFailure::kGoalOffMap);
  EXPECT_EQ(p.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(p.status().message(),
            "goal (25, 0) is off the map: 25 m from the rover, beyond the 12 m planning grid "
            "less its 1.5 m goal margin (plan_length_m, goal_margin_m); allow a partial plan to "
            "plan toward it");
  p = PreparePlan(t, Request({25.0, 0.0}, 0.0, true), RoamanOptions{}, &f);
  ASSERT_TRUE(p.ok());
  EXPECT_FALSE(p->goal_on_grid);
  EXPECT_NEAR(p->grid.along0 + p->grid.height * p->grid.cell, 12.0, 1e-9);
}

TEST(Problem, AGoalWithoutDataIsAnErrorUnlessPartial) {
  TraversabilityMap t = ClassMap(-5, -5, 15, 15, 0.05, CellClass::kSafe);
  Paint(&t, {6.0, -3.0}, {6.0, 3.0}, 1.0, CellClass::kMissing);  // a shadow band
  PlanFailure f = PlanFailure::kNone;
  auto p = PreparePlan(t, Request({6.0, 0.0}), RoamanOptions{}, &f);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(f, PlanFailure::kGoalMissing);
  EXPECT_TRUE(Contains(p.status(), "goal (6, 0) is on terrain the map has no data for"));
  p = PreparePlan(t, Request({6.0, 0.0}, 0.0, true), RoamanOptions{}, &f);
  ASSERT_TRUE(p.ok());
  EXPECT_FALSE(p->goal_on_grid);
}

TEST(Problem, AGoalInOrNearAHazard) {
  TraversabilityMap t = ClassMap(-5, -5, 15, 15, 0.05, CellClass::kSafe);
  Paint(&t, {6.0, 0.0}, {6.0, 0.0}, 0.3, CellClass::kStep);
  PlanFailure f = PlanFailure::kNone;
  auto p = PreparePlan(t, Request({6.0, 0.0}), RoamanOptions{}, &f);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(f, PlanFailure::kGoalInHazard);
  EXPECT_EQ(p.status().message(),
            "goal (6, 0) is inside a hazard (step cell) and no cell within goal_tolerance 0 m is "
            "safe to stand on");
  // 0.8 m from the rock's centre: a safe cell, but the rover (turn radius 0.95 m) cannot stand
  // and turn there.
  p = PreparePlan(t, Request({6.0, 0.8}), RoamanOptions{}, &f);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(f, PlanFailure::kGoalInHazard);
  EXPECT_TRUE(Contains(p.status(), "goal (6, 0.8) is inside a hazard's reach: clearance 0."));
  EXPECT_TRUE(Contains(p.status(), "nearest: step at ("));
  EXPECT_TRUE(Contains(p.status(), "the rover needs 0.948 m to stand and turn there"));
  // With a tolerance the anchor moves to the nearest cell it can turn on.
  p = PreparePlan(t, Request({6.0, 0.8}, 1.0), RoamanOptions{}, &f);
  ASSERT_TRUE(p.ok()) << p.status().message();
  EXPECT_TRUE(p->goal_on_grid);
  EXPECT_LE((p->goal_anchor - Eigen::Vector2d(6.0, 0.8)).norm(), 1.0);
  EXPECT_GE(p->grid.ClearanceAt(p->goal_anchor), p->turn_clearance);
}

TEST(Problem, TheStartAnchorAndNoSafeCellNearTheRover) {
  // Rocks 1.4 m to the left and right: the rover's own cell has 1.4 m - 0.3 m of clearance.
  TraversabilityMap t = ClassMap(-5, -5, 15, 15, 0.05, CellClass::kSafe);
  Paint(&t, {0.0, 0.8}, {0.0, 0.8}, 0.3, CellClass::kStep);  // 0.5 m from the rover's centre
  PlanFailure f = PlanFailure::kNone;
  auto p = PreparePlan(t, Request({6.0, 0.0}), RoamanOptions{}, &f);
  ASSERT_TRUE(p.ok()) << p.status().message();
  // The rover cannot turn where it stands (0.45 m clearance): routes begin at the nearest cell
  // that allows it, reached by a straight leg.
  EXPECT_GT((p->start_anchor - Eigen::Vector2d::Zero()).norm(), 0.1);
  EXPECT_GE(p->grid.ClearanceAt(p->start_anchor), p->turn_clearance);
  EXPECT_LE(p->start_anchor.norm(), RoamanOptions{}.start_search_radius);

  // Boxed in by a ring of rock 0.7 m away: nowhere within 2 m to turn.
  TraversabilityMap ring = ClassMap(-5, -5, 15, 15, 0.05, CellClass::kSafe);
  for (int k = 0; k < 64; ++k) {
    const double a = 2.0 * M_PI * k / 64;
    Paint(&ring, {0.7 * std::cos(a), 0.7 * std::sin(a)}, {0.7 * std::cos(a), 0.7 * std::sin(a)},
          0.08, CellClass::kStep);
  }
  p = PreparePlan(ring, Request({6.0, 0.0}), RoamanOptions{}, &f);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(f, PlanFailure::kNoSafeStart);
  EXPECT_TRUE(Contains(p.status(),
                       "no safe cell near the rover at (0, 0): no cell within "
                       "start_search_radius 2 m has the 0.948 m clearance"));
  EXPECT_TRUE(Contains(p.status(), "(nearest hazard: step at ("));

  // Standing on a blocked cell.
  TraversabilityMap blocked = ClassMap(-5, -5, 15, 15, 0.05, CellClass::kSafe);
  Paint(&blocked, {-1.0, 0.0}, {1.0, 0.0}, 0.2, CellClass::kBlocked);
  p = PreparePlan(blocked, Request({6.0, 0.0}), RoamanOptions{}, &f);
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(f, PlanFailure::kNoSafeStart);
  EXPECT_TRUE(Contains(p.status(), "the rover stands on a blocked cell"));
  EXPECT_STREQ(PlanFailureName(PlanFailure::kNoSafeStart), "no_safe_start");
}

}  // namespace
}  // namespace rover::apl::roaman
