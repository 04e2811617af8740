#include "rover/apl/gestalt/arc_evaluator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>

#include "test_maps.hpp"

namespace rover::apl::gestalt {
namespace {

using nav_core::ArcEvaluation;
using nav_core::ArcRequest;
using nav_core::GoalMode;
using nav_core::GoodnessMap;
using nav_core::MotionKind;
using nav_core::Vote;

using testing::KnownMap;  // a 10 m map centred on the origin, every cell known
void SetRect(GoodnessMap* m, double x0, double x1, double y0, double y1, int g, int c = 255,
             std::uint8_t flags = nav_core::kCellKnown) {
  for (int j = 0; j < m->height; ++j) {
    for (int i = 0; i < m->width; ++i) {
      const Eigen::Vector2d p = m->CellCenter(i, j);
      if (p.x() < x0 || p.x() > x1 || p.y() < y0 || p.y() > y1) continue;
      m->goodness[m->Index(i, j)] = static_cast<std::uint8_t>(g);
      m->certainty[m->Index(i, j)] = static_cast<std::uint8_t>(c);
      m->flags[m->Index(i, j)] = flags;
    }
  }
}

ArcRequest Toward(double gx, double gy, double yaw = 0.0, double tolerance = 0.3) {
  ArcRequest r;
  r.site_from_rover.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  r.goal = {gx, gy};
  r.goal_tolerance = tolerance;
  return r;
}

ArcEvaluator MakeEvaluator(const GestaltOptions& o = {}) {
  auto e = ArcEvaluator::Create(o);
  EXPECT_TRUE(e.ok()) << e.status().message();
  return std::move(e).value();
}

TEST(ArcEvaluator, CandidatesAreMersArcsAndTurns) {
  const ArcEvaluator ev = MakeEvaluator();
  const auto& c = ev.candidates();
  ASSERT_EQ(c.size(), 23u + 23u + 23u);
  EXPECT_EQ(c[0].curvature, -1.0);
  EXPECT_EQ(c[11].curvature, 0.0);
  EXPECT_EQ(c[22].curvature, 1.0);
  EXPECT_EQ(c[23].direction, -1);
  EXPECT_EQ(c[46].kind, MotionKind::kPointTurn);
  EXPECT_NEAR(c[46].turn_angle, -165.0 * std::numbers::pi / 180.0, 1e-12);
  EXPECT_NEAR(c.back().turn_angle, std::numbers::pi, 1e-12);
}

TEST(ArcEvaluator, OpenGroundPicksTheArcToTheGoal) {
  const ArcEvaluator ev = MakeEvaluator();
  auto e = ev.Evaluate(KnownMap(), Toward(4.0, 0.0));
  ASSERT_TRUE(e.ok()) << e.status().message();
  EXPECT_EQ(e->mode, GoalMode::kNormal);
  ASSERT_TRUE(e->has_choice());
  EXPECT_EQ(e->choice().kind, MotionKind::kArc);
  EXPECT_EQ(e->choice().direction, 1);
  EXPECT_EQ(e->choice().curvature, 0.0);
  EXPECT_EQ(e->merged[11].goodness, 255);
  EXPECT_DOUBLE_EQ(e->choice().length, 3.0);  // plan_max_dist
  EXPECT_TRUE(e->all_paths_safe);
  EXPECT_FALSE(e->image_rear);
  EXPECT_DOUBLE_EQ(e->distance_to_goal, 4.0);
}

TEST(ArcEvaluator, WaypointVotesAreGaussiansAroundTheGoalArc) {
  GestaltOptions o;
  const ArcEvaluator ev = MakeEvaluator(o);
  const double gx = 3.0, gy = 1.0;
  auto e = ev.Evaluate(KnownMap(), Toward(gx, gy));
  ASSERT_TRUE(e.ok());
  const double k_goal = 2.0 * gy / (gx * gx + gy * gy);
  const double bearing = std::atan2(gy, gx);
  for (std::size_t k = 0; k < e->candidates.size(); ++k) {
    const auto& c = e->candidates[k];
    double want = 0.0;
    if (c.kind == MotionKind::kArc) {
      const double peak = c.direction > 0 ? 255.0 : 128.0;
      want = peak * std::exp(-std::pow(c.curvature - k_goal, 2) / (2.0 * 3.2));
    } else {
      const double da = std::remainder(c.turn_angle - bearing, 2.0 * std::numbers::pi);
      want = 128.0 * std::exp(-da * da / (2.0 * o.turn_vote_variance));
    }
    EXPECT_EQ(e->waypoint[k].goodness, static_cast<int>(std::lround(want))) << k;
    EXPECT_EQ(e->waypoint[k].certainty, 192);
  }
  // The chosen arc is the one nearest k*: hazard is flat, so the waypoint vote decides.
  ASSERT_TRUE(e->has_choice());
  EXPECT_NEAR(e->choice().curvature, k_goal, 1.0 / 11.0);
}

TEST(ArcEvaluator, GoalBehindPrefersBackingUp) {
  const ArcEvaluator ev = MakeEvaluator();
  auto e = ev.Evaluate(KnownMap(), Toward(-3.0, 0.0));
  ASSERT_TRUE(e.ok());
  ASSERT_TRUE(e->has_choice());
  EXPECT_EQ(e->choice().kind, MotionKind::kArc);
  EXPECT_EQ(e->choice().direction, -1);
  EXPECT_EQ(e->choice().curvature, 0.0);
  EXPECT_EQ(e->waypoint[11].goodness, 128);  // forward straight: away from the goal
  EXPECT_EQ(e->waypoint[23 + 11].goodness, 255);
}

TEST(ArcEvaluator, ObstacleForbidsArcsAndTheRoverGoesAround) {
  GoodnessMap m = KnownMap();
  SetRect(&m, 1.4, 2.2, -0.6, 1.6, 0);  // a rock blob ahead and to the left
  const ArcEvaluator ev = MakeEvaluator();
  auto e = ev.Evaluate(m, Toward(4.0, 0.0));
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->hazard[11].goodness, 0);  // straight ahead is forbidden
  EXPECT_EQ(e->hazard[11].certainty, 255);
  EXPECT_EQ(e->merged[11].goodness, 0);
  ASSERT_TRUE(e->has_choice());
  EXPECT_EQ(e->choice().kind, MotionKind::kArc);
  EXPECT_LT(e->choice().curvature, 0.0);  // to the right, away from the blob
  EXPECT_GT(e->hazard[static_cast<std::size_t>(e->chosen)].goodness, 200);
  EXPECT_FALSE(e->all_paths_safe);  // some forward arc is forbidden: image before the next step
}

TEST(ArcEvaluator, NearerCellsWeighMore) {
  // Equal poor patches near and far on two straight paths: the path with the near patch scores
  // lower. Compare the two halves of the same straight arc.
  GoodnessMap near_bad = KnownMap(), far_bad = KnownMap();
  SetRect(&near_bad, 0.3, 1.2, -0.4, 0.4, 100);
  SetRect(&far_bad, 2.1, 3.0, -0.4, 0.4, 100);
  const ArcEvaluator ev = MakeEvaluator();
  auto a = ev.Evaluate(near_bad, Toward(5.0, 0.0));
  auto b = ev.Evaluate(far_bad, Toward(5.0, 0.0));
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_LT(a->hazard[11].goodness, b->hazard[11].goodness);
}

TEST(ArcEvaluator, UnknownCellsAreAllowedButPoor) {
  GoodnessMap m = KnownMap();
  SetRect(&m, -5.0, 5.0, -5.0, 5.0, 11, 0, 0);  // all unknown
  const ArcEvaluator ev = MakeEvaluator();
  auto e = ev.Evaluate(m, Toward(4.0, 0.0));
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->hazard[11].goodness, 11);
  EXPECT_EQ(e->hazard[11].certainty, 0);
  EXPECT_EQ(e->merged[11].goodness, 11);  // below min_vote_goodness: the minimum
  ASSERT_TRUE(e->has_choice());
  EXPECT_FALSE(e->all_paths_safe);
  EXPECT_TRUE(e->image_rear);
}

