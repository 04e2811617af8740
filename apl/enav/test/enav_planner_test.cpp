#include "rover/apl/enav/enav_planner.hpp"

#include <gtest/gtest.h>

#include <numbers>
#include <optional>

#include "scene.hpp"

namespace rover::apl::enav {
namespace {

using testing::Block;
using testing::Blocks;
using testing::ScanOf;
using testing::TerrainOf;
using testing::TestOptions;

nav_core::ArcRequest Toward(double x, double y) {
  nav_core::ArcRequest r;
  r.goal = {x, y};
  r.goal_tolerance = 0.3;
  return r;
}


TEST(EnavPlanner, NeedsHeightsAndCheckedRequests) {
  auto p = EnavPlanner::Create(TestOptions());
  ASSERT_TRUE(p.ok());
  nav_core::GoodnessMap map;
  auto e = p->Evaluate(map, Toward(3, 0));
  ASSERT_FALSE(e.ok());
  EXPECT_EQ(e.status().code(), StatusCode::kFailedPrecondition);
  const HeightTerrain t = TerrainOf(Blocks({}));
  auto nan = p->Plan(t, Toward(std::nan(""), 0));
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.status().message().find("ArcRequest.goal"), std::string::npos);
  nav_core::ArcRequest neg = Toward(3, 0);
  neg.goal_tolerance = -1.0;
  EXPECT_FALSE(p->Plan(t, neg).ok());
}

TEST(EnavPlanner, OpenGroundDrivesStraightAtTheGoal) {
  auto p = EnavPlanner::Create(TestOptions());
  ASSERT_TRUE(p.ok());
  const HeightTerrain t = TerrainOf(Blocks({}));
  auto e = p->Plan(t, Toward(4, 0));
  ASSERT_TRUE(e.ok()) << e.status().message();
  ASSERT_TRUE(e->has_choice());
  EXPECT_EQ(e->choice().kind, nav_core::MotionKind::kArc);
  EXPECT_DOUBLE_EQ(e->choice().curvature, 0.0);
  EXPECT_EQ(e->choice().direction, 1);
  EXPECT_EQ(e->candidates_ranked, 24 * 9 * 9);
  EXPECT_EQ(e->clearance_checks, 1);
  EXPECT_GE(e->path.size(), 1u);
  // Goal behind: a turn in place first (part of the way: arcs finish turning while driving).
  auto back = p->Plan(t, Toward(-4, 0));
  ASSERT_TRUE(back.ok());
  ASSERT_TRUE(back->has_choice());
  EXPECT_EQ(back->choice().kind, nav_core::MotionKind::kPointTurn);
  EXPECT_GE(std::abs(back->choice().turn_angle), std::numbers::pi / 2);
}

TEST(EnavPlanner, RockAheadIsPassedAndTheChosenPathIsClear) {
  auto p = EnavPlanner::Create(TestOptions());
  ASSERT_TRUE(p.ok());
  // A 0.3 m rock 1.8 m ahead, 0.4 m across, on the line to the goal: the straight path puts a
  // wheel line or the rocker on it? The rock is under the centre line, so the body straddles
  // it only if 0.3 m clears the belly margin (0.35 - 0.05 = 0.30: it does not).
  const HeightTerrain t = TerrainOf(Blocks({{1.8, 0.0, 0.2, 0.32}}));
  auto e = p->Plan(t, Toward(4.5, 0));
  ASSERT_TRUE(e.ok());
  ASSERT_TRUE(e->has_choice());
  const PlanRecord& r = p->last();
  const TreePath& chosen = r.paths[static_cast<std::size_t>(r.chosen)];
  const ClearanceChecker checker(t);
  for (const geometry::Pose2& pose : p->Samples(r.start, chosen)) {
    EXPECT_TRUE(checker.CheckPose(pose, false).ok);
  }
  // Not the straight path through the rock: it fails the check.
  EXPECT_FALSE(chosen.turn == 0.0 && chosen.k1 == 0.0 && chosen.k2 == 0.0);
  TreePath straight;
  straight.length1 = TestOptions().first_length;
  straight.length2 = TestOptions().second_length;
  bool straight_clear = true;
  for (const geometry::Pose2& pose : p->Samples(r.start, straight)) {
    straight_clear = straight_clear && checker.CheckPose(pose, false).ok;
  }
  EXPECT_FALSE(straight_clear);
}

TEST(EnavPlanner, NearTheGoalItIsReached) {
  auto p = EnavPlanner::Create(TestOptions());
  ASSERT_TRUE(p.ok());
  const HeightTerrain t = TerrainOf(Blocks({}));
  auto e = p->Plan(t, Toward(0.2, 0.0));
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->mode, nav_core::GoalMode::kReached);
  EXPECT_FALSE(e->has_choice());
}

