// The directed task against a fake drive service on an isolated DDS domain: no processes. The
// fake answers each dl/drive_command with a scripted terminal dl/drive_status after a scripted
// simulated time; the clock advances one step per pass of the run loop, so runs are repeatable.
#include "rover/deploy/runner/tasks/directed_task.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "run_fixture.hpp"

namespace rover::deploy::runner {
namespace {
using testing::RunFixture;
using testing::ScriptedClock;

struct Reply {
  rover_dl_DriveState state = rover_dl_DRIVE_DONE;
  rover_dl_DriveTermination termination = rover_dl_TERMINATION_NOMINAL;
  std::string message;
  double after_s = 1.0;  ///< simulated seconds after the command
};

class FakeDrive {
 public:
  FakeDrive(int domain, ScriptedClock* clock) : clock_(clock) {
    participant_ = dds::Participant::Create(domain).value();
    commands_ =
        dds::Reader<rover_dl_DriveCommand>::Create(participant_, "dl/drive_command").value();
    status_ = dds::Writer<rover_dl_DriveStatus>::Create(participant_, "dl/drive_status").value();
  }

  // One pass: time moves on, commands are heard, due statuses are sent.
  void Step() {
    clock_->Tick();
    for (auto& c : commands_.Take()) {
      received.push_back(c.data());
      if (c->primitive == rover_dl_PRIMITIVE_STOP && running_) {
        // As dl-locomotion does: a STOP ends the running primitive with STOP_COMMAND.
        Send(*running_, {rover_dl_DRIVE_FAILED, rover_dl_TERMINATION_STOP_COMMAND, "stopped", 0});
        running_.reset();
        continue;
      }
      running_ = c->command_id;
      started_at_ = clock_->now();
    }
    if (running_ && !silent_.count(*running_)) {
      const Reply r = script.count(*running_) ? script[*running_] : Reply{};
      if (clock_->now() - started_at_ >= r.after_s - 1e-9) {
        Send(*running_, r);
        running_.reset();
      }
    }
  }
  void NeverAnswer(std::uint32_t id) { silent_.insert(id); }

  std::map<std::uint32_t, Reply> script;
  std::vector<rover_dl_DriveCommand> received;

 private:
  void Send(std::uint32_t id, const Reply& r) {
    rover_dl_DriveStatus s{};
    s.command_id = id;
    s.state = r.state;
    s.termination = r.termination;
    dds::CopyString(s.message, r.message);
    (void)status_.Write(s);
  }