TEST(ArcEvaluator, KTurnForAGoalInsideTheTurningCircle) {
  // The goal 0.5 m to the left, 0.2 m ahead: k* = 2 y / |g|^2 = 3.45 > 1.
  GestaltOptions no_turns;
  no_turns.num_point_turns = 0;
  auto e = MakeEvaluator(no_turns).Evaluate(KnownMap(), Toward(0.2, 0.5, 0.0, 0.1));
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->mode, GoalMode::kBackUp);
  ASSERT_TRUE(e->has_choice());
  // Back up along (about) the tightest arc away from the goal, which swings the heading toward
  // it: the Gaussian peaks, halved, on the k = -1 backward arc (index 23); the merged 8-bit
  // votes of its neighbours tie and the middle of that plateau is driven.
  EXPECT_EQ(e->choice().direction, -1);
  EXPECT_LE(e->choice().curvature, -0.8);
  EXPECT_EQ(e->waypoint[23].goodness, 128);  // 255 halved
  EXPECT_EQ(e->waypoint[22].goodness, 64);   // forward arcs cannot reach it either: 128 halved
  const Eigen::Vector2d end = ArcPoint(-1.0, -1, 0.5);
  EXPECT_LT(end.y(), 0.0);  // moved away from the goal's side
  // With turns in place available, the halved back-up vote loses to the turn toward the goal.
  auto t = MakeEvaluator().Evaluate(KnownMap(), Toward(0.2, 0.5, 0.0, 0.1));
  ASSERT_TRUE(t.ok());
  ASSERT_TRUE(t->has_choice());
  EXPECT_EQ(t->choice().kind, MotionKind::kPointTurn);
  EXPECT_NEAR(t->choice().turn_angle, 75.0 * std::numbers::pi / 180.0, 1e-9);  // bearing 68 deg
}