TEST(EnavPlanner, TheLastStepIsCheckedAsFarAsTheGoalNotJustIntoItsTolerance) {
  // Goal 0.9 m ahead with 0.5 m tolerance: the straight path enters the tolerance after 0.4 m,
  // but the mobility manager drives the last step up to the goal's distance (0.9 m), where the
  // left front wheel (centre 0.625 m ahead, reach 0.148 m) would be on a 0.3 m rock whose near
  // edge is 1.5 m out. The check covers what is driven, so the straight path is not cleared to
  // the goal: it is checked again only 5 cm into the tolerance (0.45 m: the wheel stays 0.2 m
  // short of the rock), passes, and is offered that far (max_drive), no farther.
  auto p = EnavPlanner::Create(TestOptions());
  ASSERT_TRUE(p.ok());
  const HeightTerrain t = TerrainOf(Blocks({{1.65, 0.5, 0.15, 0.3}}));
  nav_core::ArcRequest r;
  r.goal = {0.9, 0.0};
  r.goal_tolerance = 0.5;
  auto e = p->Plan(t, r);
  ASSERT_TRUE(e.ok()) << e.status().message();
  const PlanRecord& rec = p->last();
  ASSERT_GE(rec.chosen, 0);
  const TreePath& chosen = rec.paths[static_cast<std::size_t>(rec.chosen)];
  EXPECT_TRUE(chosen.turn == 0.0 && chosen.k1 == 0.0);
  EXPECT_TRUE(chosen.settled);
  EXPECT_NEAR(chosen.end_s, 0.45, 1e-9);
  EXPECT_NEAR(e->max_drive, 0.45, 1e-9);
  const ClearanceChecker checker(t);
  for (const geometry::Pose2& pose : p->Samples(rec.start, chosen)) {
    EXPECT_TRUE(checker.CheckPose(pose, false).ok);
  }
  // The rock 0.3 m nearer (near edge 1.2 m): not even 0.45 m of the straight path is clear, so
  // something else is chosen, checked all the way to the goal.
  {
    auto q = EnavPlanner::Create(TestOptions());
    ASSERT_TRUE(q.ok());
    const HeightTerrain near = TerrainOf(Blocks({{1.35, 0.5, 0.15, 0.3}}));
    auto f = q->Plan(near, r);
    ASSERT_TRUE(f.ok()) << f.status().message();
    const PlanRecord& qr = q->last();
    ASSERT_GE(qr.chosen, 0) << "a turn or a curve past the rock is open";
    const TreePath& other = qr.paths[static_cast<std::size_t>(qr.chosen)];
    EXPECT_FALSE(other.turn == 0.0 && other.k1 == 0.0) << "the straight path puts wheel_lf on it";
    const ClearanceChecker near_checker(near);
    for (const geometry::Pose2& pose : q->Samples(qr.start, other)) {
      EXPECT_TRUE(near_checker.CheckPose(pose, false).ok);
    }
  }
  // A caller that says it drives 0.3 m of the path before deciding again: checked into the
  // tolerance (0.4 m), the wheel stays short of the rock and the straight path is taken.
  // (A fresh planner: the first one would favour continuing its last choice.)
  r.drive_length = 0.3;
  auto p2 = EnavPlanner::Create(TestOptions());
  ASSERT_TRUE(p2.ok());
  auto short_step = p2->Plan(t, r);
  ASSERT_TRUE(short_step.ok()) << short_step.status().message();
  const PlanRecord& rec2 = p2->last();
  ASSERT_GE(rec2.chosen, 0);
  const TreePath& straight = rec2.paths[static_cast<std::size_t>(rec2.chosen)];
  EXPECT_TRUE(straight.turn == 0.0 && straight.k1 == 0.0);
  EXPECT_NEAR(straight.end_s, 0.4, 1e-9);
  EXPECT_FALSE(straight.settled);
  EXPECT_EQ(short_step->max_drive, 0.0);
  r.drive_length = -1.0;
  auto bad = p->Plan(t, r);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("ArcRequest.drive_length"), std::string::npos);
}

