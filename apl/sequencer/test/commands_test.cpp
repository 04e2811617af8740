#include "rover/apl/sequencer/commands.hpp"

#include <gtest/gtest.h>

#include <set>

#include <cmath>
#include <numbers>

#include "rover/base/units.hpp"
#include "sequencer_test_util.hpp"

namespace rover::apl::sequencer {
namespace {

using MF = msg::MobilityFault;

using testing::CallOf;
using testing::MustParse;
Command Build(const std::string& line, const PoseSample* pose = nullptr) {
  Result<Command> c = BuildCommand(CallOf(line), pose, 7, 3);
  EXPECT_TRUE(c.ok()) << c.status().ToString();
  return c.ok() ? *c : Command{};
}

TEST(BuildCommand, DirectedArcCarriesIdStepLineAndSiUnits) {
  const Command c = Build("DRIVE ARC curvature=0.5 distance=150 cm speed=4 cm/s");
  EXPECT_EQ(c.id, 7u);
  EXPECT_EQ(c.step, 3);
  EXPECT_EQ(c.line, 1);
  EXPECT_EQ(c.kind, CommandKind::kDriveArc);
  EXPECT_EQ(c.family, Family::kMobility);
  EXPECT_EQ(c.text, "DRIVE ARC curvature=0.5 distance=150 cm speed=4 cm/s");
  const auto m = std::get<MobilityRequest>(c.request);
  EXPECT_EQ(m.mode, msg::MobilityMode::kDirected);
  EXPECT_EQ(m.primitive, msg::DrivePrimitive::kArc);
  EXPECT_DOUBLE_EQ(m.curvature, 0.5);
  EXPECT_DOUBLE_EQ(m.distance, 1.5);
  EXPECT_DOUBLE_EQ(m.speed, 0.04);
  EXPECT_DOUBLE_EQ(m.time_budget_s, 0.0);
}

TEST(BuildCommand, ModesFollowTheCommandNames) {
  struct Case {
    const char* line;
    msg::MobilityMode mode;
    std::optional<msg::DrivePrimitive> primitive;
  };
  for (const Case& k : std::vector<Case>{
           {"TURN angle_deg=90", msg::MobilityMode::kDirected, msg::DrivePrimitive::kTurnInPlace},
           {"VISODOM STRAIGHT distance=0.3", msg::MobilityMode::kVisOdom, msg::DrivePrimitive::kStraight},
           {"VISODOM ARC curvature=-1 distance=1", msg::MobilityMode::kVisOdom, msg::DrivePrimitive::kArc},
           {"GUARDED ARC curvature=0.2 distance=2", msg::MobilityMode::kGuardedArc, msg::DrivePrimitive::kArc},
           {"GOTO (5, 2)", msg::MobilityMode::kGoToWaypoint, std::nullopt},
           {"VISODOM GOTO (5, 2)", msg::MobilityMode::kVisOdomGoToWaypoint, std::nullopt},
           {"GUARDED goal=(5, 2)", msg::MobilityMode::kGuarded, std::nullopt},
           {"GUARDED VISODOM goal=(5, 2)", msg::MobilityMode::kGuardedVisOdom, std::nullopt},
           {"AUTONAV goal=(5, 2) tolerance=0.3", msg::MobilityMode::kAutoNav, std::nullopt},
           {"AUTONAV VISODOM goal=(5, 2)", msg::MobilityMode::kAutoNavVisOdom, std::nullopt},
           {"LONG_TRAVERSE goal=(50, 20)", msg::MobilityMode::kLongTraverse, std::nullopt},
           {"STOP", msg::MobilityMode::kStop, std::nullopt},
           {"CLEAR_FAULT", msg::MobilityMode::kClearFault, std::nullopt}}) {
    SCOPED_TRACE(k.line);
    const auto m = std::get<MobilityRequest>(Build(k.line).request);
    EXPECT_EQ(m.mode, k.mode);
    EXPECT_EQ(m.primitive, k.primitive);
  }
  const auto turn = std::get<MobilityRequest>(Build("TURN angle_deg=-45").request);
  EXPECT_DOUBLE_EQ(turn.angle, -45 * kDegree);
  const auto nav =
      std::get<MobilityRequest>(Build("AUTONAV goal=(5, 2) tolerance=0.4 timeout=10 min").request);
  EXPECT_DOUBLE_EQ(nav.goal_x, 5.0);
  EXPECT_DOUBLE_EQ(nav.goal_y, 2.0);
  EXPECT_DOUBLE_EQ(nav.tolerance, 0.4);
  EXPECT_DOUBLE_EQ(nav.time_budget_s, 600.0);
  EXPECT_DOUBLE_EQ(std::get<MobilityRequest>(Build("GOTO (1, 1)").request).tolerance, 0.3);
}

TEST(BuildCommand, TurnToFacesAPointOrHeadingFromThePose) {
  Sequence s = MustParse("TARGET rock = (3, 4, 0)\nTURN TO rock\nVISODOM TURN TO (0, -2)\n"
                         "TURN TO heading_deg=180\n");
  PoseSample pose;
  pose.position = {0.0, 0.0, 0.0};
  pose.yaw = 10 * kDegree;
  Result<Command> a = BuildCommand(s.statements[0].command, &pose, 1, 1);
  ASSERT_TRUE(a.ok());
  EXPECT_NEAR(std::get<MobilityRequest>(a->request).angle, std::atan2(4.0, 3.0) - 10 * kDegree,
              1e-12);
  Result<Command> b = BuildCommand(s.statements[1].command, &pose, 2, 2);
  ASSERT_TRUE(b.ok());
  EXPECT_EQ(std::get<MobilityRequest>(b->request).mode, msg::MobilityMode::kVisOdom);
  EXPECT_NEAR(std::get<MobilityRequest>(b->request).angle, -100 * kDegree, 1e-12);
  // 180 - 10 deg stays in (-pi, pi]; from yaw -10 deg it would be 190 -> -170.
  Result<Command> c = BuildCommand(s.statements[2].command, &pose, 3, 3);
  EXPECT_NEAR(std::get<MobilityRequest>(c->request).angle, 170 * kDegree, 1e-12);
  pose.yaw = -10 * kDegree;
  c = BuildCommand(s.statements[2].command, &pose, 3, 3);
  EXPECT_NEAR(std::get<MobilityRequest>(c->request).angle, -170 * kDegree, 1e-12);

  EXPECT_TRUE(NeedsPose(s.statements[0].command));
  Result<Command> none = BuildCommand(s.statements[0].command, nullptr, 1, 1);
  ASSERT_FALSE(none.ok());
  EXPECT_EQ(none.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_EQ(none.status().message(), "TURN TO needs a pose estimate");
}

TEST(BuildCommand, MastRendezvousAndArmRequests) {
  const auto mast = std::get<MastRequest>(Build("MAST pan_deg=30 tilt_deg=-20").request);
  EXPECT_EQ(mast.kind, MastRequest::Kind::kAngles);
  EXPECT_NEAR(mast.pan, 30 * kDegree, 1e-12);
  EXPECT_NEAR(mast.tilt, -20 * kDegree, 1e-12);
  const auto look = std::get<MastRequest>(Build("MAST LOOK_AT (1, 2, 0.5)").request);
  EXPECT_EQ(look.kind, MastRequest::Kind::kLookAt);
  EXPECT_EQ(look.point, (Vec3{1, 2, 0.5}));

  const Command px = Build("APPROACH_TARGET image=12 pixel=(512, 300.5)");
  EXPECT_EQ(px.family, Family::kRendezvous);
  const auto a = std::get<RendezvousRequest>(px.request);
  EXPECT_EQ(a.kind, RendezvousRequest::Kind::kApproachTarget);
  ASSERT_TRUE(a.image.has_value());
  EXPECT_EQ(*a.image, 12u);
  EXPECT_DOUBLE_EQ(a.u, 512.0);
  EXPECT_DOUBLE_EQ(a.v, 300.5);
  EXPECT_FALSE(a.point.has_value());
  EXPECT_DOUBLE_EQ(a.standoff, 1.05);
  const auto p = std::get<RendezvousRequest>(
      Build("APPROACH_TARGET point=(4, 1, -0.2) standoff=1.1").request);
  EXPECT_FALSE(p.image.has_value());
  EXPECT_EQ(*p.point, (Vec3{4, 1, -0.2}));
  EXPECT_DOUBLE_EQ(p.standoff, 1.1);
  EXPECT_FALSE(p.place);
  EXPECT_FALSE(p.focus);
  const auto both = std::get<RendezvousRequest>(
      Build("APPROACH_TARGET point=(4, 1, -0.2) then=place_focus").request);
  EXPECT_TRUE(both.place);
  EXPECT_TRUE(both.focus);
  const auto focus_only = std::get<RendezvousRequest>(
      Build("APPROACH_TARGET point=(4, 1, -0.2) then=FOCUS").request);
  EXPECT_FALSE(focus_only.place);
  EXPECT_TRUE(focus_only.focus);
  const auto lander = std::get<RendezvousRequest>(Build("RETURN_TO_LANDER").request);
  EXPECT_EQ(lander.kind, RendezvousRequest::Kind::kReturnToLander);
  EXPECT_FALSE(lander.point.has_value());
  EXPECT_DOUBLE_EQ(lander.standoff, 1.0);

  const auto move = std::get<ArmRequest>(Build("ARM MOVE (0, 45, -90, 10)").request);
  EXPECT_EQ(move.kind, ArmRequest::Kind::kMove);
  EXPECT_NEAR(move.joints[2], -90 * kDegree, 1e-12);
  const auto place = std::get<ArmRequest>(Build("ARM PLACE (1, 0, -0.3) hover=5 mm").request);
  EXPECT_EQ(place.kind, ArmRequest::Kind::kPlace);
  EXPECT_DOUBLE_EQ(place.hover, 0.005);
  const auto focus = std::get<ArmRequest>(Build("AUTOFOCUS (1.1, 0, 0.02)").request);
  EXPECT_EQ(focus.kind, ArmRequest::Kind::kAutofocus);
  EXPECT_DOUBLE_EQ(focus.point.x, 1.1);
  EXPECT_EQ(focus.focus_steps, 10);
  EXPECT_DOUBLE_EQ(focus.focus_step, 0.0067);
  EXPECT_EQ(std::get<ArmRequest>(Build("ARM STOW").request).kind, ArmRequest::Kind::kStow);
  EXPECT_EQ(std::get<ArmRequest>(Build("ARM UNSTOW").request).kind, ArmRequest::Kind::kUnstow);
}

TEST(Faults, AreCoreMsgsFaultsAndClasses) {
  using RF = msg::RendezvousFault;
  // NONE, every mobility fault in core/msg's order, the rendezvous faults it lacks, OTHER.
  const auto& names = FaultNames();
  ASSERT_GE(names.size(), static_cast<std::size_t>(msg::kMobilityFaultCount) + 2);
  EXPECT_EQ(names.front(), "NONE");
  EXPECT_EQ(names.back(), "OTHER");
  for (int i = 0; i < msg::kMobilityFaultCount; ++i) {
    const Fault f(static_cast<MF>(i));
    EXPECT_EQ(f.Index(), i);
    EXPECT_EQ(f.Name(), msg::MobilityFaultName(static_cast<MF>(i)));
    EXPECT_EQ(f.DefaultClass(), msg::FaultClassOf(static_cast<MF>(i))) << f.Name();
  }
  for (int i = 1; i < msg::kRendezvousFaultCount; ++i) {
    const Fault f(static_cast<RF>(i));
    EXPECT_EQ(f.Name(), msg::RendezvousFaultName(static_cast<RF>(i)));
    EXPECT_EQ(f.DefaultClass(), msg::FaultClass::kGoalError) << f.Name();
  }
  // One fault whichever service reports it; every name appears once.
  EXPECT_EQ(Fault(RF::kBusy), Fault(MF::kBusy));
  EXPECT_EQ(Fault(RF::kBadCommand), Fault(MF::kBadCommand));
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size());
  for (const std::string& n : names) EXPECT_EQ(Fault::Named(n)->Name(), n);
  EXPECT_FALSE(Fault::Named("INVALID").has_value());
  EXPECT_FALSE(Fault::Named("WAYPT-TIMEOUT").has_value());
  EXPECT_EQ(Fault(static_cast<MF>(99)), Fault::Other());  // a wire value no enumerator has
  EXPECT_EQ(Fault(static_cast<RF>(99)), Fault::Other());
  EXPECT_EQ(Fault().Name(), "NONE");
  EXPECT_EQ(Fault().DefaultClass(), msg::FaultClass::kNone);
  EXPECT_EQ(Fault::Other().DefaultClass(), msg::FaultClass::kGoalError);
  EXPECT_EQ(Fault(MF::kWaypointTimeout).Name(), "WAYPT_TIMEOUT");
  EXPECT_EQ(Fault(MF::kTilt).DefaultClass(), msg::FaultClass::kMotionError);
  EXPECT_STREQ(TerminationName(Termination::kRejected), "REJECTED");
  EXPECT_EQ(FaultClassNames(), (std::vector<std::string>{"NONE", "GOAL_ERROR", "MOTION_ERROR"}));
}

TEST(Outcome, ValidatesAndDescribes) {
  EXPECT_TRUE(Outcome::Nominal().Validate().ok());
  EXPECT_EQ(Outcome::Nominal().Describe(), "NOMINAL");
  const Outcome stuck = Outcome::Failed(Fault(MF::kNoProgress), "limit cycle");
  EXPECT_TRUE(stuck.Validate().ok());
  EXPECT_EQ(stuck.fault_class, msg::FaultClass::kGoalError);
  EXPECT_EQ(stuck.Describe(), "NOPROGRESS (goal error): limit cycle");
  EXPECT_EQ(Outcome::Failed(Fault(MF::kTilt), "").Describe(), "TILT (motion error)");
  EXPECT_EQ(Outcome::Rejected(Fault(MF::kBusy), "running").Describe(),
            "REJECTED BUSY (goal error): running");
  EXPECT_EQ(Outcome{}.Validate().message(), "outcome termination NONE is not an outcome");
  Outcome bad = Outcome::Nominal();
  bad.fault = Fault(MF::kTilt);
  EXPECT_EQ(bad.Validate().message(), "outcome NOMINAL carries fault TILT");
  EXPECT_EQ(Outcome::Failed(Fault(), "").Validate().message(),
            "outcome FAULT carries no fault");
}

TEST(Pose, TiltAndHorizontalDistance) {
  PoseSample p;
  p.position = {1.0, 1.0, 5.0};
  EXPECT_DOUBLE_EQ(DistanceTo(p, {4.0, 5.0, -3.0}), 5.0);  // z does not count
  p.roll = 0.0;
  p.pitch = 15 * kDegree;
  EXPECT_NEAR(TiltOf(p), 15 * kDegree, 1e-12);
  p.roll = 10 * kDegree;
  p.pitch = 10 * kDegree;
  EXPECT_NEAR(TiltOf(p), std::acos(std::cos(10 * kDegree) * std::cos(10 * kDegree)), 1e-12);
}

}  // namespace
}  // namespace rover::apl::sequencer