TEST(ArcEvaluator, DirectionHysteresisKeepsDrivingForwardPastAbeam) {
  // The goal 8 m away, 100 deg to the left: 10 deg behind abeam. MER (no hysteresis) makes
  // backward the goal's direction there whatever the rover drove last.
  const double b = 100.0 * std::numbers::pi / 180.0;
  ArcRequest r = Toward(8.0 * std::cos(b), 8.0 * std::sin(b));
  r.last_direction = 1;
  auto mer = MakeEvaluator().Evaluate(KnownMap(), r);
  ASSERT_TRUE(mer.ok());
  ASSERT_TRUE(mer->has_choice());
  EXPECT_EQ(mer->choice().direction, -1);
  // With 20 deg of hysteresis the rover that drove forward keeps forward (peak 255)...
  GestaltOptions o;
  o.direction_hysteresis = 20.0 * std::numbers::pi / 180.0;
  const ArcEvaluator ev = MakeEvaluator(o);
  auto fwd = ev.Evaluate(KnownMap(), r);
  ASSERT_TRUE(fwd.ok());
  ASSERT_TRUE(fwd->has_choice());
  EXPECT_EQ(fwd->choice().direction, 1);
  EXPECT_GT(fwd->waypoint[11].goodness, 200);  // straight ahead: the forward peak's Gaussian
  EXPECT_LT(fwd->waypoint[34].goodness, 129);  // straight back: the away peak's
  // ... one that drove backward, or none yet, reverses as MER does...
  r.last_direction = -1;
  auto back = ev.Evaluate(KnownMap(), r);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->choice().direction, -1);
  r.last_direction = 0;
  EXPECT_EQ(ev.Evaluate(KnownMap(), r)->choice().direction, -1);
  // ... and beyond the hysteresis (the goal 30 deg behind abeam) forward no longer holds.
  const double far = 120.0 * std::numbers::pi / 180.0;
  ArcRequest r2 = Toward(8.0 * std::cos(far), 8.0 * std::sin(far));
  r2.last_direction = 1;
  EXPECT_EQ(ev.Evaluate(KnownMap(), r2)->choice().direction, -1);
  // Symmetric for backward: 10 deg ahead of abeam, a rover that backed keeps backing.
  const double ahead = 80.0 * std::numbers::pi / 180.0;
  ArcRequest r3 = Toward(8.0 * std::cos(ahead), 8.0 * std::sin(ahead));
  r3.last_direction = -1;
  EXPECT_EQ(ev.Evaluate(KnownMap(), r3)->choice().direction, -1);
  r3.last_direction = 1;
  EXPECT_EQ(ev.Evaluate(KnownMap(), r3)->choice().direction, 1);
}