TEST(EnavPlanner, AGoalOnATallRockIsRefusedSayingWhy) {
  auto p = EnavPlanner::Create(TestOptions());
  ASSERT_TRUE(p.ok());
  const HeightTerrain t = TerrainOf(Blocks({{3.0, 0.0, 0.4, 0.6}}));
  auto e = p->Plan(t, Toward(3.0, 0.0));
  ASSERT_TRUE(e.ok());
  EXPECT_FALSE(e->has_choice());
  ASSERT_EQ(e->why.size(), 1u);
  EXPECT_NE(e->why[0].find("lies on a rock"), std::string::npos) << e->why[0];
  // Beside the rock it is a goal like any other.
  auto beside = p->Plan(t, Toward(3.0, 2.0));
  ASSERT_TRUE(beside.ok());
  EXPECT_TRUE(beside->has_choice());
}

TEST(EnavPlanner, WhenTheCostToGoReachesNoPathTheTreeIsRankedBlind) {
  auto p = EnavPlanner::Create(TestOptions());
  ASSERT_TRUE(p.ok());
  // A ring of 0.25 m rocks 0.9 m about the rover: it fits there in no heading, so the
  // configuration-space cost-to-go cannot reach its cell, nor any path that starts there.
  std::vector<Block> ring;
  for (int a = 0; a < 48; ++a) {
    const double t = 2.0 * std::numbers::pi * a / 48;
    ring.push_back({0.9 * std::cos(t), 0.9 * std::sin(t), 0.1, 0.25});
  }
  const HeightTerrain t = TerrainOf(Blocks(ring));
  auto e = p->Plan(t, Toward(4, 0));
  ASSERT_TRUE(e.ok());
  EXPECT_TRUE(p->last().blind);
  EXPECT_GT(e->candidates_ranked, 0);
  EXPECT_GT(e->clearance_checks, 0);  // the checks decided (here: nothing passes)
  EXPECT_FALSE(e->has_choice());
}

// The cost-to-go the mobility manager's progress window reads: the field's value for the goal
// of the latest decision; none for another goal, nor where the field is blocked.
TEST(EnavPlanner, ItsCostToGoIsTheLatestFieldsForThatGoalOnly) {
  std::vector<Block> wall;
  for (double y = -1.0; y <= 1.0 + 1e-9; y += 0.2) wall.push_back({3.0, y, 0.1, 0.6});
  const HeightTerrain t = TerrainOf(Blocks(wall));
  auto p = EnavPlanner::Create(TestOptions());
  ASSERT_TRUE(p.ok());
  const Eigen::Vector2d goal(6.0, 0.0);
  EXPECT_FALSE(p->CostToGo(goal, {0.0, 0.0}).has_value());  // no decision yet
  ASSERT_TRUE(p->Plan(t, Toward(goal.x(), goal.y())).ok());
  const std::optional<double> here = p->CostToGo(goal, {0.0, 0.0});
  ASSERT_TRUE(here.has_value());
  EXPECT_DOUBLE_EQ(*here, p->cost_to_go().Cost({0.0, 0.0}));
  EXPECT_GT(*here, 6.0 + 0.5);  // round the wall's end, not through it
  EXPECT_FALSE(p->CostToGo(goal, {3.0, 0.0}).has_value());   // on the wall: blocked
  EXPECT_FALSE(p->CostToGo({7.0, 0.0}, {0.0, 0.0}).has_value());  // another goal
}

TEST(EnavPlanner, BoxedInByTallRocksThereIsNoChoice) {
  auto p = EnavPlanner::Create(TestOptions());
  ASSERT_TRUE(p.ok());
  std::vector<Block> ring;
  for (int a = 0; a < 60; ++a) {
    const double t = 2.0 * std::numbers::pi * a / 60;
    ring.push_back({1.3 * std::cos(t), 1.3 * std::sin(t), 0.1, 0.6});
  }
  const HeightTerrain t = TerrainOf(Blocks(ring));
  auto e = p->Plan(t, Toward(4, 0));
  ASSERT_TRUE(e.ok());
  EXPECT_FALSE(e->has_choice());
  EXPECT_EQ(e->mode, nav_core::GoalMode::kNormal);
}

// A ring of 0.6 m rocks (radius 1.3 m) about (cx, 0): no path out of it passes.
HeightTerrain BoxedAt(double cx) {
  std::vector<Block> ring;
  for (int a = 0; a < 60; ++a) {
    const double t = 2.0 * std::numbers::pi * a / 60;
    ring.push_back({cx + 1.3 * std::cos(t), 1.3 * std::sin(t), 0.1, 0.6});
  }
  return TerrainOf(Blocks(ring));
}