  ScriptedClock* clock_;
  dds::Participant participant_;
  dds::Reader<rover_dl_DriveCommand> commands_;
  dds::Writer<rover_dl_DriveStatus> status_;
  std::optional<std::uint32_t> running_;
  double started_at_ = 0;
  std::set<std::uint32_t> silent_;
};

DriveStep Step(Primitive p, double distance, double curvature = 0, double angle = 0) {
  DriveStep s;
  s.primitive = p;
  s.distance = distance;
  s.curvature = curvature;
  s.angle = angle;
  return s;
}

DirectedTaskSpec ThreeSteps() {
  DirectedTaskSpec spec;
  spec.steps.push_back(Step(Primitive::kStraight, 4));
  spec.steps.push_back(Step(Primitive::kArc, 2, 0.5));
  spec.steps.push_back(Step(Primitive::kTurnInPlace, 0, 0, M_PI / 2));
  return spec;
}

class DirectedTaskTest : public ::testing::Test {
 protected:
  explicit DirectedTaskTest(LoopLimits limits = testing::Limits())
      : run_(limits), clock_(run_.participant()), drive_(run_.domain(), &clock_) {
    // The fake drive service lives in the loop: one step per pass.
    run_.loop().AddCheck([this] {
      drive_.Step();
      return std::string();
    });
  }
  // Opens the task and waits, as the runner does, until the drive service hears it.
  TaskOutcome Run(DirectedTask& task) {
    TaskContext ctx = run_.Context();
    EXPECT_TRUE(task.Open(ctx).ok());
    EXPECT_EQ(ctx.WaitUntil([&] { return task.Ready(); }), "");
    return task.Run(ctx);
  }
  // Runs ThreeSteps() with step `index` expecting `expect`.
  TaskOutcome RunExpecting(std::size_t index, const std::string& expect) {
    DirectedTaskSpec spec = ThreeSteps();
    spec.steps[index].expect = expect;
    DirectedTask task(spec, 0, 0, 0);
    return Run(task);
  }
  RunFixture run_;
  ScriptedClock clock_;
  FakeDrive drive_;
};

TEST_F(DirectedTaskTest, OneCommandPerStepEachAfterTheLastEnded) {
  DirectedTask task(ThreeSteps(), 0, 0, 0);
  const TaskOutcome out = Run(task);
  EXPECT_EQ(out.failure, "");
  ASSERT_EQ(out.steps.size(), 3u);
  ASSERT_EQ(drive_.received.size(), 3u);
  const char* names[] = {"straight", "arc", "turn_in_place"};
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(out.steps[i].command_id, i + 1);
    EXPECT_EQ(out.steps[i].primitive, names[i]);
    EXPECT_EQ(out.steps[i].state, "done");
    EXPECT_EQ(out.steps[i].termination, "nominal");
    EXPECT_GE(out.steps[i].sim_end_s - out.steps[i].sim_start_s, 1.0 - 1e-9);
    if (i > 0) {
      EXPECT_GE(out.steps[i].sim_start_s, out.steps[i - 1].sim_end_s);
    }
    EXPECT_EQ(drive_.received[i].command_id, i + 1);
  }
  // The command carries the step: a straight has no curvature, an arc its own.
  EXPECT_EQ(drive_.received[0].primitive, rover_dl_PRIMITIVE_STRAIGHT);
  EXPECT_EQ(drive_.received[0].distance, 4);
  EXPECT_EQ(drive_.received[1].primitive, rover_dl_PRIMITIVE_ARC);
  EXPECT_EQ(drive_.received[1].curvature, 0.5);
  EXPECT_EQ(drive_.received[2].primitive, rover_dl_PRIMITIVE_TURN_IN_PLACE);
  EXPECT_NEAR(drive_.received[2].angle, M_PI / 2, 1e-12);
  EXPECT_EQ(run_.notes, (std::vector<std::string>{"step 1/3 straight", "step 2/3 arc",
                                                  "step 3/3 turn_in_place"}));
}

TEST_F(DirectedTaskTest, AnUnexpectedFaultFailsTheRunAndEndsTheSequence) {
  drive_.script[2] = {rover_dl_DRIVE_FAILED, rover_dl_TERMINATION_TILT, "tilt 31 deg", 0.5};
  DirectedTask task(ThreeSteps(), 0, 0, 0);
  const TaskOutcome out = Run(task);
  EXPECT_EQ(out.failure, "step 2 (arc) ended failed (tilt): tilt 31 deg");
  ASSERT_EQ(out.steps.size(), 2u);
  EXPECT_EQ(out.steps[1].state, "failed");
  EXPECT_EQ(drive_.received.size(), 2u);  // step 3 never sent
}

TEST_F(DirectedTaskTest, AnExpectedFaultPassesAndEndsTheSequence) {
  drive_.script[2] = {rover_dl_DRIVE_FAILED, rover_dl_TERMINATION_TILT, "", 0.5};
  const TaskOutcome out = RunExpecting(1, "tilt");
  EXPECT_EQ(out.failure, "");
  EXPECT_EQ(out.steps.size(), 2u);
  EXPECT_EQ(drive_.received.size(), 2u);
}

TEST_F(DirectedTaskTest, ExpectingAFaultThatDoesNotComeFails) {
  const TaskOutcome out = RunExpecting(0, "timeout");
  EXPECT_EQ(out.failure, "step 1 (straight) ended done (nominal), expected timeout");
  EXPECT_EQ(out.steps.size(), 1u);
}

TEST_F(DirectedTaskTest, StopAfterSendsAStopThatEndsTheStep) {
  drive_.NeverAnswer(1);
  DirectedTaskSpec spec;
  spec.steps.push_back(Step(Primitive::kStraight, 9));
  spec.steps[0].stop_after_s = 2;
  spec.steps[0].expect = "stop_command";
  DirectedTask task(spec, 0, 0, 0);
  const TaskOutcome out = Run(task);
  EXPECT_EQ(out.failure, "");
  ASSERT_EQ(out.steps.size(), 1u);
  EXPECT_EQ(out.steps[0].termination, "stop_command");
  EXPECT_GE(out.steps[0].sim_end_s - out.steps[0].sim_start_s, 2.0 - 1e-9);
  ASSERT_EQ(drive_.received.size(), 2u);
  EXPECT_EQ(drive_.received[1].primitive, rover_dl_PRIMITIVE_STOP);
  EXPECT_EQ(drive_.received[1].command_id, 1 + DirectedTask::kStopIdOffset);
}

class DirectedTaskBudgetTest : public DirectedTaskTest {
 protected:
  DirectedTaskBudgetTest() : DirectedTaskTest(testing::Limits(5)) {}
};

TEST_F(DirectedTaskBudgetTest, AStepCutShortByTheRunIsInterrupted) {
  drive_.NeverAnswer(2);
  DirectedTask task(ThreeSteps(), 0, 0, 0);
  const TaskOutcome out = Run(task);
  EXPECT_EQ(out.failure, "time budget of 5 simulated s exceeded");
  ASSERT_EQ(out.steps.size(), 2u);
  EXPECT_EQ(out.steps[0].state, "done");
  EXPECT_EQ(out.steps[1].state, "interrupted");
  EXPECT_GT(out.steps[1].sim_end_s, 5.0);
}

TEST(DirectedTaskParse, StepsAndTheirErrors) {
  const yaml::FileErrors err("s.yaml");
  auto parse = [&](const std::string& task_yaml) {
    Scenario s;
    s.file = "s.yaml";
    s.text = "name: x\n" + task_yaml;
    const YAML::Node root = YAML::Load(s.text);
    const YAML::Node section = root["task"];
    return ParseDirectedTask(TaskSource{s, section, err});
  };
  auto ok = parse(
      "task:\n  type: directed\n  steps:\n    - {primitive: straight, distance: 5}\n"
      "    - {primitive: turn_in_place, angle_deg: -90}\n"
      "    - {primitive: arc, curvature: 0.5, distance: 3, speed: 0.04, expect: tilt}\n"
      "  goal: {x: 3, y: 4}\n");
  ASSERT_TRUE(ok.ok()) << ok.status().message();
  ASSERT_EQ(ok->steps.size(), 3u);
  EXPECT_EQ(ok->steps[1].primitive, Primitive::kTurnInPlace);
  EXPECT_NEAR(ok->steps[1].angle, -M_PI / 2, 1e-12);
  EXPECT_EQ(ok->steps[2].speed, 0.04);
  EXPECT_EQ(ok->steps[2].expect, "tilt");
  EXPECT_EQ(ok->steps[2].line, 7);
  ASSERT_TRUE(ok->goal.has_value());

  auto err_of = [&](const std::string& steps) {
    return parse("task: {type: directed, steps: [" + steps + "]}\n").status().message();
  };
  EXPECT_EQ(err_of("{primitive: arc, distance: 1}"),
            "s.yaml:2: task.steps[]: 'arc' needs 'curvature'");
  EXPECT_EQ(err_of("{primitive: arc, distance: 1, curvature: 2}"),
            "s.yaml:2: task.steps[].curvature: 2 is out of range [-1, 1]");
  EXPECT_EQ(err_of("{primitive: stop, expect: tilted}"),
            "s.yaml:2: task.steps[].expect: 'tilted' is not one of: nominal, tilt, suspension, "
            "motor_stall, motor_current, motor_fault, timeout, stop_command, rejected_busy, "
            "rejected_invalid, stale_sensor (did you mean 'tilt'?)");
  EXPECT_EQ(err_of("{primitive: straigt, distance: 1}"),
            "s.yaml:2: task.steps[].primitive: 'straigt' is not one of: straight, arc, "
            "turn_in_place, steer, stop (did you mean 'straight'?)");
  EXPECT_EQ(err_of("{distance: 1}"), "s.yaml:2: task.steps[]: missing 'primitive'");
  EXPECT_EQ(err_of("{primitive: stop, sped: 1}"),
            "s.yaml:2: task.steps[]: unknown key 'sped' (did you mean 'speed'?) (known: primitive, "
            "distance, curvature, angle_deg, speed, timeout_s, stop_after_s, expect)");
  EXPECT_EQ(parse("task: {type: directed}\n").status().message(),
            "s.yaml:2: task.steps: a directed task needs a non-empty list of steps");
  EXPECT_EQ(parse("task: {type: directed, steps: [], gaol: {}}\n").status().message(),
            "s.yaml:2: task: unknown key 'gaol' (did you mean 'goal'?) (known: type, steps, goal)");
}

TEST(DirectedTaskPath, DeadReckonsTheSteps) {
  DirectedTaskSpec spec = ThreeSteps();
  spec.steps.push_back(Step(Primitive::kStraight, 1));
  spec.goal = TaskGoal{{9, 9}, 1};
  const auto path = DirectedPlannedPath(spec, 1, 2, 0);
  EXPECT_EQ(path.front(), Eigen::Vector2d(1, 2));
  EXPECT_EQ(path.size(), 1u + 40 + 20 + 10 + 1);  // 0.1 m points; the turn adds none; the goal
  EXPECT_NEAR(path[40].x(), 5, 1e-9);             // after the 4 m straight
  EXPECT_NEAR(path[40].y(), 2, 1e-9);
  // A 2 m arc of radius 2 turns by 1 rad: it ends at (5 + 2 sin 1, 2 + 2 (1 - cos 1)).
  // Midpoint steps of 0.1 m on a 2 m radius: within a millimetre of the exact arc.
  EXPECT_NEAR(path[60].x(), 5 + 2 * std::sin(1.0), 1e-3);
  EXPECT_NEAR(path[60].y(), 2 + 2 * (1 - std::cos(1.0)), 1e-3);
  // Then a quarter turn left and 1 m: heading 1 + pi/2.
  EXPECT_NEAR(path[70].x(), path[60].x() + std::cos(1 + M_PI / 2), 1e-6);
  EXPECT_NEAR(path[70].y(), path[60].y() + std::sin(1 + M_PI / 2), 1e-6);
  EXPECT_EQ(path.back(), Eigen::Vector2d(9, 9));
}

}  // namespace
}  // namespace rover::deploy::runner
