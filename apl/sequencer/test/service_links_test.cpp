// apl-sequencer's links to its neighbours' messages: requests to commands, statuses to
// outcomes, dl/pose to the pose input, the interpreter's status to apl/sequence_status.
#include "service_links.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rover/apl/sequencer/parser.hpp"
#include "sequencer_test_util.hpp"

namespace rover::apl::sequencer {
namespace {

using MF = msg::MobilityFault;

using testing::MustParse;

Command Built(const std::string& line, std::uint32_t id = 7) {
  const Sequence s = MustParse(line + "\n");
  PoseSample pose;
  Result<Command> c = BuildCommand(s.statements.at(0).command, &pose, id, 1);
  EXPECT_TRUE(c.ok()) << c.status().ToString();
  return c.ok() ? *c : Command{};
}

TEST(ServiceLinks, MobilityMastRendezvousAndArmAreDispatched) {
  EXPECT_TRUE(CheckDispatchable(MustParse("ON_ABORT\n  STOP\nEND\nMAST LOOK_AT (1, 2, 0)\n"
                                          "IF tilt > 5\n  AUTONAV goal=(3, 0)\nEND\n"))
                  .ok());
  EXPECT_TRUE(CheckDispatchable(MustParse("STOP\nIF tilt > 5\n  TURN angle_deg=5\nELSE\n  ARM STOW\nEND\n"
                                          "ARM PLACE (1, 0, 0)\nARM MOVE joints_deg=(0, 80, -170, 170)\n"))
                  .ok());
  EXPECT_TRUE(CheckDispatchable(
                  MustParse("STOP\nIF tilt > 5\n  TURN angle_deg=5\nELSE\n  AUTOFOCUS (1, 0, 0)\nEND\n"))
                  .ok());
  const Status inner = CheckDispatchable(
      MustParse("STOP\nIF tilt > 5\n  TURN angle_deg=5\nELSE\n  ARM UNSTOW\nEND\n"));
  EXPECT_EQ(inner.message(), "line 5: ARM UNSTOW: apl-sequencer does not dispatch it (dl-arm "
                             "has no unstowed pose; ARM MOVE names one)");
  EXPECT_TRUE(CheckDispatchable(MustParse(
                  "ON_ABORT\n  RETURN_TO_LANDER\nEND\nAPPROACH_TARGET point=(3, 0, 0)\n"))
                  .ok());
  const Status in_abort =
      CheckDispatchable(MustParse("ON_ABORT\n  ARM UNSTOW\nEND\nAPPROACH_TARGET point=(3, 0, 0)\n"));
  EXPECT_EQ(in_abort.message(), "line 2: ARM UNSTOW: apl-sequencer does not dispatch it (dl-arm "
                                "has no unstowed pose; ARM MOVE names one)");
}

TEST(ServiceLinks, ArmCommandsAndTheirStatuses) {
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(2.0, 1.0, 0.0);
  pose.linear() = Eigen::AngleAxisd(M_PI / 2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Result<msg::ArmCommand> place = ArmCommandOf(Built("ARM PLACE (2, 2.05, 0.1)", 9), pose, Time{5});
  ASSERT_TRUE(place.ok()) << place.status().ToString();
  EXPECT_EQ(place->mode, msg::ArmMode::kPlace);
  EXPECT_EQ(place->command_id, 9u);
  // 1.05 m ahead of a rover facing +y (site), 10 cm up: the rover frame's (1.05, 0, 0.1).
  EXPECT_TRUE(place->target.isApprox(Eigen::Vector3d(1.05, 0.0, 0.1), 1e-12)) << place->target.transpose();
  EXPECT_FALSE(ArmCommandOf(Built("ARM PLACE (2, 2.05, 0.1)"), std::nullopt, Time{5}).ok());
  const Result<msg::ArmCommand> hover = ArmCommandOf(Built("ARM PLACE (2, 2, 0) hover=5 mm"), pose, Time{5});
  ASSERT_FALSE(hover.ok());
  EXPECT_NE(hover.status().message().find("hover = 0.005"), std::string::npos) << hover.status().ToString();
  const Result<msg::ArmCommand> move = ArmCommandOf(Built("ARM MOVE joints_deg=(0, 90, -90, 0)"), std::nullopt, Time{5});
  ASSERT_TRUE(move.ok());
  EXPECT_EQ(move->mode, msg::ArmMode::kJoints);
  EXPECT_NEAR(move->joints[1], M_PI / 2, 1e-12);
  EXPECT_EQ(ArmCommandOf(Built("ARM STOW"), std::nullopt, Time{5})->mode, msg::ArmMode::kStow);
  const Result<msg::ArmCommand> focus =
      ArmCommandOf(Built("AUTOFOCUS (2, 2.05, 0.1) steps=12 step=5 mm"), pose, Time{5});
  ASSERT_TRUE(focus.ok()) << focus.status().ToString();
  EXPECT_EQ(focus->mode, msg::ArmMode::kAutofocus);
  EXPECT_TRUE(focus->target.isApprox(Eigen::Vector3d(1.05, 0.0, 0.1), 1e-12));
  EXPECT_EQ(focus->focus_steps, 12);
  EXPECT_NEAR(focus->focus_span, 0.055, 1e-12);
  EXPECT_FALSE(ArmCommandOf(Built("AUTOFOCUS (2, 2, 0)"), std::nullopt, Time{5}).ok());
  const Result<msg::ArmCommand> long_sweep =
      ArmCommandOf(Built("AUTOFOCUS (2, 2, 0) steps=30 step=15 mm"), pose, Time{5});
  ASSERT_FALSE(long_sweep.ok());
  EXPECT_NE(long_sweep.status().message().find("at most 0.3 m"), std::string::npos);
  const msg::ArmCommand stop = ArmStopCommand(12, Time{6});
  EXPECT_EQ(stop.mode, msg::ArmMode::kStop);
  EXPECT_EQ(stop.command_id, 12u | kCancelIdBit);

  msg::ArmStatus s;
  s.state = msg::ArmState::kMoving;
  EXPECT_FALSE(OutcomeOfArmStatus(s).has_value());
  for (msg::ArmState done : {msg::ArmState::kAtGoal, msg::ArmState::kPlaced, msg::ArmState::kStowed}) {
    s.state = done;
    ASSERT_TRUE(OutcomeOfArmStatus(s).has_value());
    EXPECT_EQ(OutcomeOfArmStatus(s)->termination, Termination::kNominal);
  }
  s.state = msg::ArmState::kFault;
  s.message = "no contact within 0.03 m below the target";
  ASSERT_TRUE(OutcomeOfArmStatus(s).has_value());
  EXPECT_EQ(OutcomeOfArmStatus(s)->termination, Termination::kFault);
  EXPECT_EQ(OutcomeOfArmStatus(s)->message, s.message);
  s.state = msg::ArmState::kRejected;
  EXPECT_EQ(OutcomeOfArmStatus(s)->termination, Termination::kRejected);
}

TEST(ServiceLinks, RendezvousCommandsAndTheirStatuses) {
  const msg::RendezvousCommand by_pixel =
      RendezvousCommandOf(Built("APPROACH_TARGET image=3355443201 pixel=(512, 300.5) standoff=1.1"),
                          Time{5});
  EXPECT_EQ(by_pixel.command_id, 7u);
  EXPECT_EQ(by_pixel.target, msg::RendezvousTarget::kScience);
  EXPECT_EQ(by_pixel.image_id, 3355443201u);
  EXPECT_DOUBLE_EQ(by_pixel.pixel_x, 512.0);
  EXPECT_DOUBLE_EQ(by_pixel.pixel_y, 300.5);
  EXPECT_DOUBLE_EQ(by_pixel.standoff, 1.1);
  const msg::RendezvousCommand by_point =
      RendezvousCommandOf(Built("APPROACH_TARGET point=(4, 1, -0.2)"), Time{5});
  EXPECT_EQ(by_point.image_id, 0u);
  EXPECT_EQ(by_point.target_estimate, Eigen::Vector3d(4, 1, -0.2));
  EXPECT_FALSE(by_point.place_instrument);
  EXPECT_FALSE(by_point.autofocus);
  const msg::RendezvousCommand fido = RendezvousCommandOf(
      Built("APPROACH_TARGET point=(4, 1, -0.2) then=PLACE_FOCUS"), Time{5});
  EXPECT_TRUE(fido.place_instrument);
  EXPECT_TRUE(fido.autofocus);
  const msg::RendezvousCommand lander =
      RendezvousCommandOf(Built("RETURN_TO_LANDER lander=(30, 1, 0) timeout=2000 s"), Time{5});
  EXPECT_EQ(lander.target, msg::RendezvousTarget::kLander);
  EXPECT_EQ(lander.target_estimate, Eigen::Vector3d(30, 1, 0));
  EXPECT_DOUBLE_EQ(lander.time_budget_s, 2000.0);
  EXPECT_FALSE(lander.climb);
  const msg::RendezvousCommand stop = RendezvousStopCommand(12, Time{5});
  EXPECT_EQ(stop.target, msg::RendezvousTarget::kStop);
  EXPECT_EQ(stop.command_id, 12u | kCancelIdBit);

  msg::RendezvousStatus s;
  s.command_id = 7;
  s.phase = msg::RendezvousPhase::kApproachTarget;
  EXPECT_FALSE(OutcomeOfRendezvousStatus(s).has_value());
  s.phase = msg::RendezvousPhase::kAtTarget;
  EXPECT_FALSE(OutcomeOfRendezvousStatus(s).has_value());
  s.phase = msg::RendezvousPhase::kDone;
  EXPECT_EQ(OutcomeOfRendezvousStatus(s)->termination, Termination::kNominal);
  s.phase = msg::RendezvousPhase::kFailed;
  s.fault = msg::RendezvousFault::kTargetLost;
  s.message = "target lost (OUT_OF_VIEW)";
  const Outcome lost = *OutcomeOfRendezvousStatus(s);
  EXPECT_EQ(lost.termination, Termination::kFault);
  EXPECT_EQ(lost.fault.Name(), "TARGET_LOST");
  EXPECT_EQ(lost.fault_class, msg::FaultClass::kGoalError);
  EXPECT_EQ(lost.message, "target lost (OUT_OF_VIEW)");
  s.fault = msg::RendezvousFault::kBadCommand;
  EXPECT_EQ(OutcomeOfRendezvousStatus(s)->termination, Termination::kRejected);
}

TEST(ServiceLinks, MobilityCommandsCarryModeGoalAndOnePrimitive) {
  const msg::MobilityCommand arc =
      *MobilityCommandOf(Built("VISODOM ARC curvature=0.5 distance=2 timeout=90 s"), Time{5});
  EXPECT_EQ(arc.stamp, Time{5});
  EXPECT_EQ(arc.command_id, 7u);
  EXPECT_EQ(arc.mode, msg::MobilityMode::kVisOdom);
  EXPECT_DOUBLE_EQ(arc.time_budget_s, 90.0);
  ASSERT_EQ(arc.primitives.size(), 1u);
  EXPECT_EQ(arc.primitives[0].kind, msg::DrivePrimitive::kArc);
  EXPECT_DOUBLE_EQ(arc.primitives[0].curvature, 0.5);
  EXPECT_DOUBLE_EQ(arc.primitives[0].distance, 2.0);

  const msg::MobilityCommand turn = *MobilityCommandOf(Built("TURN angle_deg=90"), Time{5});
  EXPECT_EQ(turn.mode, msg::MobilityMode::kDirected);
  EXPECT_EQ(turn.primitives.at(0).kind, msg::DrivePrimitive::kTurnInPlace);
  EXPECT_NEAR(turn.primitives.at(0).angle, std::numbers::pi / 2, 1e-12);

  const msg::MobilityCommand go =
      *MobilityCommandOf(Built("AUTONAV goal=(5, -2) tolerance=0.4"), Time{5});
  EXPECT_EQ(go.mode, msg::MobilityMode::kAutoNav);
  EXPECT_EQ(go.goal, Eigen::Vector3d(5, -2, 0));
  EXPECT_DOUBLE_EQ(go.tolerance, 0.4);
  EXPECT_TRUE(go.primitives.empty());
  EXPECT_EQ(MobilityCommandOf(Built("LONG_TRAVERSE goal=(9, 9)"), Time{5})->mode,
            msg::MobilityMode::kLongTraverse);
  EXPECT_EQ(MobilityCommandOf(Built("CLEAR_FAULT"), Time{5})->mode,
            msg::MobilityMode::kClearFault);

  const Result<msg::MobilityCommand> fast =
      MobilityCommandOf(Built("DRIVE STRAIGHT distance=1 speed=5 cm/s"), Time{5});
  ASSERT_FALSE(fast.ok());
  EXPECT_EQ(fast.status().message(),
            "speed = 0.05 m/s: apl/mobility_command carries no speed (the mobility manager's "
            "drive speed is its parameter); leave speed at 0");

  const msg::MobilityCommand stop = MobilityStopCommand(12, Time{5});
  EXPECT_EQ(stop.mode, msg::MobilityMode::kStop);
  EXPECT_EQ(stop.command_id, 12u | kCancelIdBit);
  EXPECT_EQ(stop.stamp, Time{5});
}

TEST(ServiceLinks, MastCommandsPointByAnglesOrAtAPoint) {
  const msg::MastCommand a = MastCommandOf(Built("MAST pan_deg=90 tilt_deg=-30"), Time{5});
  EXPECT_EQ(a.stamp, Time{5});
  EXPECT_EQ(a.command_id, 7u);
  EXPECT_EQ(a.pointing, msg::MastPointing::kAngles);
  EXPECT_NEAR(a.pan, std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(a.tilt, -std::numbers::pi / 6, 1e-12);
  const msg::MastCommand b = MastCommandOf(Built("MAST LOOK_AT (1, 2, 0.5)"), Time{5});
  EXPECT_EQ(b.pointing, msg::MastPointing::kLookAt);
  EXPECT_EQ(b.look_at, Eigen::Vector3d(1, 2, 0.5));
}

TEST(ServiceLinks, StatusesEndTheirCommandOnlyWhenTerminal) {
  msg::MobilityStatus s;
  s.stamp = Time::FromSeconds(12);
  s.command_id = 3;
  s.state = msg::MobilityState::kRunning;
  EXPECT_FALSE(OutcomeOfMobilityStatus(s).has_value());
  s.state = msg::MobilityState::kSucceeded;
  Outcome o = *OutcomeOfMobilityStatus(s);
  EXPECT_EQ(o.termination, Termination::kNominal);
  EXPECT_EQ(o.stamp, s.stamp);
  EXPECT_TRUE(o.Validate().ok());

  s.state = msg::MobilityState::kFailed;
  s.fault = msg::MobilityFault::kNoProgress;
  s.fault_class = msg::FaultClass::kGoalError;
  s.message = "limit cycle";
  o = *OutcomeOfMobilityStatus(s);
  EXPECT_EQ(o.Describe(), "NOPROGRESS (goal error): limit cycle");
  EXPECT_TRUE(o.Validate().ok());
  s.fault = msg::MobilityFault::kTilt;
  s.fault_class = msg::FaultClass::kMotionError;
  EXPECT_EQ(OutcomeOfMobilityStatus(s)->fault_class, msg::FaultClass::kMotionError);

  s.state = msg::MobilityState::kRejected;
  s.fault = msg::MobilityFault::kBadCommand;
  s.fault_class = msg::FaultClass::kGoalError;
  o = *OutcomeOfMobilityStatus(s);
  EXPECT_EQ(o.termination, Termination::kRejected);
  EXPECT_EQ(o.fault, Fault(MF::kBadCommand));
  s.fault = msg::MobilityFault::kNone;  // an off-nominal end always names a fault
  EXPECT_EQ(OutcomeOfMobilityStatus(s)->fault, Fault::Other());
  EXPECT_TRUE(OutcomeOfMobilityStatus(s)->Validate().ok());
  // Every mobility fault keeps core/msg's name and class: KEEPOUT once became OTHER, BAD_COMMAND
  // INVALID.
  for (int i = 1; i < msg::kMobilityFaultCount; ++i) {
    const auto f = static_cast<MF>(i);
    s.fault = f;
    s.fault_class = msg::FaultClass::kNone;
    const Outcome out = *OutcomeOfMobilityStatus(s);
    EXPECT_EQ(out.fault.Name(), msg::MobilityFaultName(f)) << i;
    EXPECT_EQ(out.fault_class, msg::FaultClassOf(f)) << i;
  }
  s.fault = MF::kKeepOut;
  EXPECT_EQ(OutcomeOfMobilityStatus(s)->Describe().substr(0, 25), "REJECTED KEEPOUT (goal er");
  s.fault = static_cast<MF>(99);
  EXPECT_EQ(OutcomeOfMobilityStatus(s)->fault, Fault::Other());

  msg::MastStatus m;
  m.state = msg::MastState::kMoving;
  EXPECT_FALSE(OutcomeOfMastStatus(m).has_value());
  m.state = msg::MastState::kAtGoal;
  EXPECT_EQ(OutcomeOfMastStatus(m)->termination, Termination::kNominal);
  m.state = msg::MastState::kRejected;
  m.message = "pan out of range";
  EXPECT_EQ(OutcomeOfMastStatus(m)->Describe(), "REJECTED BAD_COMMAND (goal error): pan out of range");
  m.state = msg::MastState::kFault;
  EXPECT_EQ(OutcomeOfMastStatus(m)->termination, Termination::kFault);
}

TEST(ServiceLinks, PoseVisOdomAndSequenceStatus) {
  msg::PoseEstimate p;
  p.stamp = Time{9};
  p.position = {1, 2, 3};
  p.rpy = {0.1, 0.2, 0.3};
  const PoseSample s = PoseOfEstimate(p);
  EXPECT_EQ(s.stamp, Time{9});
  EXPECT_EQ(s.position, (Vec3{1, 2, 3}));
  EXPECT_DOUBLE_EQ(s.roll, 0.1);
  EXPECT_DOUBLE_EQ(s.pitch, 0.2);
  EXPECT_DOUBLE_EQ(s.yaw, 0.3);
  EXPECT_TRUE(s.valid);

  msg::RelativePose r;
  r.source = msg::MotionSource::kVisualOdometry;
  r.status = msg::RelativePoseStatus::kConverged;
  EXPECT_FALSE(IsVisOdomFailure(r));
  r.status = msg::RelativePoseStatus::kTooFewFeatures;
  EXPECT_TRUE(IsVisOdomFailure(r));
  r.source = msg::MotionSource::kWheelOdometry;
  EXPECT_FALSE(IsVisOdomFailure(r));

  SequenceStatus st;
  st.state = SequenceState::kAborting;
  st.step = 4;
  EXPECT_EQ(SequenceStatusOf(st, 2, Time{1}).state, msg::SequenceState::kRunning);
  st.state = SequenceState::kAborted;
  st.message = "stopped at step 4 (line 6): operator";
  const msg::SequenceStatus m = SequenceStatusOf(st, 2, Time{1});
  EXPECT_EQ(m.state, msg::SequenceState::kFailed);
  EXPECT_EQ(m.command_id, 2u);
  EXPECT_EQ(m.step, 4u);
  EXPECT_EQ(m.message, st.message);
  st.state = SequenceState::kDone;
  EXPECT_EQ(SequenceStatusOf(st, 2, Time{1}).state, msg::SequenceState::kDone);
}

}  // namespace
}  // namespace rover::apl::sequencer
