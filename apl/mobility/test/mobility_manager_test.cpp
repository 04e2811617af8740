// The mobility manager driven in-process: GESTALT injected, the kinematic FakeWorld of
// test/fake_world.hpp for locomotion and stereo, or scripted inputs for the fault cases.
#include "rover/apl/mobility/mobility_manager.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fake_world.hpp"
#include "rover/apl/gestalt/arc_evaluator.hpp"
#include "rover/apl/gestalt/terrain_map.hpp"
#include "rover/base/units.hpp"

namespace rover::apl::mobility {
namespace {

using testing::DriveReport;
using testing::FakeWorld;
using testing::MakeGestaltManager;
using testing::WorldOptions;
MobilityCommand Autonav(std::uint32_t id, double x, double y, double tol = 0.3) {
  MobilityCommand c;
  c.command_id = id;
  c.mode = Mode::kAutoNav;
  c.goal = Eigen::Vector3d(x, y, 0.0);
  c.tolerance = tol;
  return c;
}

MobilityCommand Directed(std::uint32_t id, Mode mode, std::vector<Primitive> prims) {
  MobilityCommand c;
  c.command_id = id;
  c.mode = mode;
  c.primitives = std::move(prims);
  return c;
}

Primitive Straight(double s) { return {PrimitiveKind::kStraight, 0.0, s, 0.0}; }
Primitive Turn(double a) { return {PrimitiveKind::kTurnInPlace, 0.0, 0.0, a}; }

PoseSample PoseAt(Time t, double x, double y, double heading = 0.0) {
  PoseSample p;
  p.stamp = t;
  p.site_from_rover.linear() =
      Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  p.site_from_rover.translation() = Eigen::Vector3d(x, y, 0.0);
  return p;
}

Time T(double s) { return Time::FromSeconds(s); }

// GESTALT's votes behind a selector that also keeps a scripted cost-to-go (lower the farther
// the position lies toward +y with `falls`, else the same everywhere) and may say it checks the
// drive length: what the manager does with a planner like ENav, on GESTALT's simple world.
class ScriptedCostToGo : public nav_core::ArcSelector {
 public:
  explicit ScriptedCostToGo(bool falls, bool checks_drive_length = false, double max_drive = 0.0,
                            bool checks_turns = false)
      : falls_(falls),
        checks_drive_length_(checks_drive_length),
        max_drive_(max_drive),
        checks_turns_(checks_turns) {
    auto arcs = gestalt::ArcEvaluator::Create(gestalt::GestaltOptions{});
    ROVER_DEMAND(arcs.ok());
    arcs_ = std::make_unique<gestalt::ArcEvaluator>(std::move(arcs).value());
  }
  Result<nav_core::ArcEvaluation> Evaluate(const nav_core::GoodnessMap& map,
                                           const nav_core::ArcRequest& request) const override {
    auto e = arcs_->Evaluate(map, request);
    if (e.ok()) e->max_drive = max_drive_;
    return e;
  }
  std::optional<double> CostToGo(const Eigen::Vector2d& goal,
                                 const Eigen::Vector2d& xy) const override {
    (void)goal;
    return falls_ ? 100.0 - xy.y() : 100.0;
  }
  bool ChecksDriveLength() const override { return checks_drive_length_; }
  bool ChecksTurns() const override { return checks_turns_; }

