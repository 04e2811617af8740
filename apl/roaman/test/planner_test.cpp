// RoamanPlanner end to end: range data in, waypoints out; cul-de-sacs, replanning around
// blocked corridors, unreachable goals and bad input.
#include "rover/apl/roaman/planner.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "mast_synth.hpp"
#include "scenes.hpp"

namespace rover::apl::roaman {
namespace {

nav_core::PlanRequest Request(Eigen::Vector2d start, Eigen::Vector2d goal, bool partial = false) {
  nav_core::PlanRequest r;
  r.start = start;
  r.goal = goal;
  r.allow_partial = partial;
  return r;
}

// A planner that has seen all of `ground` in [x0, x1] x [y0, y1] (within max_range) from a
// rover at (x, y).
std::unique_ptr<RoamanPlanner> Seen(const sim::terrain::HeightField& ground, const RoamanOptions& o,
                                    double x, double y, double x0, double y0, double x1,
                                    double y1) {
  auto planner = RoamanPlanner::Create(o);
  EXPECT_TRUE(planner.ok()) << planner.status().message();
  const Status s = (*planner)->AddScan(
      testing::OverheadScan(ground, x0, y0, x1, y1, 0.04, testing::RoverPose(ground, x, y, 0.0)));
  EXPECT_TRUE(s.ok()) << s.message();
  return std::move(planner).value();
}

// Every leg of the plan is a clear straight drive and every turn point a safe turn, on the
// planner's own grid.
void ExpectSafe(const RoamanPlanner& p, const RoamanPlan& plan) {
  ASSERT_NE(p.last_problem(), nullptr);
  const PlanProblem& pr = *p.last_problem();
  for (std::size_t k = 0; k < plan.legs.size(); ++k) {
    const Leg& l = plan.legs[k];
    const bool first = k == 0 && pr.start_anchor != pr.request.start;
    if (!first) {
      EXPECT_TRUE(pr.grid.SegmentClear(l.from, l.to, pr.leg_clearance))
          << "leg " << k << " " << l.from.transpose() << " -> " << l.to.transpose();
    }
    if (k > 0) {
      EXPECT_GE(pr.grid.ClearanceAt(l.from), pr.footprint.TurnClearance(l.turn))
          << "turn before leg " << k;
    }
  }
}

// The U-shaped wall of the cul-de-sac tests: base at x = 6 across the way to the goal, its
// mouth facing the rover, 3 m wide inside, 3 m deep, 0.8 m high.
const sim::terrain::HeightField& CulDeSac() {
  static const sim::terrain::HeightField g = [] {
    sim::terrain::HeightField f = testing::FlatGround(-3, -7, 14, 7, 0.04);
    testing::AddCulDeSac(&f, {6.0, 0.0}, {-1.0, 0.0}, 3.0, 3.0, 0.3, 0.8);
    return f;
  }();
  return g;
}

bool InsideTheU(const Eigen::Vector2d& p) {
  return p.x() > 3.0 && p.x() < 5.85 && std::abs(p.y()) < 1.5;
}

RoamanOptions Wide() {
  RoamanOptions o;
  o.plan_width = 10.0;
  return o;
}

TEST(Planner, NoMapNoPlanAndBadRequestsAreNamed) {
  auto planner = RoamanPlanner::Create(RoamanOptions{});
  ASSERT_TRUE(planner.ok());
  RoamanPlanner& p = **planner;
  auto r = p.Plan(Request({0, 0}, {5, 0}));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_EQ(p.last_failure(), PlanFailure::kNoMap);
  r = p.Plan(Request({0, 0}, {std::nan(""), 0}));
  EXPECT_EQ(r.status().message(), "PlanRequest.goal.x is nan (must be finite)");
  EXPECT_EQ(p.last_failure(), PlanFailure::kInvalidRequest);
  RoamanOptions bad;
  bad.cell_size = -1.0;
  EXPECT_FALSE(RoamanPlanner::Create(bad).ok());
}

TEST(Planner, ScansThatAreAllInvalidOrNaNAreRejectedByName) {
  auto planner = RoamanPlanner::Create(RoamanOptions{});
  ASSERT_TRUE(planner.ok());
  const sim::terrain::HeightField flat = testing::FlatGround(-2, -3, 8, 3, 0.04);
  // Points at the cell centres, one per cell.
  nav_core::RangeScan s =
      testing::OverheadScan(flat, 0.025, -1.975, 6.0, 2.0, 0.05, testing::RoverPose(flat, 0, 0, 0));
  nav_core::RangeScan none = s;
  none.valid.assign(none.valid.size(), 0);
  Status st = (*planner)->AddScan(none);
  EXPECT_EQ(st.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(st.message().find("RangeScan 'overhead' has no usable point: 0 of"), std::string::npos);
  nav_core::RangeScan nan = s;
  for (std::size_t k = 0; k < nan.xyz.size(); k += 6)
    nan.xyz[k] = std::numeric_limits<float>::quiet_NaN();
  auto stats = (*planner)->Add(nan);
  ASSERT_TRUE(stats.ok()) << stats.status().message();
  EXPECT_EQ(stats->non_finite, (nan.xyz.size() + 5) / 6);
  EXPECT_EQ(stats->used + stats->non_finite, stats->valid);
  // With every other point missing the map has one-cell gaps, which the fill closes.
  auto plan = (*planner)->Plan(Request({0, 0}, {4, 0}));
  EXPECT_TRUE(plan.ok()) << plan.status().message();
}

TEST(Planner, OpenGroundIsOneStraightLeg) {
  const sim::terrain::HeightField flat = testing::FlatGround(-3, -5, 12, 5, 0.04);
  auto p = Seen(flat, RoamanOptions{}, 0, 0, -2, -4, 11, 4);
  for (const Algorithm a : {Algorithm::kRoaman, Algorithm::kAStar}) {
    auto plan = p->Plan(Request({0, 0}, {8, 0}), a);
    ASSERT_TRUE(plan.ok()) << AlgorithmName(a) << ": " << plan.status().message();
    EXPECT_EQ(plan->algorithm, a);
    EXPECT_FALSE(plan->fell_back);
    EXPECT_TRUE(plan->reaches_goal);
    EXPECT_EQ(plan->waypoints.back(), Eigen::Vector2d(8, 0));
    EXPECT_NEAR(plan->length, 8.0, 1e-6) << AlgorithmName(a);
    EXPECT_EQ(plan->legs.size(), 1u);
    EXPECT_NEAR(plan->cost, 8.0, 1e-6);
  }
  // Through the interface.
  auto g = p->MakePlan(Request({0, 0}, {8, 0}));
  ASSERT_TRUE(g.ok());
  EXPECT_TRUE(g->reaches_goal);
  EXPECT_EQ(g->waypoints.size(), 1u);
  // A goal within tolerance of the start: nothing to drive.
  nav_core::PlanRequest here = Request({0, 0}, {0.1, 0});
  here.goal_tolerance = 0.2;
  auto none = p->Plan(here);
  ASSERT_TRUE(none.ok());
  EXPECT_TRUE(none->reaches_goal);
  EXPECT_TRUE(none->waypoints.empty());
}

TEST(Planner, GoesAroundACulDeSacStraightOnTheWay) {
  auto p = Seen(CulDeSac(), Wide(), 0, 0, -2, -6, 12, 6);
  for (const Algorithm a : {Algorithm::kRoaman, Algorithm::kAStar}) {
    auto plan = p->Plan(Request({0, 0}, {10, 0}), a);
    ASSERT_TRUE(plan.ok()) << AlgorithmName(a) << ": " << plan.status().message();
    EXPECT_EQ(plan->algorithm, a);
    EXPECT_FALSE(plan->fell_back);
    EXPECT_TRUE(plan->reaches_goal);
    ExpectSafe(*p, *plan);
    // Never into the U: sample the legs.
    for (const Leg& l : plan->legs) {
      for (double s = 0.0; s <= 1.0; s += 0.01) {
        EXPECT_FALSE(InsideTheU(l.from + s * (l.to - l.from))) << AlgorithmName(a);
      }
    }
    // Around an arm: at least 1.8 m to the side somewhere, longer than the 10 m straight line.
    double side = 0.0;
    for (const Eigen::Vector2d& w : plan->waypoints) side = std::max(side, std::abs(w.y()));
    EXPECT_GT(side, 1.8) << AlgorithmName(a);
    EXPECT_GT(plan->length, 10.5);
    EXPECT_LT(plan->length, 15.0);
  }
  // ROAMAN's road map saw the U: axis cells inside it lead nowhere.
  ASSERT_TRUE(p->Plan(Request({0, 0}, {10, 0}), Algorithm::kRoaman).ok());
  ASSERT_NE(p->last_road_map(), nullptr);
  EXPECT_GT(p->last_road_map()->dropped, 0);
}

TEST(Planner, PlansTowardAGoalInTheShadowOfTheCulDeSac) {
  // The same U seen from the mast: its base hides the ground behind it, where the goal is.
  RoamanOptions o = Wide();
  auto planner = RoamanPlanner::Create(o);
  ASSERT_TRUE(planner.ok());
  testing::MastCamera cam;
  for (const auto& scan : testing::SynthesizePanorama(
           CulDeSac(),
           testing::PanoramaPointings(cam, 45.0 * kDegree, 3, {-8.0 * kDegree, -28.0 * kDegree}),
           testing::RoverPose(CulDeSac(), 0, 0, 0))) {
    ASSERT_TRUE((*planner)->AddScan(scan).ok());
  }
  RoamanPlanner& p = **planner;
  auto plan = p.Plan(Request({0, 0}, {8.0, 0}));
  ASSERT_FALSE(plan.ok());
  EXPECT_EQ(p.last_failure(), PlanFailure::kGoalMissing);
  EXPECT_NE(plan.status().message().find("goal (8, 0) is on terrain the map has no data for"),
            std::string::npos);
  plan = p.Plan(Request({0, 0}, {8.0, 0}, true));
  ASSERT_TRUE(plan.ok()) << plan.status().message();
  EXPECT_FALSE(plan->reaches_goal);
  EXPECT_LT(plan->goal_distance, 8.0 - o.min_progress);
  ExpectSafe(p, *plan);
  for (const Leg& l : plan->legs) {
    for (double s = 0.0; s <= 1.0; s += 0.01)
      EXPECT_FALSE(InsideTheU(l.from + s * (l.to - l.from)));
  }
  EXPECT_FALSE(plan->ToGlobalPlan().reaches_goal);
}

// Two corridors to the goal either side of a wall, closed outside by walls at |y| = 3.5.
const sim::terrain::HeightField& TwoCorridors() {
  static const sim::terrain::HeightField g = [] {
    sim::terrain::HeightField f = testing::FlatGround(-3, -5, 14, 5, 0.04);
    testing::AddWall(&f, {2.0, 0.0}, {8.0, 0.0}, 0.25, 0.6);
    testing::AddWall(&f, {-3.0, 3.75}, {14.0, 3.75}, 0.25, 0.6);
    testing::AddWall(&f, {-3.0, -3.75}, {14.0, -3.75}, 0.25, 0.6);
    return f;
  }();
  return g;
}

TEST(Planner, ReplansAroundABlockedCorridorUntilEveryRouteIsBlocked) {
  RoamanOptions o;
  o.plan_width = 8.0;
  auto p = Seen(TwoCorridors(), o, 0, 0, -2, -4.5, 12, 4.5);
  const nav_core::PlanRequest req = Request({0, 0}, {10, 0});
  auto first = p->Plan(req);
  ASSERT_TRUE(first.ok()) << first.status().message();
  ASSERT_TRUE(first->reaches_goal);
  // Which side it took, from the waypoints along the wall.
  double side = 0.0;
  for (const Leg& l : first->legs) {
    const Eigen::Vector2d m = 0.5 * (l.from + l.to);
    if (m.x() > 3.0 && m.x() < 7.0) side = m.y();
  }
  ASSERT_NE(side, 0.0);
  const double y = side > 0 ? 1.9 : -1.9;
  // The mobility manager reports NOPATH on that corridor: it is blocked from x = 4 to 6.
  ASSERT_TRUE(p->ReportBlocked({4.0, y}, {6.0, y}, 1.6).ok());
  auto second = p->Plan(req);
  ASSERT_TRUE(second.ok()) << second.status().message();
  EXPECT_TRUE(second->reaches_goal);
  ExpectSafe(*p, *second);
  for (const Leg& l : second->legs) {
    for (double s = 0.0; s <= 1.0; s += 0.02) {
      const Eigen::Vector2d q = l.from + s * (l.to - l.from);
      if (q.x() > 3.0 && q.x() < 7.0) {
        EXPECT_LT(q.y() * side, 0.0) << q.transpose();
      }
    }
  }
  // And the other one: every route is known blocked, and the error says so.
  ASSERT_TRUE(p->ReportBlocked({4.0, -y}, {6.0, -y}, 1.6).ok());
  auto third = p->Plan(req);
  ASSERT_FALSE(third.ok());
  EXPECT_EQ(third.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(p->last_failure(), PlanFailure::kBlocked);
  EXPECT_EQ(third.status().message().rfind("every route to the goal (10, 0) is blocked: ", 0), 0u)
      << third.status().message();
  EXPECT_NE(third.status().message().find("2 corridors reported blocked"), std::string::npos);
  EXPECT_FALSE(p->ReportBlocked({0, 0}, {1, 0}, -1.0).ok());
  // Clear() forgets the corridors with the map.
  p->Clear();
  EXPECT_EQ(p->Plan(req).status().code(), StatusCode::kFailedPrecondition);
}

TEST(Planner, AGoalNoRouteReachesIsAGoalErrorThatSaysSo) {
  // A closed ring of wall 0.3 m thick and 0.6 m high, 1.6 m in radius, around the goal.
  const sim::terrain::HeightField f =
      testing::HeightFieldOf(-3, -5, 14, 5, 0.04, [](double x, double y) {
        return std::abs(std::hypot(x - 7.0, y) - 1.6) <= 0.15 ? 0.6 : 0.0;
      });
  auto p = Seen(f, RoamanOptions{}, 0, 0, -2, -4, 11, 4);
  auto plan = p->Plan(Request({0, 0}, {7.0, 0}));
  ASSERT_FALSE(plan.ok());
  EXPECT_EQ(p->last_failure(), PlanFailure::kBlocked);
  EXPECT_EQ(plan.status().message().rfind("every route to the goal (7, 0) is blocked: the ", 0), 0u)
      << plan.status().message();
  EXPECT_NE(plan.status().message().find("0 corridors reported blocked (roaman: "),
            std::string::npos);
  EXPECT_NE(plan.status().message().find("; astar: "), std::string::npos);
}

TEST(Planner, GoalsInHazardsOffTheMapAndRoversBoxedIn) {
  sim::terrain::HeightField f = testing::FlatGround(-3, -5, 14, 5, 0.04);
  testing::AddRock(&f, 6.0, 0.0, 1.0, 0.6);
  auto p = Seen(f, RoamanOptions{}, 0, 0, -2, -4, 11, 4);
  auto r = p->Plan(Request({0, 0}, {6.0, 0}));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(p->last_failure(), PlanFailure::kGoalInHazard);
  EXPECT_NE(r.status().message().find("goal (6, 0) is inside a hazard"), std::string::npos);
  r = p->Plan(Request({0, 0}, {30.0, 0}));
  EXPECT_EQ(p->last_failure(), PlanFailure::kGoalOffMap);
  EXPECT_NE(r.status().message().find("goal (30, 0) is off the map"), std::string::npos);
  r = p->Plan(Request({0, 0}, {30.0, 0}, true));
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_FALSE(r->reaches_goal);
  EXPECT_GT(r->waypoints.back().x(), 8.5);  // near the end of the data (11 m), a turn short

  sim::terrain::HeightField boxed = testing::FlatGround(-3, -5, 14, 5, 0.04);
  for (int k = 0; k < 12; ++k) {
    const double a = 2.0 * M_PI * k / 12;
    testing::AddRock(&boxed, 0.9 * std::cos(a), 0.9 * std::sin(a), 0.5, 0.5);
  }
  auto q = Seen(boxed, RoamanOptions{}, 0, 0, -2, -4, 11, 4);
  r = q->Plan(Request({0, 0}, {6.0, 0}));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(q->last_failure(), PlanFailure::kNoSafeStart);
  EXPECT_EQ(r.status().message().rfind("no safe cell near the rover at (0, 0): ", 0), 0u);
}

TEST(Planner, FallsBackToAStarWhenTheRoadMapHasNoRoute) {
  RoamanOptions o;
  o.connect_radius = 0.0;  // the start connects to no axis cell: the road map cannot begin
  const sim::terrain::HeightField flat = testing::FlatGround(-3, -5, 12, 5, 0.04);
  auto p = Seen(flat, o, 0, 0, -2, -4, 11, 4);
  auto plan = p->Plan(Request({0, 0}, {8, 0}));
  ASSERT_TRUE(plan.ok()) << plan.status().message();
  EXPECT_EQ(plan->algorithm, Algorithm::kAStar);
  EXPECT_TRUE(plan->fell_back);
  o.fallback = false;
  auto q = Seen(flat, o, 0, 0, -2, -4, 11, 4);
  EXPECT_EQ(q->Plan(Request({0, 0}, {8, 0})).status().code(), StatusCode::kNotFound);
  EXPECT_EQ(q->last_failure(), PlanFailure::kBlocked);
}

TEST(Planner, TheMapMemoryMergesPanoramasAsTheRoverMoves) {
  // A 26 m strip; the first "panorama" sees 12 m around the start, the second 12 m around
  // x = 8 m. After the second the goal 16 m out is on the grid and reached.
  sim::terrain::HeightField f = testing::FlatGround(-3, -5, 24, 5, 0.04);
  testing::AddRock(&f, 4.0, 0.0, 1.0, 0.6);
  auto p = Seen(f, RoamanOptions{}, 0, 0, -2, -4, 23, 4);
  const double centre = p->site_map().center().x();
  auto far = p->Plan(Request({0, 0}, {16, 0}));
  EXPECT_EQ(p->last_failure(), PlanFailure::kGoalOffMap);
  auto step = p->Plan(Request({0, 0}, {16, 0}, true));
  ASSERT_TRUE(step.ok()) << step.status().message();
  EXPECT_FALSE(step->reaches_goal);
  ASSERT_TRUE(
      p->AddScan(testing::OverheadScan(f, 6, -4, 23, 4, 0.04, testing::RoverPose(f, 8.0, 0.0, 0.0)))
          .ok());
  EXPECT_GT(p->site_map().panorama(), 1);
  EXPECT_GT(p->site_map().center().x(), centre + 6.0);  // recentred on the rover
  auto there = p->Plan(Request({8, 0}, {16, 0}));
  ASSERT_TRUE(there.ok()) << there.status().message();
  EXPECT_TRUE(there->reaches_goal);
  // The rock behind the rover, which only the first panorama saw, is still in the map.
  int hazard = 0;
  for (double dx = -0.5; dx <= 0.5; dx += 0.05) {
    for (double dy = -0.5; dy <= 0.5; dy += 0.05) {
      hazard += IsHazard(p->Traversability().ClassAt(4.0 + dx, dy));
    }
  }
  EXPECT_GT(hazard, 20);
}

}  // namespace
}  // namespace rover::apl::roaman