TEST(ArcEvaluator, RequestWithABadLastDirectionIsRefused) {
  ArcRequest r = Toward(4.0, 0.0);
  r.last_direction = 2;
  auto e = MakeEvaluator().Evaluate(KnownMap(), r);
  ASSERT_FALSE(e.ok());
  EXPECT_NE(e.status().message().find("ArcRequest.last_direction"), std::string::npos)
      << e.status().message();
}

TEST(ArcEvaluator, FramesFollowTheRoverHeading) {
  // Rover facing site +y (yaw 90 deg); a goal at site (0, 4) is straight ahead.
  const ArcEvaluator ev = MakeEvaluator();
  auto e = ev.Evaluate(KnownMap(), Toward(0.0, 4.0, std::numbers::pi / 2));
  ASSERT_TRUE(e.ok());
  ASSERT_TRUE(e->has_choice());
  EXPECT_EQ(e->choice().curvature, 0.0);
  EXPECT_EQ(e->choice().direction, 1);
  // A blob at site (0, 2) now blocks it.
  GoodnessMap m = KnownMap();
  SetRect(&m, -0.4, 0.4, 1.6, 2.4, 0);
  auto b = ev.Evaluate(m, Toward(0.0, 4.0, std::numbers::pi / 2));
  ASSERT_TRUE(b.ok());
  EXPECT_EQ(b->hazard[11].goodness, 0);
}

TEST(ArcEvaluator, ReachedGoalChoosesNothing) {
  auto e = MakeEvaluator().Evaluate(KnownMap(), Toward(0.2, 0.1, 0.0, 0.3));
  ASSERT_TRUE(e.ok());
  EXPECT_EQ(e->mode, GoalMode::kReached);
  EXPECT_FALSE(e->has_choice());
}

TEST(ArcEvaluator, SkipImagingNeedsEveryPathKnownAndGood) {
  const ArcEvaluator ev = MakeEvaluator();
  GoodnessMap unknown_patch = KnownMap();
  SetRect(&unknown_patch, 2.0, 3.0, 1.0, 2.0, 11, 0,
          0);  // off to the left: the k = 1 arcs cross it
  auto a = ev.Evaluate(unknown_patch, Toward(4.0, 0.0));
  ASSERT_TRUE(a.ok());
  ASSERT_TRUE(a->has_choice());
  EXPECT_FALSE(a->all_paths_safe);
  GoodnessMap rough = KnownMap();
  SetRect(&rough, -5.0, 5.0, -5.0, 5.0, 190);
  auto b = ev.Evaluate(rough, Toward(4.0, 0.0));
  ASSERT_TRUE(b.ok());
  EXPECT_FALSE(b->all_paths_safe);  // 190 < skip_imaging_goodness 200
  GoodnessMap fine = KnownMap();
  SetRect(&fine, -5.0, 5.0, -5.0, 5.0, 210);
  auto c = ev.Evaluate(fine, Toward(4.0, 0.0));
  ASSERT_TRUE(c.ok());
  EXPECT_TRUE(c->all_paths_safe);
}