 private:
  bool falls_;
  bool checks_drive_length_;
  double max_drive_;
  bool checks_turns_;
  std::unique_ptr<gestalt::ArcEvaluator> arcs_;
};


// A manager on GESTALT's terrain map with `selector` (ScriptedCostToGo in these tests).
MobilityManager MakeManagerWith(const MobilityOptions& options,
                                std::unique_ptr<nav_core::ArcSelector> selector) {
  auto map = gestalt::TerrainMap::Create(gestalt::GestaltOptions{});
  ROVER_DEMAND(map.ok());
  auto created = MobilityManager::Create(
      options, std::make_unique<gestalt::TerrainMap>(std::move(map).value()), std::move(selector));
  ROVER_DEMAND(created.ok());
  return std::move(created).value();
}

// ---- driving in the fake world ---------------------------------------------------------------

TEST(MobilityManagerWorld, AutonavReachesGoalThroughRocks) {
  MobilityManager m = MakeGestaltManager();
  FakeWorld w(&m);
  // One rock right on the straight line, a gate of two behind it, and one more near the goal
  // (rocks forbid a disc of ~1.5 m radius: the rover's 1.3 m disc plus the rock).
  w.rocks().push_back({4.0, 0.0, 0.3, 0.45});
  w.rocks().push_back({7.5, 2.6, 0.25, 0.4});
  w.rocks().push_back({7.5, -2.6, 0.25, 0.4});
  w.rocks().push_back({10.0, 3.0, 0.2, 0.35});
  const MobilityStatus s = w.Run(Autonav(1, 12.0, 0.0), 2000.0);
  EXPECT_EQ(s.state, State::kSucceeded) << s.message << " at " << w.pose().x << ", " << w.pose().y;
  EXPECT_EQ(s.fault, Fault::kNone);
  EXPECT_LE(s.distance_to_goal, 0.3 + 1e-9);
  EXPECT_GT(w.min_rock_clearance(), 0.3);  // the rover centre never came near a rock
  EXPECT_GT(s.steps, 15u);
  EXPECT_GT(w.arc_vote_snapshots(), 0);
}

// The last step ends at the goal, not at the edge of its tolerance, with a planner that checks
// as far as the manager drives (ENav): 2.3 m ahead on open ground, three 0.5 m steps leave
// 0.8 m, within step_length + tolerance, so the fourth drives all of it (it used to drive 0.5 m
// and stop 0.3 m short, which the estimate's own error then adds to). Arc voting keeps MER's
// fixed steps: its arcs are judged by goodness, not checked over a length.
TEST(MobilityManagerWorld, TheLastStepEndsAtTheGoalNotAtTheEdgeOfItsTolerance) {
  for (const bool checks : {true, false}) {
    MobilityManager m =
        MakeManagerWith(MobilityOptions{}, std::make_unique<ScriptedCostToGo>(false, checks));
    FakeWorld w(&m);
    const MobilityStatus s = w.Run(Autonav(1, 2.3, 0.0, 0.5), 2000.0);
    ASSERT_EQ(s.state, State::kSucceeded) << s.message;
    ASSERT_FALSE(w.drives().empty());
    // Farther than step_length + tolerance, a step is step_length.
    EXPECT_NEAR(w.drives().front().distance, 0.5, 1e-9);
    if (checks) {
      EXPECT_LT(s.distance_to_goal, 0.05) << s.message;
      EXPECT_NEAR(w.drives().back().distance, 0.8, 0.05);
    } else {
      EXPECT_GT(s.distance_to_goal, 0.2) << s.message;
      EXPECT_NEAR(w.drives().back().distance, 0.5, 1e-9);
    }
  }
}

// A planner that clears less of its choice than the manager would drive (ArcEvaluation's
// max_drive: ENav's last step settled into the goal's tolerance) is driven no farther.
TEST(MobilityManagerWorld, NoStepRunsPastWhatThePlannerCleared) {
  MobilityManager m =
      MakeManagerWith(MobilityOptions{}, std::make_unique<ScriptedCostToGo>(false, true, 0.3));
  FakeWorld w(&m);
  const MobilityStatus s = w.Run(Autonav(1, 2.3, 0.0, 0.5), 2000.0);
  ASSERT_EQ(s.state, State::kSucceeded) << s.message;
  ASSERT_FALSE(w.drives().empty());
  for (const DriveCommand& d : w.drives()) {
    if (d.primitive != PrimitiveKind::kTurnInPlace) {
      EXPECT_LE(std::abs(d.distance), 0.3 + 1e-9);
    }
  }
}

TEST(MobilityManagerWorld, DriveWhileThinkingStandsStillLessThanStopAndGo) {
  double still[2] = {0, 0}, moving[2] = {0, 0};
  for (int think = 0; think < 2; ++think) {
    MobilityManager m = MakeGestaltManager();
    FakeWorld w(&m);
    w.Scatter(3, 10, 2.0, 9.0, -3.0, 3.0, 0.2, 0.35, {{0, 0}, {10, 0}}, 1.6);
    MobilityCommand c = Autonav(1, 10.0, 0.0);
    c.think = think ? ThinkMode::kDriveWhileThinking : ThinkMode::kStopAndGo;
    const MobilityStatus s = w.Run(c, 2000.0);
    ASSERT_EQ(s.state, State::kSucceeded) << s.message;
    still[think] = m.counters().still_s;
    moving[think] = m.counters().moving_s;
    if (think) {
      EXPECT_GT(m.counters().images_while_driving, 0);
    } else {
      EXPECT_EQ(m.counters().images_while_driving, 0);
    }
  }
  // The figures, for the record (simulated seconds; the ratio is what is asserted).
  std::printf(
      "stop-and-go: still %.1f s, moving %.1f s (%.0f %% still); drive while thinking: "
      "still %.1f s, moving %.1f s (%.0f %% still)\n",
      still[0], moving[0], 100.0 * still[0] / (still[0] + moving[0]), still[1], moving[1],
      100.0 * still[1] / (still[1] + moving[1]));
  EXPECT_LT(still[1], 0.5 * still[0])
      << "stop-and-go still " << still[0] << " s, moving " << moving[0] << " s; thinking still "
      << still[1] << " s, moving " << moving[1] << " s";
}

TEST(MobilityManagerWorld, OpenGroundSkipsSomeImaging) {
  MobilityOptions o;
  o.drive_while_thinking = false;
  MobilityManager m = MakeGestaltManager(o);
  FakeWorld w(&m);
  const MobilityStatus s = w.Run(Autonav(1, 8.0, 0.0), 1000.0);
  ASSERT_EQ(s.state, State::kSucceeded) << s.message;
  EXPECT_GT(m.counters().images_skipped, 0);
  EXPECT_LT(s.images, s.steps);
}

TEST(MobilityManagerWorld, GoalBehindTheRoverBacksOrTurns) {
  MobilityManager m = MakeGestaltManager();
  FakeWorld w(&m);
  const MobilityStatus s = w.Run(Autonav(1, -3.0, 0.5), 1000.0);
  EXPECT_EQ(s.state, State::kSucceeded) << s.message;
}

// GESTALT's votes as in short_autonav seed 4, whose goal lay inside the rover's tightest turning
// circle: the best forward arc wins over every turn in place (there, backing arcs and arcs
// circled the goal for 9.7 m of driving toward a goal 3 m away).
class PreferArcs : public nav_core::ArcSelector {
 public:
  Result<nav_core::ArcEvaluation> Evaluate(const nav_core::GoodnessMap& map,
                                           const nav_core::ArcRequest& request) const override {
    auto e = gestalt_.Evaluate(map, request);
    if (!e.ok() || !e->has_choice()) return e;
    int best = -1;
    for (std::size_t k = 0; k < e->candidates.size(); ++k) {
      const nav_core::Candidate& c = e->candidates[k];
      if (c.kind != nav_core::MotionKind::kArc || c.direction < 0 || e->merged[k].goodness == 0) {
        continue;
      }
      if (best < 0 || e->merged[k].goodness > e->merged[static_cast<std::size_t>(best)].goodness) {
        best = static_cast<int>(k);
      }
    }
    if (best >= 0) e->chosen = best;
    return e;
  }