nav_core::ArcRequest From(double x, double y, double heading, const nav_core::ArcRequest& r) {
  nav_core::ArcRequest out = r;
  out.site_from_rover = Eigen::Translation3d(x, y, 0.0) *
                        Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ());
  return out;
}

TEST(EnavPlanner, WithNoPathItBacksAlongTheArcItJustDrove) {
  auto p = EnavPlanner::Create(TestOptions());
  ASSERT_TRUE(p.ok());
  const HeightTerrain open = TerrainOf(Blocks({}));
  auto first = p->Plan(open, Toward(6, 0));
  ASSERT_TRUE(first.ok() && first->has_choice());
  ASSERT_EQ(first->choice().kind, nav_core::MotionKind::kArc);
  ASSERT_DOUBLE_EQ(first->choice().curvature, 0.0);
  // 0.4 m on, the map now shows it boxed in: back the 0.4 m it came, not a goal error.
  const HeightTerrain boxed = BoxedAt(0.4);
  auto back = p->Plan(boxed, From(0.4, 0.0, 0.0, Toward(6, 0)));
  ASSERT_TRUE(back.ok()) << back.status().message();
  ASSERT_TRUE(back->has_choice());
  EXPECT_TRUE(p->last().retrace);
  EXPECT_EQ(back->choice().kind, nav_core::MotionKind::kArc);
  EXPECT_EQ(back->choice().direction, -1);
  EXPECT_DOUBLE_EQ(back->choice().curvature, 0.0);
  EXPECT_NEAR(back->choice().length, 0.4, 0.021);
  // Asked again on the way back (a decision made ahead while driving, then redone): the rest.
  auto halfway = p->Plan(boxed, From(0.2, 0.0, 0.0, Toward(6, 0)));
  ASSERT_TRUE(halfway.ok() && halfway->has_choice());
  EXPECT_EQ(halfway->choice().direction, -1);
  EXPECT_NEAR(halfway->choice().length, 0.2, 0.021);
  // Back where the arc began and still boxed in: nothing left to retrace.
  auto again = p->Plan(BoxedAt(0.0), Toward(6, 0));
  ASSERT_TRUE(again.ok());
  EXPECT_FALSE(again->has_choice());
  EXPECT_FALSE(p->last().retrace);
}

TEST(EnavPlanner, AfterATurnAndAnArcItRetracesTheArcNotTheTurn) {
  auto p = EnavPlanner::Create(TestOptions());
  ASSERT_TRUE(p.ok());
  // Goal to the left: a turn in place, then an arc.
  auto first = p->Plan(TerrainOf(Blocks({})), Toward(0, 6));
  ASSERT_TRUE(first.ok() && first->has_choice());
  ASSERT_EQ(first->choice().kind, nav_core::MotionKind::kPointTurn);
  ASSERT_GE(first->path.size(), 2u);
  const double turn = first->path[0].turn_angle, k = first->path[1].curvature;
  // The turn and 0.4 m of the arc later, boxed in.
  const geometry::Pose2 there = geometry::AlongArc({0.0, 0.0, turn}, k, 0.4);
  auto back = p->Plan(BoxedAt(0.0), From(there.x, there.y, there.heading, Toward(0, 6)));
  ASSERT_TRUE(back.ok());
  ASSERT_TRUE(back->has_choice());
  EXPECT_TRUE(p->last().retrace);
  EXPECT_EQ(back->choice().kind, nav_core::MotionKind::kArc);
  EXPECT_EQ(back->choice().direction, -1);
  EXPECT_DOUBLE_EQ(back->choice().curvature, k);
  EXPECT_NEAR(back->choice().length, 0.4, 0.021);
}

TEST(EnavPlanner, OffItsLastDriveThereIsNothingToRetrace) {
  auto p = EnavPlanner::Create(TestOptions());
  ASSERT_TRUE(p.ok());
  auto first = p->Plan(TerrainOf(Blocks({})), Toward(6, 0));
  ASSERT_TRUE(first.ok() && first->has_choice());
  // Not where that drive went (0.5 m to the side, or turned 30 deg): no retrace.
  for (const auto& [y, h] : {std::pair{0.5, 0.0}, std::pair{0.0, 0.52}}) {
    auto e = p->Plan(BoxedAt(0.4), From(0.4, y, h, Toward(6, 0)));
    ASSERT_TRUE(e.ok());
    EXPECT_FALSE(e->has_choice()) << y << " " << h;
  }
}

}  // namespace
}  // namespace rover::apl::enav