TEST(ArcEvaluator, RejectsBadRequests) {
  const ArcEvaluator ev = MakeEvaluator();
  ArcRequest r = Toward(std::numeric_limits<double>::quiet_NaN(), 0.0);
  EXPECT_EQ(ev.Evaluate(KnownMap(), r).status().message(),
            "ArcRequest.goal.x is nan (must be finite)");
  r = Toward(1.0, 0.0, 0.0, -1.0);
  EXPECT_EQ(ev.Evaluate(KnownMap(), r).status().message(),
            "ArcRequest.goal_tolerance = -1 m is outside [0, inf)");
  r = Toward(1.0, 0.0);
  r.site_from_rover.translation().y() = std::numeric_limits<double>::infinity();
  EXPECT_EQ(ev.Evaluate(KnownMap(), r).status().message(),
            "ArcRequest.site_from_rover(1, 3) is inf (must be finite)");
  GestaltOptions bad;
  bad.num_forward_arcs = 0;
  EXPECT_EQ(ArcEvaluator::Create(bad).status().message(),
            "num_forward_arcs = 0 is outside [1, 99]");
}

TEST(MergeVotes, MinimumBelowTheThresholdWeightedSumAbove) {
  EXPECT_EQ(MergeVotes({20, 255}, {250, 192}, 26).goodness, 20);
  EXPECT_EQ(MergeVotes({200, 255}, {20, 192}, 26).goodness, 20);
  const Vote m = MergeVotes({200, 255}, {100, 192}, 26);
  EXPECT_EQ(m.goodness, static_cast<int>(std::lround((200.0 * 255 + 100.0 * 192) / (255 + 192))));
  EXPECT_EQ(m.certainty, 255);
  EXPECT_EQ(MergeVotes({200, 0}, {100, 192}, 26).goodness, 100);  // no hazard certainty
  EXPECT_EQ(MergeVotes({200, 0}, {100, 0}, 26).goodness, 100);    // none at all: the minimum
}

TEST(ChooseCandidate, MiddleOfTheLongestPlateau) {
  auto votes = [](std::vector<int> g) {
    std::vector<Vote> v;
    for (int x : g) v.push_back({x, 255});
    return v;
  };
  EXPECT_EQ(ChooseCandidate(votes({1, 5, 5, 5, 2}), {0, 0, 0, 0, 0}), 2);
  EXPECT_EQ(ChooseCandidate(votes({5, 5, 0, 5, 5, 5}), {0, 0, 0, 0, 0, 0}), 4);
  EXPECT_EQ(ChooseCandidate(votes({5, 5, 5, 5}), {0, 0, 0, 0}), 1);  // even: the lower middle
  EXPECT_EQ(ChooseCandidate(votes({5, 0, 5}), {0, 0, 0}), 0);        // equal runs: the first
  // A plateau does not run across groups (the last forward arc and the first backward arc).
  EXPECT_EQ(ChooseCandidate(votes({5, 5, 5, 5, 5}), {0, 0, 1, 1, 1}), 3);
  EXPECT_EQ(ChooseCandidate(votes({3, 9, 3}), {0, 0, 0}), 1);
  EXPECT_EQ(ChooseCandidate(votes({0, 0}), {0, 0}), -1);
  EXPECT_EQ(ChooseCandidate({}, {}), -1);
}