 private:
  gestalt::ArcEvaluator gestalt_ = std::move(gestalt::ArcEvaluator::Create({})).value();
};

MobilityManager MakePreferArcsManager() {
  auto map = gestalt::TerrainMap::Create({});
  ROVER_DEMAND(map.ok());
  auto m = MobilityManager::Create(MobilityOptions{},
                                   std::make_unique<gestalt::TerrainMap>(std::move(map).value()),
                                   std::make_unique<PreferArcs>());
  ROVER_DEMAND(m.ok());
  return std::move(m).value();
}

// A goal 0.94 m away, 58 degrees to the left, lies inside the tightest turning circle (1.1 m
// radius): no arc reaches it. The rover turns in place to face it and drives there.
TEST(MobilityManagerWorld, AGoalInsideTheTurningCircleIsFacedByATurnInPlace) {
  MobilityManager m = MakePreferArcsManager();
  FakeWorld w(&m);
  const MobilityStatus s = w.Run(Autonav(1, 0.5, 0.8), 1000.0);
  ASSERT_EQ(s.state, State::kSucceeded) << s.message;
  EXPECT_EQ(m.counters().goal_facing_turns, 1);
  ASSERT_FALSE(w.drives().empty());
  EXPECT_EQ(w.drives().front().primitive, msg::DrivePrimitive::kTurnInPlace);
  EXPECT_NEAR(w.drives().front().angle, std::atan2(0.8, 0.5), 1e-6);
  EXPECT_LE(s.steps, 3u);
  EXPECT_LT(m.counters().distance, 1.5);
}

// A goal the tightest arc reaches is driven to by arcs: no turn to face it.
TEST(MobilityManagerWorld, AGoalOutsideTheTurningCircleIsNotFacedByATurn) {
  MobilityManager m = MakePreferArcsManager();
  FakeWorld w(&m);
  const MobilityStatus s = w.Run(Autonav(1, 2.0, 1.0), 1000.0);
  ASSERT_EQ(s.state, State::kSucceeded) << s.message;
  EXPECT_EQ(m.counters().goal_facing_turns, 0);
}

TEST(MobilityManagerWorld, GuardedDriveAtARockIsVetoed) {
  MobilityManager m = MakeGestaltManager();
  FakeWorld w(&m);
  w.rocks().push_back({3.5, 0.0, 0.35, 0.5});
  const MobilityStatus s = w.Run(Directed(1, Mode::kGuarded, {Straight(6.0)}), 1000.0);
  EXPECT_EQ(s.state, State::kFailed);
  EXPECT_EQ(s.fault, Fault::kNoPath) << s.message;
  EXPECT_EQ(s.fault_class, FaultClass::kGoalError);
  EXPECT_NE(s.message.find("vetoed"), std::string::npos) << s.message;
  EXPECT_FALSE(s.motion_error_latched);
  EXPECT_LT(w.pose().x, 3.5 - 0.35 - 0.3);  // halted before the rock
  EXPECT_GE(w.pose().x, 0.9);               // but drove the safe pieces first
}

TEST(MobilityManagerWorld, GuardedDriveOnClearGroundRuns) {
  MobilityManager m = MakeGestaltManager();
  FakeWorld w(&m);
  const MobilityStatus s =
      w.Run(Directed(1, Mode::kGuarded, {Straight(2.5), Turn(kPi / 2)}), 1000.0);
  EXPECT_EQ(s.state, State::kSucceeded) << s.message;
  EXPECT_NEAR(w.pose().x, 2.5, 1e-6);
  EXPECT_NEAR(w.pose().heading, kPi / 2, 1e-6);
}

TEST(MobilityManagerWorld, GuardedArcTurnsBlindThenChecksTheSegment) {
  MobilityManager m = MakeGestaltManager();
  FakeWorld w(&m);
  w.rocks().push_back({0.0, 2.5, 0.35, 0.5});  // to the left, where the turn points
  const MobilityStatus s =
      w.Run(Directed(1, Mode::kGuardedArc, {Turn(kPi / 2), Straight(3.0)}), 1000.0);
  EXPECT_EQ(s.fault, Fault::kNoPath) << s.message;
  EXPECT_NEAR(w.pose().heading, kPi / 2, 1e-6);  // the turn ran
  EXPECT_LT(w.pose().y, 2.5 - 0.35 - 0.3);
}

TEST(MobilityManagerWorld, KeepOutZoneHaltsBeforeIt) {
  MobilityManager m = MakeGestaltManager();
  FakeWorld w(&m);
  MobilityCommand c = Autonav(1, 10.0, 0.0);
  c.keep_out.push_back({"dune", {{5.0, -4.0}, {6.0, -4.0}, {6.0, 4.0}, {5.0, 4.0}}});
  const MobilityStatus s = w.Run(c, 1000.0);
  EXPECT_EQ(s.fault, Fault::kKeepOut) << s.message;
  EXPECT_EQ(s.fault_class, FaultClass::kGoalError);
  EXPECT_NE(s.message.find("dune"), std::string::npos);
  EXPECT_LT(w.pose().x, 5.0 - m.options().keepout_margin + 1e-6);
  EXPECT_GT(w.pose().x, 3.0);
}

TEST(MobilityManagerWorld, BlindGoToWaypointIgnoresKeepOutOnlyIfClear) {
  MobilityManager m = MakeGestaltManager();
  FakeWorld w(&m);
  MobilityCommand c = Autonav(1, 6.0, 3.0);
  c.mode = Mode::kGoToWaypoint;
  const MobilityStatus s = w.Run(c, 1000.0);
  EXPECT_EQ(s.state, State::kSucceeded) << s.message;
  EXPECT_TRUE(w.range_requests().empty());  // blind: no imaging
}

TEST(MobilityManagerWorld, NoPathWhenBoxedIn) {
  MobilityManager m = MakeGestaltManager();
  FakeWorld w(&m);
  // A rock wall wrapped close around the rover: its own cell is unsafe, so every candidate is.
  for (int i = 0; i < 24; ++i) {
    const double a = 2.0 * kPi * i / 24;
    w.rocks().push_back({1.0 * std::cos(a), 1.0 * std::sin(a), 0.2, 0.4});
  }
  const MobilityStatus s = w.Run(Autonav(1, 8.0, 0.0), 1000.0);
  EXPECT_EQ(s.fault, Fault::kNoPath) << s.message;
  EXPECT_EQ(s.fault_class, FaultClass::kGoalError);
  EXPECT_LT(std::hypot(w.pose().x, w.pose().y), 0.05);  // never moved
}

TEST(MobilityManagerWorld, CulDeSacEndsNoProgress) {
  MobilityOptions o;
  o.progress_steps = 8;
  o.min_progress = 0.5;
  MobilityManager m = MakeGestaltManager(o);
  FakeWorld w(&m);
  // A U of rocks opening toward the rover, goal beyond its closed end.
  w.AddWall({5.0, -4.0}, {5.0, 4.0}, 0.3, 0.2, 0.5);
  w.AddWall({0.5, -4.0}, {5.0, -4.0}, 0.3, 0.2, 0.5);
  w.AddWall({0.5, 4.0}, {5.0, 4.0}, 0.3, 0.2, 0.5);
  const MobilityStatus s = w.Run(Autonav(1, 12.0, 0.0), 3000.0);
  EXPECT_EQ(s.state, State::kFailed) << s.message;
  EXPECT_TRUE(s.fault == Fault::kNoProgress || s.fault == Fault::kNoPath) << s.message;
  EXPECT_EQ(s.fault_class, FaultClass::kGoalError);
  EXPECT_GT(w.min_rock_clearance(), 0.3);
}

// A rover whose pose never moves (100 % slip) fails every NOPROGRESS window. MER's limit-cycle
// turn comes first: with the goal ahead, 90 deg toward the better forward arcs (left on flat
// ground, where the straight arc is best), and the window starts again; after the last turn
// the command ends NOPROGRESS, saying how many turns it took.
TEST(MobilityManagerWorld, NoProgressTurnsInPlaceBeforeItGivesUp) {
  for (const int turns : {0, 2}) {
    MobilityOptions o;
    o.progress_steps = 4;
    o.limit_cycle_turns = turns;
    MobilityManager m = MakeGestaltManager(o);
    FakeWorld w(&m);
    w.tamper_pose = [](PoseSample* p) { p->site_from_rover.translation().setZero(); };
    const MobilityStatus s = w.Run(Autonav(1, 8.0, 0.0), 2000.0);
    EXPECT_EQ(s.fault, Fault::kNoProgress) << s.message;
    std::vector<double> angles;
    for (const DriveCommand& d : w.drives()) {
      if (d.primitive == PrimitiveKind::kTurnInPlace) angles.push_back(d.angle);
    }
    ASSERT_EQ(static_cast<int>(angles.size()), turns) << s.message;
    if (turns > 0) {
      EXPECT_NEAR(angles[0], o.limit_cycle_turn, 1e-9);  // the goal was ahead: 90 deg left
      // The arcs driven since point the rover off the goal: the second turn faces it.
      EXPECT_GE(std::abs(angles[1]), o.limit_cycle_min_bearing);
    }
    EXPECT_EQ(s.message.find("limit-cycle turn") != std::string::npos, turns > 0) << s.message;
  }
}

// A planner that checks its own turns (ENav) gets no limit-cycle turn: the same stuck rover
// ends NOPROGRESS at the first window with no turn in place the planner did not choose, while
// the same planner not saying so gets the manager's turns.
TEST(MobilityManagerWorld, APlannerThatChecksItsTurnsGetsNoTurnOfTheManagers) {
  for (const bool checks_turns : {false, true}) {
    MobilityOptions o;
    o.progress_steps = 4;
    o.limit_cycle_turns = 2;
    MobilityManager m = MakeManagerWith(
        o, std::make_unique<ScriptedCostToGo>(false, false, 0.0, checks_turns));
    FakeWorld w(&m);
    w.tamper_pose = [](PoseSample* p) { p->site_from_rover.translation().setZero(); };
    const MobilityStatus s = w.Run(Autonav(1, 8.0, 0.0), 2000.0);
    EXPECT_EQ(s.fault, Fault::kNoProgress) << s.message;
    int turns = 0;
    for (const DriveCommand& d : w.drives()) {
      turns += d.primitive == PrimitiveKind::kTurnInPlace ? 1 : 0;
    }
    EXPECT_EQ(turns, checks_turns ? 0 : 2) << s.message;
    EXPECT_EQ(s.message.find("limit-cycle turn") != std::string::npos, !checks_turns)
        << s.message;
  }
}

// The NOPROGRESS window counts progress along the planner's cost-to-go too: a detour that takes
// the rover no nearer the goal in a straight line for many steps, yet runs down the cost-to-go
// (here the reported pose walks sideways, +y, as the rover drives), is not stopped; a planner
// whose cost-to-go stands still is, and the message gives both figures.
TEST(MobilityManagerWorld, ProgressCountsAlongThePlannersCostToGo) {
  for (const bool falls : {true, false}) {
    MobilityOptions o;
    o.progress_steps = 4;
    o.limit_cycle_turns = 0;
    o.max_steps = 12;
    MobilityManager m = MakeManagerWith(o, std::make_unique<ScriptedCostToGo>(falls));
    FakeWorld w(&m);
    // The reported position moves along +y as far as the rover drives along +x: the straight
    // distance to a goal ahead on +x grows.
    w.tamper_pose = [](PoseSample* p) {
      const Eigen::Vector3d t = p->site_from_rover.translation();
      p->site_from_rover.translation() = Eigen::Vector3d(0.0, t.x(), t.z());
    };
    const MobilityStatus s = w.Run(Autonav(1, 8.0, 0.0), 2000.0);
    EXPECT_EQ(s.fault, Fault::kNoProgress) << s.message;
    if (falls) {
      EXPECT_NE(s.message.find("max_steps"), std::string::npos) << s.message;
      EXPECT_EQ(s.steps, 12u) << s.message;
    } else {
      EXPECT_NE(s.message.find("cost-to-go from 100 to 100 m"), std::string::npos) << s.message;
      EXPECT_LT(s.steps, 12u) << s.message;
    }
  }
}

TEST(MobilityManagerWorld, ImagesThatStopArrivingAreImgAndLatch) {
  MobilityManager m = MakeGestaltManager();
  WorldOptions wo;
  wo.deliver_images = false;
  FakeWorld w(&m, wo);
  const MobilityStatus s = w.Run(Autonav(1, 8.0, 0.0), 100.0);
  EXPECT_EQ(s.fault, Fault::kImg) << s.message;
  EXPECT_EQ(s.fault_class, FaultClass::kMotionError);
  EXPECT_TRUE(s.motion_error_latched);
  EXPECT_NE(s.message.find("image_timeout_s"), std::string::npos);
  // Re-sent twice (image_resend_s 4 s, max_image_resends 2) before the 10 s ran out.
  EXPECT_NE(s.message.find("sent 3 times"), std::string::npos) << s.message;
  EXPECT_EQ(w.range_requests().size(), 3u);
  EXPECT_TRUE(w.drives().empty());
}

// A request lost to a restarted dl-stereo (it reads only what is written after it started) is
// asked again and the drive goes on; before, the run ended IMG after image_timeout_s.
TEST(MobilityManagerWorld, ALostRangeRequestIsSentAgain) {
  MobilityManager m = MakeGestaltManager();
  WorldOptions wo;
  wo.lose_requests = 1;
  FakeWorld w(&m, wo);
  const MobilityStatus s = w.Run(Autonav(1, 8.0, 0.0), 400.0);
  EXPECT_EQ(s.state, State::kSucceeded) << s.message;
  ASSERT_GE(w.range_requests().size(), 2u);
  EXPECT_NE(w.range_requests()[0].request_id, w.range_requests()[1].request_id);
  EXPECT_EQ(w.range_requests()[0].camera, w.range_requests()[1].camera);
  EXPECT_FALSE(w.drives().empty());
}

TEST(MobilityManagerWorld, WrongCameraAndAllInvalidAreImg) {
  for (int variant = 0; variant < 2; ++variant) {
    MobilityManager m = MakeGestaltManager();
    FakeWorld w(&m);
    w.tamper_image = [variant](nav_core::RangeScan* scan, CameraId* cam) {
      if (variant == 0) *cam = CameraId::kNavcam;
      if (variant == 1) std::fill(scan->valid.begin(), scan->valid.end(), 0);
    };
    const MobilityStatus s = w.Run(Autonav(1, 8.0, 0.0), 100.0);
    EXPECT_EQ(s.fault, Fault::kImg) << s.message;
    EXPECT_NE(s.message.find(variant == 0 ? "navcam" : "invalid"), std::string::npos) << s.message;
    EXPECT_TRUE(w.drives().empty());
  }
}

TEST(MobilityManagerWorld, PoseThatStopsOrJumpsIsSapp) {
  {
    MobilityManager m = MakeGestaltManager();
    FakeWorld w(&m);
    int n = 0;
    w.tamper_pose = [&n](PoseSample* p) {
      if (++n > 30) p->site_from_rover.translation().x() += 2.0;  // a 2 m jump mid-drive
    };
    const MobilityStatus s = w.Run(Directed(1, Mode::kDirected, {Straight(3.0)}), 100.0);
    EXPECT_EQ(s.fault, Fault::kSapp) << s.message;
    EXPECT_NE(s.message.find("jumped"), std::string::npos);
    EXPECT_TRUE(s.motion_error_latched);
    ASSERT_FALSE(w.drives().empty());
    EXPECT_EQ(w.drives().back().primitive, PrimitiveKind::kStop);
  }
  {
    MobilityManager m = MakeGestaltManager();
    WorldOptions wo;
    FakeWorld w(&m, wo);
    int n = 0;
    w.tamper_pose = [&n](PoseSample* p) {
      if (++n > 20) p->stamp = Time::FromSeconds(2.0);  // stuck: no newer sample
    };
    const MobilityStatus s = w.Run(Directed(1, Mode::kDirected, {Straight(3.0)}), 100.0);
    EXPECT_EQ(s.fault, Fault::kSapp) << s.message;
    EXPECT_NE(s.message.find("pose_stale_s"), std::string::npos);
  }
}

TEST(MobilityManagerWorld, VisOdomSplitsStepsAndCountsFailures) {
  MobilityOptions o;
  o.max_visodom_failures = 1;
  MobilityManager m = MakeGestaltManager(o);
  FakeWorld w(&m);
  // No VO results arrive: each step waits visodom_timeout_s and counts as failed.
  const MobilityStatus s = w.Run(Directed(1, Mode::kVisOdom, {Straight(3.0)}), 1000.0);
  EXPECT_EQ(s.fault, Fault::kVisOdom) << s.message;
  EXPECT_EQ(s.fault_class, FaultClass::kGoalError);
  EXPECT_EQ(w.drives().size(), 2u);  // two 0.6 m steps, then the second failure ends it
  EXPECT_NEAR(w.drives()[0].distance, 0.6, 1e-9);
}

// ---- scripted inputs -------------------------------------------------------------------------

class MobilityManagerScripted : public ::testing::Test {
 protected:
  MobilityManager m_ = MakeGestaltManager();
  MobilityOutput Cmd(const MobilityCommand& c, double t) {
    m_.OnPose(PoseAt(T(t), 0, 0), T(t));
    return m_.OnCommand(c, T(t));
  }
  // Runs a directed 1 m drive and reports its drive command back with `state` / `term`.
  MobilityStatus FailDrive(DriveState state, DriveTermination term, double t) {
    MobilityOutput out = Cmd(Directed(10, Mode::kDirected, {Straight(1.0)}), t);
    EXPECT_EQ(out.drives.size(), 1u);
    m_.OnPose(PoseAt(T(t + 1), 0.1, 0), T(t + 1));
    out = m_.OnDriveStatus(DriveReport(out.drives[0].command_id, state, term, 0.1, "x"), T(t + 1));
    EXPECT_FALSE(out.statuses.empty());
    return out.statuses.back();
  }
  // Locomotion's report that drive `id` is still running at `t` (it reports every cycle).
  void StillDriving(std::uint32_t id, double t) {
    m_.OnDriveStatus(DriveReport(id, DriveState::kDriving, DriveTermination::kNominal, 0.0, ""),
                     T(t));
  }
  // The command ended with motion error `fault`, latched, and `out` stopped the drive.
  void ExpectStoppedWith(Fault fault, const MobilityOutput& out) {
    EXPECT_FALSE(m_.busy());
    EXPECT_EQ(m_.status().fault, fault) << m_.status().message;
    EXPECT_EQ(m_.status().fault_class, FaultClass::kMotionError);
    EXPECT_TRUE(m_.motion_error_latched());
    ASSERT_EQ(out.drives.size(), 1u);
    EXPECT_EQ(out.drives[0].primitive, PrimitiveKind::kStop);
  }
};

TEST_F(MobilityManagerScripted, DriveTerminationsMapToMotionErrorsThatLatch) {
  const std::pair<DriveTermination, Fault> cases[] = {
      {DriveTermination::kTilt, Fault::kTilt},
      {DriveTermination::kSuspension, Fault::kSuspension},
      {DriveTermination::kMotorStall, Fault::kMot},
      {DriveTermination::kMotorCurrent, Fault::kMot},
      {DriveTermination::kMotorFault, Fault::kMot},
      {DriveTermination::kTimeout, Fault::kDriveTimeout},
      {DriveTermination::kStaleSensor, Fault::kSapp},
  };
  double t = 0;
  for (const auto& [term, fault] : cases) {
    const MobilityStatus s = FailDrive(DriveState::kFailed, term, t += 10);
    EXPECT_EQ(s.fault, fault) << msg::MobilityFaultName(fault);
    EXPECT_EQ(s.fault_class, FaultClass::kMotionError);
    EXPECT_TRUE(s.motion_error_latched);
    // Every motion command is refused, with the latched fault, until CLEAR_FAULT.
    MobilityOutput out = Cmd(Autonav(11, 3, 0), t += 1);
    ASSERT_EQ(out.statuses.size(), 1u);
    EXPECT_EQ(out.statuses[0].state, State::kRejected);
    EXPECT_EQ(out.statuses[0].fault, fault);
    EXPECT_TRUE(out.drives.empty() && out.range_requests.empty());
    MobilityCommand clear;
    clear.command_id = 12;
    clear.mode = Mode::kClearFault;
    out = Cmd(clear, t += 1);
    EXPECT_EQ(out.statuses.back().state, State::kSucceeded);
    EXPECT_FALSE(m_.motion_error_latched());
  }
}

TEST_F(MobilityManagerScripted, GoalErrorsFromLocomotionLeaveTheRoverReady) {
  MobilityStatus s = FailDrive(DriveState::kRejected, DriveTermination::kRejectedBusy, 1);
  EXPECT_EQ(s.fault, Fault::kArb);
  EXPECT_EQ(s.fault_class, FaultClass::kGoalError);
  EXPECT_FALSE(s.motion_error_latched);
  s = FailDrive(DriveState::kFailed, DriveTermination::kStopCommand, 10);
  EXPECT_EQ(s.fault, Fault::kStopped);
  s = FailDrive(DriveState::kRejected, DriveTermination::kRejectedInvalid, 20);
  EXPECT_EQ(s.fault, Fault::kBadCommand);
  const MobilityOutput out = Cmd(Directed(13, Mode::kDirected, {Straight(1.0)}), 30);
  EXPECT_EQ(out.drives.size(), 1u);  // still ready
}

TEST_F(MobilityManagerScripted, DriveWatchdogStopsAndLatches) {
  MobilityOutput out = Cmd(Directed(1, Mode::kDirected, {Straight(1.0)}), 0);
  ASSERT_EQ(out.drives.size(), 1u);
  const std::uint32_t drive = out.drives[0].command_id;
  for (double t = 0.5; t < 200; t += 0.5) {
    m_.OnPose(PoseAt(T(t), 0, 0), T(t));
    // Locomotion reports the drive running but it never ends.
    StillDriving(drive, t);
    out = m_.Step(T(t));
    if (!m_.busy()) break;
  }
  ExpectStoppedWith(Fault::kDriveTimeout, out);
}

TEST_F(MobilityManagerScripted, BusyRejectsTheSecondCommandAndTheFirstContinues) {
  MobilityOutput out = Cmd(Directed(1, Mode::kDirected, {Straight(1.0)}), 0);
  ASSERT_EQ(out.drives.size(), 1u);
  const std::uint32_t drive = out.drives[0].command_id;
  out = Cmd(Autonav(2, 5, 0), 1);
  ASSERT_EQ(out.statuses.size(), 2u);
  EXPECT_EQ(out.statuses[0].command_id, 2u);
  EXPECT_EQ(out.statuses[0].state, State::kRejected);
  EXPECT_EQ(out.statuses[0].fault, Fault::kBusy);
  EXPECT_EQ(out.statuses[0].fault_class, FaultClass::kGoalError);
  EXPECT_EQ(out.statuses[1].command_id, 1u);  // the latched status stays the running one
  EXPECT_EQ(out.statuses[1].state, State::kRunning);
  EXPECT_TRUE(out.drives.empty());
  m_.OnPose(PoseAt(T(20), 0.4, 0), T(20));
  out = m_.OnDriveStatus(DriveReport(drive, DriveState::kDone, DriveTermination::kNominal, 1.0, ""),
                        T(20));
  ASSERT_FALSE(out.statuses.empty());
  EXPECT_EQ(out.statuses.back().command_id, 1u);
  EXPECT_EQ(out.statuses.back().state, State::kSucceeded);
  EXPECT_DOUBLE_EQ(out.statuses.back().distance_driven, 1.0);
}

TEST(MobilityArcVotes, SnapshotBecomesTheMessageValue) {
  ArcVotesSnapshot s;
  s.stamp = T(3);
  s.command_id = 4;
  s.step = 2;
  s.site_from_rover.translation() = Eigen::Vector3d(1, 2, 0);
  s.evaluation.candidates = {{nav_core::MotionKind::kArc, 0.5, -1, 2.0, 0.0},
                             {nav_core::MotionKind::kPointTurn, 0.0, 1, 0.0, 1.5}};
  s.evaluation.hazard = {{200, 255}, {100, 255}};
  s.evaluation.waypoint = {{10, 192}, {300, 192}};
  s.evaluation.merged = {{-5, 255}};  // shorter than the candidates: 0 for the rest
  s.evaluation.chosen = 1;
  const msg::ArcVotes a = ArcVotesOf(s);
  EXPECT_EQ(a.stamp, T(3));
  EXPECT_EQ(a.command_id, 4u);
  EXPECT_EQ(a.step, 2u);
  EXPECT_EQ(a.rover_pose.translation(), Eigen::Vector3d(1, 2, 0));
  ASSERT_EQ(a.votes.size(), 2u);
  EXPECT_EQ(a.votes[0].kind, msg::CandidateKind::kArc);
  EXPECT_EQ(a.votes[0].direction, -1);
  EXPECT_EQ(a.votes[0].curvature, 0.5);
  EXPECT_EQ(a.votes[0].hazard, 200);
  EXPECT_EQ(a.votes[0].merged, 0);  // clamped to a byte
  EXPECT_EQ(a.votes[1].kind, msg::CandidateKind::kPointTurn);
  EXPECT_EQ(a.votes[1].turn_angle, 1.5);
  EXPECT_EQ(a.votes[1].waypoint, 255);  // clamped to a byte
  EXPECT_EQ(a.votes[1].merged, 0);
  EXPECT_EQ(a.chosen, 1);
}

// dl/relative_pose reaches the manager whole: only visual-odometry results end a VO wait.
TEST(MobilityManagerVisOdom, OnlyVisualOdometryResultsCountAndNotConvergedFails) {
  for (const bool converged : {true, false}) {
    MobilityOptions o;
    o.max_visodom_failures = 0;
    MobilityManager m = MakeGestaltManager(o);
    m.OnPose(PoseAt(T(0), 0, 0), T(0));
    MobilityOutput out = m.OnCommand(Directed(1, Mode::kVisOdom, {Straight(0.3)}), T(0));
    ASSERT_EQ(out.drives.size(), 1u);
    m.OnPose(PoseAt(T(10), 0.3, 0), T(10));
    out = m.OnDriveStatus(DriveReport(out.drives[0].command_id, DriveState::kDone,
                                      DriveTermination::kNominal, 0.3, ""),
                          T(10));
    ASSERT_TRUE(m.busy());  // waiting for visual odometry
    RelativePose wheels;
    wheels.source = msg::MotionSource::kWheelOdometry;
    wheels.t_to = T(10.5);
    wheels.status = msg::RelativePoseStatus::kNotConverged;
    EXPECT_TRUE(m.OnVisOdom(wheels, T(10.5)).empty());
    EXPECT_TRUE(m.busy());
    m.OnPose(PoseAt(T(11), 0.3, 0), T(11));
    RelativePose vo;
    vo.source = msg::MotionSource::kVisualOdometry;
    vo.t_to = T(10.5);
    vo.status = converged ? msg::RelativePoseStatus::kConverged
                          : msg::RelativePoseStatus::kNotConverged;
    out = m.OnVisOdom(vo, T(11));
    ASSERT_FALSE(out.statuses.empty());
    if (converged) {
      EXPECT_EQ(out.statuses.back().state, State::kSucceeded) << out.statuses.back().message;
    } else {
      EXPECT_EQ(out.statuses.back().fault, Fault::kVisOdom) << out.statuses.back().message;
    }
  }
}

TEST_F(MobilityManagerScripted, StopEndsTheRunningCommandStopped) {
  MobilityOutput out = Cmd(Directed(1, Mode::kDirected, {Straight(1.0)}), 0);
  MobilityCommand stop;
  stop.command_id = 2;
  stop.mode = Mode::kStop;
  out = Cmd(stop, 1);
  ASSERT_EQ(out.statuses.size(), 2u);
  EXPECT_EQ(out.statuses[0].command_id, 2u);
  EXPECT_EQ(out.statuses[0].state, State::kSucceeded);
  EXPECT_EQ(out.statuses[1].command_id, 1u);
  EXPECT_EQ(out.statuses[1].fault, Fault::kStopped);
  EXPECT_EQ(out.statuses[1].fault_class, FaultClass::kGoalError);
  ASSERT_EQ(out.drives.size(), 1u);
  EXPECT_EQ(out.drives[0].primitive, PrimitiveKind::kStop);
  EXPECT_FALSE(m_.busy());
}

TEST_F(MobilityManagerScripted, BadCommandsAreRejectedNamingTheFieldAndNothingMoves) {
  auto expect_bad = [&](MobilityCommand c, const std::string& field) {
    const MobilityOutput out = Cmd(c, 1);
    ASSERT_EQ(out.statuses.size(), 1u) << field;
    EXPECT_EQ(out.statuses[0].state, State::kRejected) << field;
    EXPECT_EQ(out.statuses[0].fault, Fault::kBadCommand) << field;
    EXPECT_EQ(out.statuses[0].fault_class, FaultClass::kGoalError) << field;
    EXPECT_NE(out.statuses[0].message.find(field), std::string::npos) << out.statuses[0].message;
    EXPECT_TRUE(out.drives.empty() && out.range_requests.empty()) << field;
    EXPECT_FALSE(m_.busy());
  };
  expect_bad(Autonav(1, std::nan(""), 0), "goal.x is nan");
  expect_bad(Autonav(1, 5000, 0), "max_goal_distance_m");
  expect_bad(Autonav(1, 5, 0, -1.0), "tolerance = -1");
  MobilityCommand c = Autonav(1, 5, 0);
  c.mode = static_cast<Mode>(42);
  expect_bad(c, "mode = 42");
  c = Autonav(1, 5, 0);
  c.keep_out.push_back({"bowtie", {{0, 0}, {2, 2}, {2, 0}, {0, 1}}});
  expect_bad(c, "keep_out[0] ('bowtie').vertices: edges 0 and 2 cross");
  c = Autonav(1, 5, 0);
  c.keep_out.push_back({"line", {{3, 0}, {4, 0}}});
  expect_bad(c, "2 vertices");
  expect_bad(Directed(1, Mode::kGuarded, {}), "primitives: 0 given");
  expect_bad(Directed(1, Mode::kDirected, {{PrimitiveKind::kArc, 3.0, 1.0, 0.0}}),
             "primitives[0].curvature = 3");
  expect_bad(Directed(1, Mode::kDirected, {Straight(std::nan(""))}),
             "primitives[0].distance is nan");
  c = Autonav(1, 5, 0);
  c.lmst_end_h = 30;
  expect_bad(c, "lmst_end_h = 30");
  c = Autonav(1, 5, 0);
  c.mode = Mode::kLongTraverse;
  expect_bad(c, "not supported");
}

TEST_F(MobilityManagerScripted, SoftwareEnableOffIsAcm) {
  m_.SetSoftwareEnable(false);
  const MobilityOutput out = Cmd(Autonav(1, 5, 0), 1);
  EXPECT_EQ(out.statuses.back().fault, Fault::kAcm);
  EXPECT_EQ(out.statuses.back().fault_class, FaultClass::kGoalError);
  EXPECT_TRUE(out.range_requests.empty() && out.drives.empty());
}

TEST_F(MobilityManagerScripted, NoPoseIsSappAtCommandTime) {
  const MobilityOutput out = m_.OnCommand(Autonav(1, 5, 0), T(0));
  EXPECT_EQ(out.statuses.back().fault, Fault::kSapp);
  EXPECT_NE(out.statuses.back().message.find("no dl/pose"), std::string::npos);
  EXPECT_TRUE(m_.motion_error_latched());
}

TEST_F(MobilityManagerScripted, NonFinitePoseWhileDrivingIsSapp) {
  MobilityOutput out = Cmd(Directed(1, Mode::kDirected, {Straight(1.0)}), 0);
  PoseSample p = PoseAt(T(1), 0, 0);
  p.site_from_rover.translation().y() = std::nan("");
  out = m_.OnPose(p, T(1));
  ASSERT_FALSE(out.statuses.empty());
  EXPECT_EQ(out.statuses.back().fault, Fault::kSapp);
  EXPECT_NE(out.statuses.back().message.find("not finite"), std::string::npos);
}

// ---- input faults (issue 12) -----------------------------------------------------------------

TEST_F(MobilityManagerScripted, DriveStatusThatStopsArrivingIsMotAndStops) {
  MobilityOutput out = Cmd(Directed(1, Mode::kDirected, {Straight(1.0)}), 0);
  ASSERT_EQ(out.drives.size(), 1u);
  const std::uint32_t drive = out.drives[0].command_id;
  double ended = -1;
  for (double t = 0.1; t < 60; t += 0.1) {
    m_.OnPose(PoseAt(T(t), 0, 0), T(t));
    if (t < 1.0) {  // reports for a second, then silence
      m_.OnDriveStatus(
          DriveReport(drive, DriveState::kDriving, DriveTermination::kNominal, 0.01, ""), T(t));
    }
    out = m_.Step(T(t));
    if (!m_.busy()) {
      ended = t;
      break;
    }
  }
  ASSERT_GT(ended, 0.0);
  // The last report came at 0.9 s; drive_status_timeout_s = 2 s.
  EXPECT_NEAR(ended, 0.9 + m_.options().drive_status_timeout_s, 0.15);
  ExpectStoppedWith(Fault::kMot, out);
  EXPECT_NE(m_.status().message.find("no dl/drive_status"), std::string::npos);
}

TEST_F(MobilityManagerScripted, RejectedDriveStatusesDoNotKeepTheDriveAliveAndAreNamed) {
  MobilityOutput out = Cmd(Directed(1, Mode::kDirected, {Straight(1.0)}), 0);
  ASSERT_EQ(out.drives.size(), 1u);
  for (double t = 0.1; t < 10 && m_.busy(); t += 0.1) {
    m_.OnPose(PoseAt(T(t), 0, 0), T(t));
    out = m_.OnInputRejected(MobilityInput::kDriveStatus, "state = 9 is not a DriveState", T(t));
    EXPECT_TRUE(out.statuses.empty());  // one bad report alone stops nothing
    out = m_.Step(T(t));
  }
  ASSERT_FALSE(m_.busy());
  EXPECT_EQ(m_.status().fault, Fault::kMot);
  EXPECT_NE(m_.status().message.find("last one rejected: state = 9"), std::string::npos)
      << m_.status().message;
  // The drive-status time-out can be turned off: then the watchdog is what remains.
  MobilityOptions o;
  o.drive_status_timeout_s = 0.0;
  MobilityManager quiet = MakeGestaltManager(o);
  quiet.OnPose(PoseAt(T(0), 0, 0), T(0));
  out = quiet.OnCommand(Directed(1, Mode::kDirected, {Straight(1.0)}), T(0));
  ASSERT_EQ(out.drives.size(), 1u);
  for (double t = 0.5; t < 20; t += 0.5) {
    quiet.OnPose(PoseAt(T(t), 0, 0), T(t));
    quiet.Step(T(t));
  }
  EXPECT_TRUE(quiet.busy());
}

TEST_F(MobilityManagerScripted, RejectedPoseWhileDrivingIsSappAndStops) {
  // Idle: a bad pose sample changes nothing.
  MobilityOutput out = m_.OnInputRejected(MobilityInput::kPose, "pose.position.x is nan", T(0));
  EXPECT_TRUE(out.empty());
  EXPECT_FALSE(m_.motion_error_latched());
  out = Cmd(Directed(1, Mode::kDirected, {Straight(1.0)}), 1);
  ASSERT_EQ(out.drives.size(), 1u);
  out = m_.OnInputRejected(MobilityInput::kPose,
                           "pose.position.x is nan (must be finite)", T(1.5));
  ASSERT_FALSE(out.statuses.empty());
  EXPECT_EQ(out.statuses.back().state, State::kFailed);
  EXPECT_EQ(out.statuses.back().message,
            "dl/pose rejected: pose.position.x is nan (must be finite)");
  ExpectStoppedWith(Fault::kSapp, out);
}

TEST_F(MobilityManagerScripted, StalePoseWhileDrivingIsSappAndStops) {
  MobilityOutput out = Cmd(Directed(1, Mode::kDirected, {Straight(1.0)}), 0);
  ASSERT_EQ(out.drives.size(), 1u);
  const std::uint32_t drive = out.drives[0].command_id;
  double ended = -1;
  for (double t = 0.1; t < 10; t += 0.1) {  // no pose after the command's
    StillDriving(drive, t);
    out = m_.Step(T(t));
    if (!m_.busy()) {
      ended = t;
      break;
    }
  }
  EXPECT_NEAR(ended, m_.options().pose_stale_s, 0.15);
  ExpectStoppedWith(Fault::kSapp, out);
}

TEST_F(MobilityManagerScripted, RejectedRangeImageOfThePendingRequestIsImg) {
  MobilityOutput out = Cmd(Autonav(1, 5, 0), 0);
  ASSERT_EQ(out.range_requests.size(), 1u);
  const std::uint32_t id = out.range_requests[0].request_id;
  // Another client's image (or one whose id was corrupted): not ours.
  out = m_.OnInputRejected(MobilityInput::kRangeImage, "width = 0", T(0.5), id + 100);
  EXPECT_TRUE(out.statuses.empty());
  EXPECT_TRUE(m_.busy());
  out = m_.OnInputRejected(MobilityInput::kRangeImage, "xyz[12] is nan (must be finite)", T(0.6),
                           id);
  ASSERT_FALSE(out.statuses.empty());
  EXPECT_EQ(out.statuses.back().fault, Fault::kImg);
  EXPECT_EQ(out.statuses.back().fault_class, FaultClass::kMotionError);
  EXPECT_NE(out.statuses.back().message.find("dl/range_image rejected: xyz[12] is nan"),
            std::string::npos)
      << out.statuses.back().message;
  EXPECT_TRUE(m_.motion_error_latched());
  EXPECT_TRUE(out.drives.empty());  // nothing was moving
}

TEST(MobilityManagerInputs, RejectedVisualOdometryIsAFailedStep) {
  MobilityOptions o;
  o.max_visodom_failures = 0;
  MobilityManager m = MakeGestaltManager(o);
  m.OnPose(PoseAt(T(0), 0, 0), T(0));
  MobilityOutput out = m.OnCommand(Directed(1, Mode::kVisOdom, {Straight(0.5)}), T(0));
  ASSERT_EQ(out.drives.size(), 1u);
  // Not waiting for VO yet: ignored.
  EXPECT_TRUE(m.OnInputRejected(MobilityInput::kVisOdom, "bad", T(0.5)).statuses.empty());
  m.OnPose(PoseAt(T(2), 0.5, 0), T(2));
  m.OnDriveStatus(DriveReport(out.drives[0].command_id, DriveState::kDone,
                              DriveTermination::kNominal, 0.5, ""),
                  T(2));
  ASSERT_TRUE(m.busy());
  out = m.OnInputRejected(MobilityInput::kVisOdom, "covariance[0] is nan", T(2.5));
  ASSERT_FALSE(out.statuses.empty());
  EXPECT_EQ(out.statuses.back().fault, Fault::kVisOdom);
  EXPECT_STREQ(MobilityInputTopic(MobilityInput::kVisOdom), "dl/relative_pose");
}

TEST_F(MobilityManagerScripted, TimeBudgetIsWaypointTimeout) {
  MobilityCommand c = Directed(1, Mode::kDirected, {Straight(1.0)});
  c.time_budget_s = 5.0;
  const std::uint32_t drive = Cmd(c, 0).drives.at(0).command_id;
  MobilityOutput out;
  for (double t = 0.5; t < 10 && m_.busy(); t += 0.5) {
    m_.OnPose(PoseAt(T(t), 0.01 * t, 0), T(t));
    StillDriving(drive, t);
    out = m_.Step(T(t));
  }
  EXPECT_EQ(m_.status().fault, Fault::kWaypointTimeout);
  EXPECT_EQ(m_.status().fault_class, FaultClass::kGoalError);
  ASSERT_FALSE(out.drives.empty());
  EXPECT_EQ(out.drives.back().primitive, PrimitiveKind::kStop);
}

TEST_F(MobilityManagerScripted, TimeOfDayLimit) {
  // Run-clock 0 is J2000 noon; find the LMST there and ask to stop 0.01 Mars hours later.
  const double lmst = MarsLocalMeanSolarTimeHours(m_.options().run_clock_epoch_unix_s,
                                                  m_.options().site_longitude_east);
  MobilityCommand c = Directed(1, Mode::kDirected, {Straight(1.0)});
  c.lmst_end_h = std::fmod(lmst + 0.01, 24.0);
  const std::uint32_t drive = Cmd(c, 0).drives.at(0).command_id;
  for (double t = 0.5; t < 100 && m_.busy(); t += 0.5) {
    m_.OnPose(PoseAt(T(t), 0.001 * t, 0), T(t));
    StillDriving(drive, t);
    m_.Step(T(t));
  }
  EXPECT_EQ(m_.status().fault, Fault::kTod);
  // 0.01 Mars hours = 37 s.
  EXPECT_NEAR(m_.status().stamp.seconds(), 0.01 * kSecondsPerMarsHour, 0.6);
}

TEST_F(MobilityManagerScripted, TiltAndNortherlyTiltFromThePose) {
  MobilityCommand c = Directed(1, Mode::kDirected, {Straight(1.0), Straight(1.0)});
  c.min_northerly_tilt = 0.05;     // the deck must face north by 3 deg
  MobilityOutput out = Cmd(c, 0);  // flat: checked before the first step, nothing moves
  EXPECT_TRUE(out.drives.empty());
  EXPECT_EQ(m_.status().fault, Fault::kNorth) << m_.status().message;
  EXPECT_EQ(m_.status().fault_class, FaultClass::kMotionError);
  MobilityCommand clear;
  clear.command_id = 5;
  clear.mode = Mode::kClearFault;
  Cmd(clear, 1);
  out = Cmd(Directed(2, Mode::kDirected, {Straight(1.0)}), 2);
  PoseSample tilted = PoseAt(T(2.5), 0, 0);
  tilted.site_from_rover.linear() =
      Eigen::AngleAxisd(0.6, Eigen::Vector3d::UnitX()).toRotationMatrix();  // 34 deg roll
  m_.OnPose(tilted, T(2.5));
  out = m_.Step(T(2.6));
  EXPECT_EQ(m_.status().fault, Fault::kTilt) << m_.status().message;
}

// A planner that returns one detour waypoint.
class OneWaypointPlanner final : public nav_core::GlobalPlanner {
 public:
  Status AddScan(const nav_core::RangeScan&) override { return Status::Ok(); }
  Result<nav_core::GlobalPlan> MakePlan(const nav_core::PlanRequest& r) override {
    nav_core::GlobalPlan p;
    p.waypoints = {{2.0, 2.0}, r.goal};
    return p;
  }
  void Clear() override {}
};

TEST(MobilityManagerWorld, LongTraverseWithAPlannerDrivesItsLegs) {
  const gestalt::GestaltOptions g;
  auto manager = MobilityManager::Create(
      MobilityOptions{},
      std::make_unique<gestalt::TerrainMap>(gestalt::TerrainMap::Create(g).value()),
      std::make_unique<gestalt::ArcEvaluator>(gestalt::ArcEvaluator::Create(g).value()),
      std::make_unique<OneWaypointPlanner>());
  ASSERT_TRUE(manager.ok());
  FakeWorld w(&manager.value());
  MobilityCommand c = Autonav(1, 4.0, 0.0);
  c.mode = Mode::kLongTraverse;
  const MobilityStatus s = w.Run(c, 2000.0);
  EXPECT_EQ(s.state, State::kSucceeded) << s.message;
}

TEST(MobilityManagerCreate, RejectsBadOptionsAndMissingInterfaces) {
  MobilityOptions o;
  o.step_length = -1;
  const gestalt::GestaltOptions g;
  auto r = MobilityManager::Create(
      o, std::make_unique<gestalt::TerrainMap>(gestalt::TerrainMap::Create(g).value()),
      std::make_unique<gestalt::ArcEvaluator>(gestalt::ArcEvaluator::Create(g).value()));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("step_length"), std::string::npos);
  r = MobilityManager::Create(MobilityOptions{}, nullptr, nullptr);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("assessor"), std::string::npos);
}

}  // namespace
}  // namespace rover::apl::mobility