namespace rover::apl::enav {
namespace {

TEST(EnavPlanner, WithTheRouteFirstItStepsStraightAlongTheRoute) {
  // A wall of 0.5 m blocks across x = 2 with a 1.6 m gap centred at y = -1.5: the rover, at the
  // origin facing north, must line up with the gap off to its right.
  std::vector<Block> wall;
  for (double y = -5.0; y <= 5.0 + 1e-9; y += 0.1) {
    if (std::abs(y + 1.5) < 0.9) continue;
    wall.push_back({2.0, y, 0.1, 0.5});
  }
  const HeightTerrain t = TerrainOf(Blocks(wall));
  EnavOptions o = TestOptions();
  o.route_max_expansions = 400000;
  o.route_first = true;
  auto p = EnavPlanner::Create(o);
  ASSERT_TRUE(p.ok());
  auto e = p->Plan(t, Toward(4, -1.5));
  ASSERT_TRUE(e.ok()) << e.status().message();
  ASSERT_TRUE(e->has_choice());
  const PlanRecord& rec = p->last();
  ASSERT_TRUE(rec.route.has_value());
  EXPECT_TRUE(rec.routed);
  EXPECT_TRUE(rec.route->at_goal);
  // The step: a turn toward a route pose, then a straight line to it, the whole path offered.
  const TreePath& chosen = rec.paths[static_cast<std::size_t>(rec.chosen)];
  EXPECT_DOUBLE_EQ(chosen.k1, 0.0);
  EXPECT_EQ(chosen.direction, 1);
  const geometry::Pose2 aim = geometry::AlongArc(geometry::Turned(rec.start, chosen.turn), 0.0,
                                                 chosen.length1);
  double nearest = 1e9;
  for (const RouteNode& n : rec.route->nodes) {
    nearest = std::min(nearest, (n.pose.xy() - aim.xy()).norm());
  }
  EXPECT_LT(nearest, 1e-6);
  EXPECT_LT(aim.y, 0.0);  // toward the gap, not at the wall straight ahead
  // The manager is cleared to drive no more of it than its line (not a whole drive length past
  // the route pose it aims at).
  EXPECT_DOUBLE_EQ(e->max_drive, chosen.length1);
  // Progress is measured along the route: its cost where the decision was made, none elsewhere.
  const std::optional<double> here = p->CostToGo({4, -1.5}, {0.0, 0.0});
  ASSERT_TRUE(here.has_value());
  EXPECT_DOUBLE_EQ(*here, rec.route->cost);
  EXPECT_FALSE(p->CostToGo({4, -1.5}, {1.0, 1.0}).has_value());
  // The next decision, from where the step leads, searches again but keeps the route while the
  // rover is on it, it fits and the new one is no cheaper by route_switch_m; a rock dropped on
  // it makes the new route the one followed.
  const geometry::Pose2 on =
      rec.route->nodes[std::min<std::size_t>(3, rec.route->nodes.size() - 1)].pose;
  auto kept = p->Plan(t, From(on.x, on.y, on.heading, Toward(4, -1.5)));
  ASSERT_TRUE(kept.ok());
  ASSERT_TRUE(p->last().route.has_value());
  EXPECT_TRUE(p->last().route_kept);
  EXPECT_GT(p->last().route->expansions, 0);
  EXPECT_EQ(kept->candidates_ranked, p->last().route->expansions);
  EXPECT_TRUE(p->ChecksTurns());  // the manager adds no unchecked turn of its own
  std::vector<Block> blocked = wall;
  const geometry::Pose2 far = p->last().route->nodes[p->last().route->nodes.size() / 2].pose;
  blocked.push_back({far.x, far.y, 0.15, 0.5});
  const HeightTerrain t2 = TerrainOf(Blocks(blocked));
  ASSERT_TRUE(p->Plan(t2, From(on.x, on.y, on.heading, Toward(4, -1.5))).ok());
  ASSERT_TRUE(p->last().route.has_value());
  EXPECT_FALSE(p->last().route_kept);
  // Off by default: the tree alone.
  auto tree = EnavPlanner::Create(TestOptions());
  ASSERT_TRUE(tree.ok());
  ASSERT_TRUE(tree->Plan(t, Toward(4, -1.5)).ok());
  EXPECT_FALSE(tree->last().route.has_value());
  EXPECT_FALSE(tree->last().routed);
}

}  // namespace
}  // namespace rover::apl::enav