namespace footprint {

GestaltOptions FootprintOptions(bool cost_to_go = false, bool straddle = false) {
  GestaltOptions o;
  o.footprint_check = true;
  o.cost_to_go = cost_to_go;
  o.footprint_straddle = straddle;
  return o;
}

// A hazard cell (a rock's top) at site point (x, y); its goodness stays high, as the footprint
// check forbids by the flag and the floor keeps step goodness above min_allowed_goodness.
void AddHazard(GoodnessMap* m, double x, double y) {
  SetRect(m, x - 0.1, x + 0.1, y - 0.1, y + 0.1, 200, 255,
          nav_core::kCellKnown | nav_core::kCellHazard);
}

int StraightIndex(const ArcEvaluator& ev) {
  for (std::size_t k = 0; k < ev.candidates().size(); ++k) {
    const auto& c = ev.candidates()[k];
    if (c.kind == MotionKind::kArc && c.direction == 1 && c.curvature == 0.0) {
      return static_cast<int>(k);
    }
  }
  return -1;
}

TEST(ArcEvaluatorFootprint, RockBesideTheFootprintIsPassedRockInItForbids) {
  const ArcEvaluator ev = MakeEvaluator(FootprintOptions());
  const int straight = StraightIndex(ev);
  ASSERT_GE(straight, 0);
  // Half width 0.58 + margin 0.15 = 0.73 m: a rock 0.9 m to the side is clear, one 0.5 m to
  // the side (1.5 m ahead) is hit within footprint_forbid_dist of driving.
  GoodnessMap beside = KnownMap(), in_path = KnownMap();
  AddHazard(&beside, 1.5, 0.9);
  AddHazard(&in_path, 1.5, 0.5);
  auto e_beside = ev.Evaluate(beside, Toward(4.0, 0.0));
  auto e_in = ev.Evaluate(in_path, Toward(4.0, 0.0));
  ASSERT_TRUE(e_beside.ok() && e_in.ok());
  EXPECT_GT(e_beside->hazard[straight].goodness, 0);
  EXPECT_EQ(e_in->hazard[straight].goodness, 0);
  // The disc-based MER check with the same map (no hazard flags used) would not forbid it.
  auto e_mer = MakeEvaluator().Evaluate(in_path, Toward(4.0, 0.0));
  ASSERT_TRUE(e_mer.ok());
  EXPECT_GT(e_mer->hazard[straight].goodness, 0);
}

TEST(ArcEvaluatorFootprint, FartherHitScalesTheVote) {
  const ArcEvaluator ev = MakeEvaluator(FootprintOptions());
  const int straight = StraightIndex(ev);
  GoodnessMap clear = KnownMap(), far_rock = KnownMap();
  // Front edge 0.75 + 0.15: a rock at x = 2.9 is reached after ~2 m of the 3 m path.
  AddHazard(&far_rock, 2.9, 0.0);
  auto e_clear = ev.Evaluate(clear, Toward(4.0, 0.0));
  auto e_far = ev.Evaluate(far_rock, Toward(4.0, 0.0));
  ASSERT_TRUE(e_clear.ok() && e_far.ok());
  EXPECT_GT(e_far->hazard[straight].goodness, 0);
  EXPECT_LT(e_far->hazard[straight].goodness, e_clear->hazard[straight].goodness);
}

TEST(ArcEvaluatorFootprint, TurnSweepingTheCornerOverARockIsForbidden) {
  const ArcEvaluator ev = MakeEvaluator(FootprintOptions());
  // Just outside the grown front-left corner (0.9, 0.73): clear while the rover stands, hit as
  // the corner swings left.
  GoodnessMap m = KnownMap();
  AddHazard(&m, 0.65, 0.95);
  auto e = ev.Evaluate(m, Toward(0.0, 4.0));
  ASSERT_TRUE(e.ok());
  for (std::size_t k = 0; k < ev.candidates().size(); ++k) {
    const auto& c = ev.candidates()[k];
    if (c.kind == MotionKind::kPointTurn && c.turn_angle > 0.6 && c.turn_angle < 2.0) {
      EXPECT_EQ(e->hazard[k].goodness, 0) << "turn " << c.turn_angle;
    }
  }
}

TEST(ArcEvaluatorFootprint, HazardUnderTheStartFootprintDoesNotTrapTheRover) {
  const ArcEvaluator ev = MakeEvaluator(FootprintOptions());
  GoodnessMap m = KnownMap();
  AddHazard(&m, 0.3, 0.3);  // under the rover now: moving off must stay possible
  auto e = ev.Evaluate(m, Toward(4.0, 0.0));
  ASSERT_TRUE(e.ok());
  EXPECT_TRUE(e->has_choice());
}

TEST(ArcEvaluatorFootprint, CostToGoAimsAtTheGapNotTheWall) {
  // A wall of hazard cells across x = 2.5 from y = -3 to 0.6, gap to the left of it: the goal
  // straight ahead lies behind the wall. MER's vote centres on the straight arc; the cost-to-go
  // vote prefers the arcs bending left toward the gap.
  GoodnessMap m = KnownMap();
  for (double y = -3.0; y <= 0.6; y += 0.2) AddHazard(&m, 2.5, y);
  const ArcEvaluator ev = MakeEvaluator(FootprintOptions(true));
  auto e = ev.Evaluate(m, Toward(4.5, 0.0));
  ASSERT_TRUE(e.ok()) << e.status().message();
  ASSERT_TRUE(e->has_choice());
  const auto& c = e->choice();
  EXPECT_TRUE(c.kind == MotionKind::kPointTurn ? c.turn_angle > 0.0 : c.curvature > 0.0)
      << "chose curvature " << c.curvature << " turn " << c.turn_angle;
}

TEST(ArcEvaluatorFootprint, StraddleLetsALowRockPassBetweenTheWheelsNotUnderOne) {
  const ArcEvaluator rectangle = MakeEvaluator(FootprintOptions());
  const ArcEvaluator straddle = MakeEvaluator(FootprintOptions(false, true));
  const int straight = StraightIndex(straddle);
  ASSERT_GE(straight, 0);
  ASSERT_EQ(StraightIndex(rectangle), straight);
  // 1.5 m ahead on the centre line: inside the rectangle's sweep, between the wheel discs
  // (inner edges 0.5 - 0.148 m out, less the 0.15 m margin: 0.2 m).
  GoodnessMap low = KnownMap(), tall = KnownMap(), on_track = KnownMap();
  AddHazard(&low, 1.5, 0.0);
  SetRect(&tall, 1.4, 1.6, -0.1, 0.1, 200, 255,
          nav_core::kCellKnown | nav_core::kCellHazard | nav_core::kCellTall);
  AddHazard(&on_track, 1.5, 0.5);  // on the left wheel line
  auto rect_low = rectangle.Evaluate(low, Toward(4.0, 0.0));
  auto str_low = straddle.Evaluate(low, Toward(4.0, 0.0));
  auto str_tall = straddle.Evaluate(tall, Toward(4.0, 0.0));
  auto str_track = straddle.Evaluate(on_track, Toward(4.0, 0.0));
  ASSERT_TRUE(rect_low.ok() && str_low.ok() && str_tall.ok() && str_track.ok());
  EXPECT_EQ(rect_low->hazard[straight].goodness, 0);
  EXPECT_GT(str_low->hazard[straight].goodness, 0);
  EXPECT_EQ(str_tall->hazard[straight].goodness, 0);   // reaches the body
  EXPECT_EQ(str_track->hazard[straight].goodness, 0);  // under a wheel
}

TEST(ArcEvaluatorFootprint, StraddleSweepsTheRoverDescriptionsParts) {
  // Widen the track: the same centre-line rock now passes farther from the wheels, and a rock
  // on the old wheel line falls between them.
  GestaltOptions o = FootprintOptions(false, true);
  hwconfig::RoverDescription wide;
  wide.half_track = 0.8;
  o.contact_parts = wide.ContactParts();
  o.footprint_max_y = 0.9;
  o.footprint_min_y = -0.9;
  const ArcEvaluator ev = MakeEvaluator(o);
  const int straight = StraightIndex(ev);
  GoodnessMap m = KnownMap();
  AddHazard(&m, 1.5, 0.3);
  auto e = ev.Evaluate(m, Toward(4.0, 0.0));
  ASSERT_TRUE(e.ok());
  EXPECT_GT(e->hazard[straight].goodness, 0);
  GestaltOptions none = FootprintOptions(false, true);
  none.contact_parts.clear();
  EXPECT_FALSE(none.Validate().ok());
  GestaltOptions no_check;
  no_check.footprint_straddle = true;
  EXPECT_FALSE(no_check.Validate().ok());
}

}  // namespace footprint

}  // namespace
}  // namespace rover::apl::gestalt
