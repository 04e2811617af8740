// The interpreter on scripted outcomes: event-driven dispatch, IF / ELSE on the last result,
// bounded loops, waits on simulated time, abort blocks, failing steps and their reasons.
#include "rover/apl/sequencer/interpreter.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <map>
#include <numbers>
#include <optional>

#include "rover/base/param_binder.hpp"
#include "rover/base/units.hpp"
#include "sequencer_test_util.hpp"

namespace rover::apl::sequencer {
namespace {

using MF = msg::MobilityFault;

using testing::MustParse;
Time T(double s) { return Time::FromSeconds(s); }

Interpreter Make(const InterpreterOptions& o = {}) {
  Result<Interpreter> it = Interpreter::Create(o);
  EXPECT_TRUE(it.ok()) << it.status().ToString();
  return std::move(*it);
}

/// Starts `text` at t = 0 on a fresh interpreter.
Interpreter Started(const std::string& text, const InterpreterOptions& o = {}) {
  Interpreter it = Make(o);
  EXPECT_TRUE(it.Start(MustParse(text), T(0)).ok());
  return it;
}

/// Runs the sequence to its end, answering every command with `answer` one second after it was
/// dispatched. Returns the texts of the commands dispatched, in order.
std::vector<std::string> RunScripted(Interpreter& it,
                                     const std::function<Outcome(const Command&)>& answer,
                                     double t0 = 0.0) {
  std::vector<std::string> sent;
  double t = t0;
  for (int guard = 0; guard < 1000 && it.busy(); ++guard) {
    StepOutput out = it.Step(T(t));
    if (out.command) {
      sent.push_back(out.command->text);
      t += 1.0;
      EXPECT_TRUE(it.OnCommandResult(out.command->id, answer(*out.command)).ok());
    } else if (out.wake_at) {
      t = out.wake_at->seconds();
    } else if (it.busy()) {
      t += 1.0;
    }
  }
  EXPECT_FALSE(it.busy());
  return sent;
}

Outcome Nominal(const Command&) { return Outcome::Nominal(); }

TEST(Interpreter, DispatchesOneCommandAtATimeInOrder) {
  Interpreter it = Started("DRIVE STRAIGHT distance=1\nTURN angle_deg=90\nSTOP\n");
  EXPECT_EQ(it.status().state, SequenceState::kRunning);
  StepOutput a = it.Step(T(0));
  ASSERT_TRUE(a.command.has_value());
  EXPECT_EQ(a.command->text, "DRIVE STRAIGHT distance=1");
  EXPECT_EQ(a.command->step, 1);
  EXPECT_EQ(a.status.step, 1);
  EXPECT_EQ(a.status.line, 1);
  EXPECT_EQ(a.status.dispatched, 1u);
  EXPECT_EQ(it.outstanding(), a.command->id);
  // Nothing more goes out until the first command has completed (MER's event-driven sequences).
  for (double t : {1.0, 5.0, 100.0}) EXPECT_FALSE(it.Step(T(t)).command.has_value());
  ASSERT_TRUE(it.OnCommandResult(a.command->id, Outcome::Nominal()).ok());
  StepOutput b = it.Step(T(101));
  ASSERT_TRUE(b.command.has_value());
  EXPECT_EQ(b.command->kind, CommandKind::kTurn);
  EXPECT_GT(b.command->id, a.command->id);
  EXPECT_NEAR(std::get<MobilityRequest>(b.command->request).angle, 90 * kDegree, 1e-12);
  ASSERT_TRUE(it.OnCommandResult(b.command->id, Outcome::Nominal()).ok());
  StepOutput c = it.Step(T(102));
  ASSERT_TRUE(c.command.has_value());
  ASSERT_TRUE(it.OnCommandResult(c.command->id, Outcome::Nominal()).ok());
  StepOutput end = it.Step(T(103));
  EXPECT_FALSE(end.command.has_value());
  EXPECT_EQ(end.status.state, SequenceState::kDone);
  EXPECT_EQ(end.status.step, 3);
  EXPECT_EQ(end.status.dispatched, 3u);
  EXPECT_TRUE(end.status.message.empty());
  EXPECT_FALSE(it.busy());
}

TEST(Interpreter, IfElseOnTheLastTermination) {
  const std::string text =
      "DRIVE STRAIGHT distance=2 on_fault=CONTINUE\n"
      "IF last.termination == NOMINAL\n"
      "  TURN angle_deg=90\n"
      "ELSE IF last.fault == NOPROGRESS\n"
      "  DRIVE STRAIGHT distance=-0.5\n"
      "ELSE\n"
      "  AUTONAV goal=(5, 0)\n"
      "END\n"
      "STOP\n";
  {
    Interpreter it = Started(text);
    EXPECT_EQ(RunScripted(it, Nominal),
              (std::vector<std::string>{"DRIVE STRAIGHT distance=2 on_fault=CONTINUE",
                                        "TURN angle_deg=90", "STOP"}));
    EXPECT_EQ(it.status().state, SequenceState::kDone);
  }
  {
    Interpreter it = Started(text);
    auto answer = [](const Command& c) {
      return c.step == 1 ? Outcome::Failed(Fault(MF::kNoProgress), "limit cycle") : Outcome::Nominal();
    };
    EXPECT_EQ(RunScripted(it, answer),
              (std::vector<std::string>{"DRIVE STRAIGHT distance=2 on_fault=CONTINUE",
                                        "DRIVE STRAIGHT distance=-0.5", "STOP"}));
    EXPECT_EQ(it.status().state, SequenceState::kDone);
  }
  {
    Interpreter it = Started(text);
    auto answer = [](const Command& c) {
      return c.step == 1 ? Outcome::Failed(Fault(MF::kTod), "time of day") : Outcome::Nominal();
    };
    EXPECT_EQ(RunScripted(it, answer)[1], "AUTONAV goal=(5, 0)");
  }
}

TEST(Interpreter, AFailingStepRunsTheAbortBlockAndEndsFailedWithItsReason) {
  Interpreter it = Started(
      "ON_ABORT\n  STOP\n  MAST pan_deg=0 tilt_deg=0\nEND\n"
      "DRIVE STRAIGHT distance=1\nVISODOM STRAIGHT distance=0.3\nTURN angle_deg=10\n");
  std::vector<std::string> sent = RunScripted(it, [](const Command& c) {
    return c.kind == CommandKind::kVisodomStraight
               ? Outcome::Failed(Fault(MF::kNoProgress), "no progress in 3 steps")
               : Outcome::Nominal();
  });
  EXPECT_EQ(sent, (std::vector<std::string>{"DRIVE STRAIGHT distance=1",
                                            "VISODOM STRAIGHT distance=0.3", "STOP",
                                            "MAST pan_deg=0 tilt_deg=0"}));
  const SequenceStatus& s = it.status();
  EXPECT_EQ(s.state, SequenceState::kFailed);
  EXPECT_EQ(s.failed_step, 4);
  EXPECT_EQ(s.failed_outcome.fault, Fault(MF::kNoProgress));
  EXPECT_EQ(s.message,
            "step 4 (line 6: VISODOM STRAIGHT distance=0.3) failed: NOPROGRESS (goal error): no "
            "progress in 3 steps");
}

TEST(Interpreter, WithoutAnAbortBlockAFailureEndsAtOnce) {
  Interpreter it = Started("TURN angle_deg=10\nSTOP\n");
  StepOutput a = it.Step(T(0));
  ASSERT_TRUE(it.OnCommandResult(a.command->id, Outcome::Failed(Fault(MF::kTilt), "28 deg")).ok());
  EXPECT_EQ(it.status().state, SequenceState::kFailed);
  EXPECT_FALSE(it.Step(T(1)).command.has_value());
  EXPECT_EQ(it.status().message, "step 1 (line 1: TURN angle_deg=10) failed: TILT (motion error): 28 deg");
}

TEST(Interpreter, ContinueLetsOnlyGoalErrorsThrough) {
  const std::string text = "TURN angle_deg=10 on_fault=CONTINUE\nSTOP\n";
  {  // a motion error still fails
    Interpreter it = Started(text);
    auto sent = RunScripted(it, [](const Command&) { return Outcome::Failed(Fault(MF::kMot), "x"); });
    EXPECT_EQ(sent.size(), 1u);
    EXPECT_EQ(it.status().state, SequenceState::kFailed);
  }
  {  // so does a rejection
    Interpreter it = Started(text);
    auto sent = RunScripted(it, [](const Command&) {
      return Outcome::Rejected(Fault(MF::kBusy), "mobility already running");
    });
    EXPECT_EQ(sent.size(), 1u);
    EXPECT_EQ(it.status().state, SequenceState::kFailed);
    EXPECT_EQ(it.status().message,
              "step 1 (line 1: TURN angle_deg=10 on_fault=CONTINUE) failed: REJECTED BUSY (goal "
              "error): mobility already running");
  }
  {  // a goal error goes on
    Interpreter it = Started(text);
    auto sent = RunScripted(it, [](const Command& c) {
      return c.step == 1 ? Outcome::Failed(Fault(MF::kNoPath), "") : Outcome::Nominal();
    });
    EXPECT_EQ(sent.size(), 2u);
    EXPECT_EQ(it.status().state, SequenceState::kDone);
  }
}

TEST(Interpreter, RepeatRunsExactlyNTimesAndNestedCountersReset) {
  Interpreter it = Started("REPEAT 3\n  REPEAT 2\n    TURN angle_deg=1\n  END\n  STOP\nEND\n");
  std::vector<std::string> sent = RunScripted(it, Nominal);
  EXPECT_EQ(sent.size(), 9u);
  EXPECT_EQ(std::count(sent.begin(), sent.end(), "STOP"), 3);
  EXPECT_EQ(it.status().state, SequenceState::kDone);
}

TEST(Interpreter, WhileStopsAtMaxOrWhenTheConditionFails) {
  {  // always true: bounded by MAX
    Interpreter it = Started("WHILE visodom.failures < 100 MAX 4\n  TURN angle_deg=1\nEND\nSTOP\n");
    std::vector<std::string> sent = RunScripted(it, Nominal);
    EXPECT_EQ(sent.size(), 5u);
    EXPECT_EQ(sent.back(), "STOP");
  }
  {  // the condition turns false after two failures are reported
    Interpreter it = Started("WHILE visodom.failures < 2 MAX 50\n  TURN angle_deg=1\nEND\n");
    int failures = 0;
    std::vector<std::string> sent = RunScripted(it, [&](const Command&) {
      it.OnVisOdomFailures(++failures);
      return Outcome::Nominal();
    });
    EXPECT_EQ(sent.size(), 2u);
  }
  {  // false from the start: the body never runs
    Interpreter it = Started("WHILE elapsed > 1 h MAX 5\n  TURN angle_deg=1\nEND\nSTOP\n");
    EXPECT_EQ(RunScripted(it, Nominal), (std::vector<std::string>{"STOP"}));
  }
}

TEST(Interpreter, WaitEndsOnTheRunClock) {
  Interpreter it = Started("WAIT 5 s\nSTOP\n");
  StepOutput a = it.Step(T(10));  // started at 0, first stepped at 10: the wait starts now
  EXPECT_FALSE(a.command.has_value());
  ASSERT_TRUE(a.wake_at.has_value());
  EXPECT_EQ(*a.wake_at, T(15));
  EXPECT_EQ(a.status.step, 1);
  EXPECT_EQ(a.status.step_text, "WAIT 5 s");
  EXPECT_FALSE(it.Step(T(14.999)).command.has_value());
  StepOutput b = it.Step(T(15));
  ASSERT_TRUE(b.command.has_value());
  EXPECT_EQ(b.command->kind, CommandKind::kStop);
  EXPECT_EQ(b.status.step, 2);
}

TEST(Interpreter, ZeroWaitAndControlStatementsRunWithinOneStep) {
  Interpreter it = Started("WAIT 0\nIF elapsed >= 0\n  REPEAT 2\n    WAIT 0\n  END\nEND\nSTOP\n");
  StepOutput a = it.Step(T(0));
  ASSERT_TRUE(a.command.has_value());
  EXPECT_EQ(a.command->step, 3);
}

TEST(Interpreter, WaitUntilHoldsUntilTheConditionOrTimesOut) {
  {
    Interpreter it = Started("WAIT UNTIL visodom.failures >= 2 TIMEOUT 10 s\nSTOP\n");
    EXPECT_FALSE(it.Step(T(0)).command.has_value());
    it.OnVisOdomFailures(1);
    EXPECT_FALSE(it.Step(T(3)).command.has_value());
    it.OnVisOdomFailures(2);
    EXPECT_TRUE(it.Step(T(4)).command.has_value());
  }
  {
    Interpreter it = Started("WAIT UNTIL elapsed >= 30 s TIMEOUT 10 s\nSTOP\n");
    EXPECT_FALSE(it.Step(T(5)).command.has_value());
    StepOutput late = it.Step(T(15));
    EXPECT_FALSE(late.command.has_value());
    EXPECT_EQ(late.status.state, SequenceState::kFailed);
    EXPECT_EQ(late.status.failed_step, 1);
    EXPECT_EQ(late.status.failed_outcome.termination, Termination::kNone);
    EXPECT_EQ(late.status.message,
              "step 1 (line 1: WAIT UNTIL elapsed >= 30 s TIMEOUT 10 s) failed: WAIT UNTIL timed "
              "out after 10 s");
  }
  {  // elapsed counts from Start
    Interpreter it = Started("WAIT UNTIL elapsed >= 30 s TIMEOUT 1 min\nSTOP\n");
    EXPECT_FALSE(it.Step(T(29)).command.has_value());
    EXPECT_TRUE(it.Step(T(30)).command.has_value());
  }
}

TEST(Interpreter, StopCancelsTheOutstandingCommandAndRunsTheAbortBlock) {
  Interpreter it = Started("ON_ABORT\n  STOP\nEND\nAUTONAV goal=(20, 0)\nTURN angle_deg=5\n");
  StepOutput a = it.Step(T(0));
  ASSERT_TRUE(a.command.has_value());
  StepOutput s = it.Stop(T(7), "operator");
  ASSERT_TRUE(s.cancel.has_value());
  EXPECT_EQ(s.cancel->id, a.command->id);
  ASSERT_TRUE(s.command.has_value());
  EXPECT_EQ(s.command->kind, CommandKind::kStop);
  EXPECT_EQ(s.status.state, SequenceState::kAborting);
  // The cancelled command's late result is refused, the abort block's is taken.
  EXPECT_FALSE(it.OnCommandResult(a.command->id, Outcome::Nominal()).ok());
  ASSERT_TRUE(it.OnCommandResult(s.command->id, Outcome::Nominal()).ok());
  StepOutput end = it.Step(T(8));
  EXPECT_EQ(end.status.state, SequenceState::kAborted);
  EXPECT_EQ(end.status.message, "stopped at step 2 (line 4): operator");
  EXPECT_EQ(end.status.failed_step, 0);
  EXPECT_FALSE(it.Stop(T(9), "again").cancel.has_value());  // idle: no effect
  EXPECT_EQ(it.status().state, SequenceState::kAborted);
}

TEST(Interpreter, ASecondStopEndsTheAbortBlock) {
  Interpreter it = Started("ON_ABORT\n  ARM STOW\n  STOP\nEND\nAUTONAV goal=(20, 0)\n");
  it.Step(T(0));
  StepOutput s = it.Stop(T(1), "operator");
  ASSERT_TRUE(s.command.has_value());
  StepOutput again = it.Stop(T(2), "now");
  ASSERT_TRUE(again.cancel.has_value());
  EXPECT_EQ(again.cancel->kind, CommandKind::kArmStow);
  EXPECT_EQ(again.status.state, SequenceState::kAborted);
  EXPECT_EQ(again.status.message, "stopped at step 3 (line 5): operator; ON_ABORT stopped: now");
}

TEST(Interpreter, AFailureInsideTheAbortBlockEndsIt) {
  Interpreter it = Started("ON_ABORT\n  ARM STOW\n  STOP\nEND\nTURN angle_deg=1\n");
  auto sent = RunScripted(it, [](const Command& c) {
    if (c.kind == CommandKind::kTurn) return Outcome::Failed(Fault(MF::kSuspension), "contact");
    return Outcome::Failed(Fault::Other(), "body");
  });
  EXPECT_EQ(sent, (std::vector<std::string>{"TURN angle_deg=1", "ARM STOW"}));
  EXPECT_EQ(it.status().state, SequenceState::kFailed);
  EXPECT_EQ(it.status().failed_step, 3);
  EXPECT_EQ(it.status().message,
            "step 3 (line 5: TURN angle_deg=1) failed: SUSPENSION (motion error): contact; "
            "ON_ABORT step 1 (line 2: ARM STOW) failed: OTHER (goal error): body");
}

TEST(Interpreter, NoResultInTimeFailsTheStepAndCancelsIt) {
  InterpreterOptions o;
  o.result_margin_s = 5.0;
  o.default_result_timeout_s = 100.0;
  Interpreter it = Started("TURN angle_deg=1 timeout=10 s\nSTOP\n", o);
  StepOutput a = it.Step(T(0));
  EXPECT_FALSE(it.Step(T(14.9)).cancel.has_value());
  StepOutput late = it.Step(T(15));
  ASSERT_TRUE(late.cancel.has_value());
  EXPECT_EQ(late.cancel->id, a.command->id);
  EXPECT_EQ(late.status.state, SequenceState::kFailed);
  EXPECT_EQ(late.status.message,
            "step 1 (line 1: TURN angle_deg=1 timeout=10 s) failed: no result within 15 s");

  Interpreter d = Started("STOP\n", o);  // no timeout argument: the default
  d.Step(T(0));
  EXPECT_EQ(d.Step(T(99)).status.state, SequenceState::kRunning);
  EXPECT_EQ(d.Step(T(100)).status.state, SequenceState::kFailed);
}

PoseSample PoseAt(double t, double x, double y, double yaw = 0.0) {
  PoseSample p;
  p.stamp = T(t);
  p.position = {x, y, 0.0};
  p.yaw = yaw;
  return p;
}

TEST(Interpreter, TurnToUsesTheLatestPose) {
  Interpreter it = Started("TARGET rock = (2, 2, 0)\nTURN TO rock\n");
  it.OnPose(PoseAt(0, 0, 0, 90 * kDegree));
  StepOutput a = it.Step(T(0.5));
  ASSERT_TRUE(a.command.has_value());
  EXPECT_NEAR(std::get<MobilityRequest>(a.command->request).angle, -45 * kDegree, 1e-12);
}

TEST(Interpreter, ConditionsOnThePoseWaitForOneNewerThanTheLastCommand) {
  InterpreterOptions o;
  o.pose_wait_s = 3.0;
  Interpreter it = Started(
      "TARGET t = (5, 0, 0)\nDRIVE STRAIGHT distance=1\n"
      "IF distance_to(t) > 3\n  TURN angle_deg=1\nELSE\n  STOP\nEND\n",
      o);
  it.OnPose(PoseAt(0, 0, 0));
  StepOutput a = it.Step(T(0));
  // The drive ends at t = 20; a pose from before then must not decide the IF.
  ASSERT_TRUE(it.OnCommandResult(a.command->id, Outcome::Nominal(T(20))).ok());
  it.OnPose(PoseAt(19.9, 0.9, 0));
  StepOutput b = it.Step(T(20));
  EXPECT_FALSE(b.command.has_value());
  ASSERT_TRUE(b.wake_at.has_value());
  EXPECT_EQ(*b.wake_at, T(23));
  it.OnPose(PoseAt(20.5, 2.5, 0));  // 2.5 m from the target
  StepOutput c = it.Step(T(20.6));
  ASSERT_TRUE(c.command.has_value());
  EXPECT_EQ(c.command->kind, CommandKind::kStop);
}

TEST(Interpreter, NoUsablePoseFailsTheStepAfterPoseWait) {
  InterpreterOptions o;
  o.pose_wait_s = 2.0;
  o.max_pose_age_s = 1.0;
  {
    Interpreter it = Started("TARGET t = (5, 0, 0)\nTURN TO t\n", o);
    EXPECT_FALSE(it.Step(T(0)).command.has_value());
    StepOutput late = it.Step(T(2));
    EXPECT_EQ(late.status.state, SequenceState::kFailed);
    EXPECT_EQ(late.status.message,
              "step 1 (line 2: TURN TO t) failed: TURN TO t needs a pose estimate; none has been "
              "received (waited 2 s)");
  }
  {  // a stale pose is no pose
    Interpreter it = Started("IF tilt > 20\n  STOP\nEND\nTURN angle_deg=1\n", o);
    it.OnPose(PoseAt(0, 0, 0));
    EXPECT_FALSE(it.Step(T(5)).command.has_value());
    StepOutput late = it.Step(T(7));
    EXPECT_EQ(late.status.state, SequenceState::kFailed);
    EXPECT_EQ(late.status.message,
              "line 1 (IF tilt > 20) failed: the condition 'tilt > 20' needs a pose estimate; "
              "the latest is 7 s old (waited 2 s)");
    EXPECT_EQ(late.status.failed_step, 0);
    EXPECT_EQ(late.status.failed_line, 1);
  }
  {  // invalid and non-finite poses are ignored
    Interpreter it = Started("IF tilt > 20\n  STOP\nEND\nTURN angle_deg=1\n", o);
    PoseSample bad = PoseAt(0, 0, 0);
    bad.valid = false;
    it.OnPose(bad);
    bad = PoseAt(0, std::nan(""), 0);
    it.OnPose(bad);
    it.Step(T(0));
    EXPECT_EQ(it.Step(T(2)).status.state, SequenceState::kFailed);
  }
}

TEST(Interpreter, TiltAndDistanceConditions) {
  Interpreter it = Started(
      "TARGET rock = (3, 0, 0)\n"
      "IF tilt > 15 deg\n  STOP\nELSE IF distance_to(rock) < 1.1\n  TURN angle_deg=1\nEND\n");
  PoseSample p = PoseAt(0, 2.0, 0.0);
  p.pitch = 10 * kDegree;
  it.OnPose(p);
  StepOutput a = it.Step(T(0.1));
  ASSERT_TRUE(a.command.has_value());
  EXPECT_EQ(a.command->kind, CommandKind::kTurn);
}

TEST(Interpreter, ResultErrorsAreRefusedOrFailTheStep) {
  Interpreter it = Started("TURN angle_deg=1\nSTOP\n");
  EXPECT_EQ(it.OnCommandResult(1, Outcome::Nominal()).code(), StatusCode::kFailedPrecondition);
  StepOutput a = it.Step(T(0));
  EXPECT_EQ(it.OnCommandResult(a.command->id + 5, Outcome::Nominal()).code(),
            StatusCode::kInvalidArgument);
  EXPECT_TRUE(it.busy());
  Outcome bad = Outcome::Nominal();
  bad.fault = Fault(MF::kTilt);
  EXPECT_EQ(it.OnCommandResult(a.command->id, bad).code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(it.status().state, SequenceState::kFailed);
  EXPECT_EQ(it.status().message,
            "step 1 (line 1: TURN angle_deg=1) failed: its service reported an inconsistent "
            "outcome: outcome NOMINAL carries fault TILT");
}

TEST(Interpreter, StartRefusesWhileBusyAndRestartsAfterwards) {
  Interpreter it = Started("TURN angle_deg=1\n");
  StepOutput a = it.Step(T(0));
  Status busy = it.Start(MustParse("STOP\n"), T(1));
  EXPECT_EQ(busy.code(), StatusCode::kBusy);
  EXPECT_EQ(busy.message(), "a sequence is running (step 1); stop it before starting another");
  ASSERT_TRUE(it.OnCommandResult(a.command->id, Outcome::Nominal()).ok());
  EXPECT_EQ(it.Step(T(1)).status.state, SequenceState::kDone);
  ASSERT_TRUE(it.Start(MustParse("STOP\n"), T(2)).ok());
  StepOutput b = it.Step(T(2));
  ASSERT_TRUE(b.command.has_value());
  EXPECT_GT(b.command->id, a.command->id);  // ids never repeat, so old results cannot match
  EXPECT_EQ(b.status.dispatched, 1u);
  EXPECT_EQ(it.Start(Sequence{}, T(3)).code(), StatusCode::kBusy);
  Interpreter fresh = Make();
  EXPECT_EQ(fresh.Start(Sequence{}, T(0)).message(),
            "sequence '' has no statements to run");
  EXPECT_EQ(fresh.status().state, SequenceState::kIdle);
  EXPECT_EQ(fresh.Step(T(0)).status.state, SequenceState::kIdle);
}

TEST(Interpreter, ControlStepsPerCallAreBounded) {
  InterpreterOptions o;
  o.max_control_steps = 1000;
  Interpreter it =
      Started("REPEAT 10000\n  REPEAT 10000\n    WAIT 0\n  END\nEND\nSTOP\n", o);
  StepOutput a = it.Step(T(0));
  EXPECT_EQ(a.status.state, SequenceState::kFailed);
  EXPECT_NE(a.status.message.find("more than 1000 control statements without a command or wait"),
            std::string::npos);
}

/// The services on a run clock, as the apl-sequencer service would see them: each command ends
/// `kCommandS` after it went out (a mobility STRAIGHT moves the rover, or not on a fault); the
/// pose estimate arrives every second (at k + 0.5 s) and the VisOdom failure count after each
/// VISODOM command. Inputs go to the interpreter in time order and Step() follows each, as the
/// service's subscriptions and timer do.
class FakeStatusStream {
 public:
  static constexpr double kCommandS = 5.25;  // never on a pose tick

  struct Dispatch {
    double sent;      // [s] run clock
    double answered;  // [s] when its result came (-1: none)
    std::string text;
  };

  FakeStatusStream(double pitch, std::function<Outcome(const Command&)> answer,
                   std::function<bool(int visodom_command)> vo_fails)
      : answer_(std::move(answer)), vo_fails_(std::move(vo_fails)) {
    pose_.pitch = pitch;
    for (int k = 0; k < 400; ++k) {
      events_.emplace(k + 0.5, [this](double t) {
        pose_.stamp = T(t);
        it_->OnPose(pose_);
      });
    }
  }

  std::vector<Dispatch> Run(Interpreter& it) {
    it_ = &it;
    double t = 0.0;
    Step(t);
    for (int guard = 0; guard < 10000 && it.busy() && !events_.empty(); ++guard) {
      const double next = events_.begin()->first;
      if (wake_ && *wake_ <= next) {
        t = *wake_;
      } else {
        t = next;
        auto apply = std::move(events_.begin()->second);
        events_.erase(events_.begin());
        apply(t);
      }
      Step(t);
    }
    EXPECT_FALSE(it.busy());
    return sent_;
  }

 private:
  void Step(double t) {
    StepOutput out = it_->Step(T(t));
    wake_.reset();
    if (out.wake_at) wake_ = out.wake_at->seconds();
    if (!out.command) return;
    // Event-driven: nothing goes out before the previous command has answered.
    if (!sent_.empty()) {
      EXPECT_GE(sent_.back().answered, 0.0) << out.command->text;
      EXPECT_LE(sent_.back().answered, t) << out.command->text;
    }
    sent_.push_back({t, -1.0, out.command->text});
    const std::size_t index = sent_.size() - 1;
    const Command c = *out.command;
    events_.emplace(t + kCommandS, [this, c, index](double done) {
      Outcome o = answer_(c);
      o.stamp = T(done);
      if (const auto* m = std::get_if<MobilityRequest>(&c.request)) {
        if (m->primitive == msg::DrivePrimitive::kStraight && o.termination == Termination::kNominal) {
          pose_.position.x += m->distance;
        }
        if (m->mode == msg::MobilityMode::kVisOdom && vo_fails_(++visodom_commands_)) {
          it_->OnVisOdomFailures(++vo_failures_);
        }
      }
      sent_[index].answered = done;
      EXPECT_TRUE(it_->OnCommandResult(c.id, o).ok()) << c.text;
    });
  }

  std::function<Outcome(const Command&)> answer_;
  std::function<bool(int)> vo_fails_;
  Interpreter* it_ = nullptr;
  std::multimap<double, std::function<void(double)>> events_;
  std::optional<double> wake_;
  std::vector<Dispatch> sent_;
  PoseSample pose_;
  int visodom_commands_ = 0;
  int vo_failures_ = 0;
};

// Every construct on one time-ordered stream of statuses: dispatch only after the previous
// command completed, a WHILE on the distance bounded by MAX, a goal error let through by
// on_fault=CONTINUE, an IF on the VisOdom failure count with a WAIT, IF / ELSE on tilt, and a
// motion error that runs the ON_ABORT block and ends FAILED.
TEST(Interpreter, AStatusStreamDrivesEveryConstruct) {
  const std::string text =
      "ON_ABORT\n  STOP\n  MAST pan_deg=0 tilt_deg=-30\nEND\n"
      "TARGET rock = (3, 0, 0)\n"
      "MAST LOOK_AT rock\n"
      "WHILE distance_to(rock) > 1.3 m MAX 6\n"
      "  VISODOM STRAIGHT distance=0.5 on_fault=CONTINUE\n"
      "  IF visodom.failures >= 2\n    WAIT 10 s\n  END\n"
      "END\n"
      "IF tilt > 20 deg\n  STOP\nELSE\n  ARM UNSTOW\nEND\n"
      "DRIVE STRAIGHT distance=1\n";
  // The second VISODOM step makes no progress (a goal error); the drive at the end hits a
  // motor fault. VisOdom fails on the 3rd and 4th VISODOM commands.
  auto answer = [visodom = 0](const Command& c) mutable {
    if (c.kind == CommandKind::kVisodomStraight && ++visodom == 2) {
      return Outcome::Failed(Fault(MF::kNoProgress), "stuck");
    }
    if (c.kind == CommandKind::kDriveStraight) return Outcome::Failed(Fault(MF::kMot), "stall");
    return Outcome::Nominal();
  };
  auto vo_fails = [](int n) { return n == 3 || n == 4; };

  {  // level: the ELSE branch
    Interpreter it = Started(text);
    FakeStatusStream stream(0.0, answer, vo_fails);
    const auto sent = stream.Run(it);
    std::vector<std::string> texts;
    for (const auto& d : sent) texts.push_back(d.text);
    // 3 m to go, 0.5 m per nominal step, the 2nd step stuck: 5 steps reach 1.0 m (<= 1.3).
    EXPECT_EQ(texts, (std::vector<std::string>{
                         "MAST LOOK_AT rock",
                         "VISODOM STRAIGHT distance=0.5 on_fault=CONTINUE",
                         "VISODOM STRAIGHT distance=0.5 on_fault=CONTINUE",
                         "VISODOM STRAIGHT distance=0.5 on_fault=CONTINUE",
                         "VISODOM STRAIGHT distance=0.5 on_fault=CONTINUE",
                         "VISODOM STRAIGHT distance=0.5 on_fault=CONTINUE", "ARM UNSTOW",
                         "DRIVE STRAIGHT distance=1", "STOP", "MAST pan_deg=0 tilt_deg=-30"}));
    ASSERT_EQ(sent.size(), 10u);
    // A command whose dispatch follows a condition on the pose goes out once a pose newer
    // than the previous answer has come: the next tick at .5 s past a second, 0.25 s after the
    // mast's answer and 0.75 s after each step's. After the 4th and 5th VISODOM steps the
    // failure count is 2, so WAIT 10 s comes first (the pose is fresh by then). The rest (DRIVE
    // after ARM UNSTOW, the abort block) need no pose and go at once.
    const std::vector<double> gaps = {0.25, 0.75, 0.75, 0.75, 10.0, 10.0, 0.0, 0.0, 0.0};
    for (std::size_t k = 1; k < sent.size(); ++k) {
      SCOPED_TRACE(sent[k].text);
      EXPECT_DOUBLE_EQ(sent[k].sent - sent[k - 1].answered, gaps[k - 1]) << k;
    }
    EXPECT_EQ(it.status().state, SequenceState::kFailed);
    EXPECT_EQ(it.status().failed_outcome.fault, Fault(MF::kMot));
    EXPECT_EQ(it.status().message,
              "step 8 (line 18: DRIVE STRAIGHT distance=1) failed: MOT (motion error): stall");
  }
  {  // tilted 25 deg: the IF branch
    Interpreter it = Started(text);
    FakeStatusStream stream(25 * kDegree, answer, vo_fails);
    const auto sent = stream.Run(it);
    ASSERT_EQ(sent.size(), 10u);
    EXPECT_EQ(sent[6].text, "STOP");
  }
  {  // the loop bound: MAX 6 with a rover that never moves
    Interpreter it = Started(text);
    FakeStatusStream stream(
        0.0, [](const Command& c) {
          return c.kind == CommandKind::kVisodomStraight
                     ? Outcome::Failed(Fault(MF::kNoProgress), "stuck")
                     : Outcome::Nominal();
        },
        [](int) { return false; });
    const auto sent = stream.Run(it);
    ASSERT_EQ(sent.size(), 9u);  // MAST, 6 steps, ARM UNSTOW, DRIVE
    EXPECT_EQ(sent[7].text, "ARM UNSTOW");
    EXPECT_EQ(it.status().state, SequenceState::kDone);
  }
}

TEST(Interpreter, StateNames) {
  EXPECT_STREQ(SequenceStateName(SequenceState::kAborting), "ABORTING");
  EXPECT_TRUE(IsTerminal(SequenceState::kAborted));
  EXPECT_FALSE(IsTerminal(SequenceState::kRunning));
}

TEST(InterpreterOptions, ValidateAndParameters) {
  EXPECT_TRUE(InterpreterOptions{}.Validate().ok());
  InterpreterOptions o;
  o.max_pose_age_s = 0.0;
  EXPECT_EQ(o.Validate().message(), "max_pose_age_s = 0 s is outside (0, inf)");
  EXPECT_FALSE(Interpreter::Create(o).ok());

  ParamSet params("apl-sequencer");
  DeclareParams<InterpreterOptions>(params, "sequencer.");
  ASSERT_TRUE(params.SetFromString("sequencer.pose_wait_s=7.5").ok());
  Result<InterpreterOptions> read = ReadParams<InterpreterOptions>(params, "sequencer.");
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_DOUBLE_EQ(read->pose_wait_s, 7.5);
  EXPECT_DOUBLE_EQ(read->result_margin_s, 60.0);
}

}  // namespace
}  // namespace rover::apl::sequencer
