// The mobility tasks: parsing (every key, every bad value with file, line, key and value), the
// command they send, and runs against a fake mobility manager on an isolated DDS domain that
// answers apl/mobility_command with scripted statuses after scripted simulated times.
#include "rover/deploy/runner/tasks/mobility_task.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "run_fixture.hpp"

namespace rover::deploy::runner {
namespace {
using testing::RunFixture;
using testing::ScenarioWithTask;
using testing::ScriptedClock;

Result<MobilityTaskSpec> Parse(const std::string& task_yaml) {
  const Scenario s = ScenarioWithTask(task_yaml);
  const YAML::Node root = YAML::Load(s.text);
  const YAML::Node section = root["task"];
  const yaml::FileErrors err("s.yaml");
  const std::string type = section["type"].Scalar();
  const MobilityTaskType t = type == "autonav"         ? MobilityTaskType::kAutonav
                             : type == "goto_waypoint" ? MobilityTaskType::kGoToWaypoint
                             : type == "guarded"       ? MobilityTaskType::kGuarded
                                                       : MobilityTaskType::kGuardedArc;
  return ParseMobilityTask(TaskSource{s, section, err}, t);
}

std::string Error(const std::string& task_yaml) {
  return ValidateTask(ScenarioWithTask(task_yaml)).message();
}

TEST(MobilityTask, ParsesEveryKey) {
  auto spec = Parse(
      "task:\n"
      "  type: autonav\n"
      "  goal: {x: 25, y: -1, tolerance: 0.5}\n"
      "  visodom: true\n"
      "  think: stop_and_go\n"
      "  time_budget_s: 1200\n"
      "  max_steps: 80\n"
      "  max_tilt_deg: 20\n"
      "  keep_out:\n"
      "    - {name: crater, vertices: [[10, -2], [12, -2], [12, 2], [10, 2]]}\n"
      "  expect: KEEPOUT\n");
  ASSERT_TRUE(spec.ok()) << spec.status().message();
  EXPECT_EQ(spec->goal->xy, Eigen::Vector2d(25, -1));
  EXPECT_EQ(spec->goal->tolerance, 0.5);
  EXPECT_TRUE(spec->visodom);
  EXPECT_EQ(spec->think, msg::ThinkMode::kStopAndGo);
  EXPECT_EQ(spec->time_budget_s, 1200);
  EXPECT_EQ(spec->max_steps, 80);
  EXPECT_NEAR(spec->max_tilt, 20 * std::numbers::pi / 180, 1e-12);
  ASSERT_EQ(spec->keep_out.size(), 1u);
  EXPECT_EQ(spec->keep_out[0].name, "crater");
  EXPECT_EQ(spec->keep_out[0].vertices.size(), 4u);
  EXPECT_EQ(spec->expect, "KEEPOUT");

  auto guarded = Parse(
      "task:\n  type: guarded\n  primitives:\n    - {primitive: straight, distance: 6}\n"
      "    - {primitive: turn_in_place, angle_deg: 90}\n  expect: vetoed\n");
  ASSERT_TRUE(guarded.ok()) << guarded.status().message();
  ASSERT_EQ(guarded->primitives.size(), 2u);
  EXPECT_EQ(guarded->primitives[1].primitive, Primitive::kTurnInPlace);
  EXPECT_EQ(guarded->expect, "vetoed");
  EXPECT_EQ(guarded->think, msg::ThinkMode::kDefault);
  // Every registered type parses through the registry.
  for (const char* t : {"autonav", "goto_waypoint"}) {
    EXPECT_TRUE(ValidateTask(ScenarioWithTask(std::string("task: {type: ") + t +
                                              ", goal: {x: 5, y: 0}}\n"))
                    .ok())
        << t;
  }
  EXPECT_TRUE(ValidateTask(ScenarioWithTask(
                               "task: {type: guarded_arc, primitives: [{primitive: arc, "
                               "curvature: 0.5, distance: 2}]}\n"))
                  .ok());
}

TEST(MobilityTask, BadKeysAndValuesNameFileLineKeyAndValue) {
  EXPECT_EQ(Error("task: {type: autonav}\n"), "s.yaml:2: task: a 'autonav' task needs a 'goal'");
  EXPECT_EQ(Error("task: {type: guarded}\n"),
            "s.yaml:2: task.primitives: a 'guarded' task needs a list of 1..32 primitives");
  EXPECT_EQ(Error("task: {type: autonav, goal: {x: 1, y: 1}, primitives: []}\n"),
            "s.yaml:2: task: unknown key 'primitives' (known: type, visodom, think, "
            "time_budget_s, max_steps, max_tilt_deg, keep_out, expect, goal)");
  EXPECT_EQ(Error("task:\n  type: autonav\n  goal: {x: 1, y: 1}\n  expect: NOPTH\n"),
            "s.yaml:5: task.expect: 'NOPTH' is not one of: reached, ARB, ACM, POT, TOD, STOPPED, "
            "WAYPT_TIMEOUT, NOPATH, NOPROGRESS, BUSY, VISODOM, KEEPOUT, BAD_COMMAND, IMG, SAPP, "
            "MOT, DRIVE_TIMEOUT, TILT, SUSPENSION, NORTH, RESTART (did you mean 'NOPATH'?)");
  // vetoed is a guarded outcome only.
  EXPECT_NE(Error("task: {type: autonav, goal: {x: 1, y: 1}, expect: vetoed}\n")
                .find("task.expect: 'vetoed' is not one of"),
            std::string::npos);
  EXPECT_EQ(Error("task:\n  type: autonav\n  goal: {x: 1, y: 1}\n  think: fast\n"),
            "s.yaml:5: task.think: 'fast' is not one of: default, stop_and_go, "
            "drive_while_thinking");
  EXPECT_EQ(Error("task:\n  type: autonav\n  goal: {x: 1, y: 1}\n  visodom: maybe\n"),
            "s.yaml:5: task.visodom: 'maybe' is not one of: false, true");
  EXPECT_EQ(Error("task:\n  type: guarded_arc\n  primitives: [{primitive: arc, curvature: 1, "
                  "distance: 1}]\n  visodom: true\n"),
            "s.yaml:5: task.visodom: 'guarded_arc' has no VisOdom variant");
  EXPECT_EQ(Error("task:\n  type: autonav\n  goal: {x: 1, y: 1}\n  time_budget_s: -5\n"),
            "s.yaml:5: task.time_budget_s: -5 is out of range [0, 1e+06]");
  EXPECT_EQ(Error("task:\n  type: autonav\n  goal: {x: 1, y: 1}\n  max_steps: 2.5\n"),
            "s.yaml:5: task.max_steps: 2.5 is not a whole number");
  EXPECT_EQ(Error("task:\n  type: guarded\n  primitives:\n    - {primitive: steer, curvature: 1}\n"),
            "s.yaml:5: task.primitives[].primitive: 'steer' is not a mobility primitive "
            "(straight, arc, turn_in_place)");
  EXPECT_EQ(Error("task:\n  type: guarded\n  primitives:\n    - {primitive: arc, distance: 1}\n"),
            "s.yaml:5: task.primitives[]: 'arc' needs 'curvature'");
  EXPECT_EQ(Error("task:\n  type: guarded\n  primitives:\n    - {primitive: straight, distance: 1, "
                  "speed: 0.1}\n"),
            "s.yaml:5: task.primitives[]: unknown key 'speed' (known: primitive, distance, "
            "curvature, angle_deg)");
  const std::string zone = "task:\n  type: autonav\n  goal: {x: 1, y: 1}\n  keep_out:\n";
  EXPECT_EQ(Error(zone + "    - {name: z, vertices: [[0, 0], [1, 0]]}\n"),
            "s.yaml:6: task.keep_out[].vertices: zone 'z' has 2 vertices, a zone needs 3..16");
  EXPECT_EQ(Error(zone + "    - {name: bow, vertices: [[0, 0], [1, 1], [1, 0], [0, 1]]}\n"),
            "s.yaml:6: task.keep_out[].vertices: zone 'bow' is not a simple polygon: edges 0 and "
            "2 cross");
  EXPECT_EQ(Error(zone + "    - {name: flat, vertices: [[0, 0], [1, 0], [2, 0]]}\n"),
            "s.yaml:6: task.keep_out[].vertices: zone 'flat' is not a simple polygon: edges 0 "
            "and 2 overlap");
  EXPECT_EQ(Error(zone + "    - {name: z, vertices: [[0, 0], [1, nan], [1, 1]]}\n"),
            "s.yaml:6: task.keep_out[].vertices[].y: expected a finite number, got 'nan'");
  EXPECT_EQ(Error(zone + "    - {vertices: [[0, 0], [1, 0], [1, 1]]}\n"),
            "s.yaml:6: task.keep_out[]: missing 'name'");
}

TEST(MobilityTask, CommandCarriesModeGoalLimitsPrimitivesAndZones) {
  auto spec = Parse(
      "task:\n  type: autonav\n  goal: {x: 25, y: -1, tolerance: 0.5}\n  visodom: true\n"
      "  think: drive_while_thinking\n  time_budget_s: 600\n  max_steps: 40\n"
      "  keep_out: [{name: pit, vertices: [[10, -2], [12, -2], [12, 2]]}]\n");
  ASSERT_TRUE(spec.ok()) << spec.status().message();
  MobilityCommandStorage storage;
  const rover_apl_MobilityCommand c = MakeMobilityCommand(*spec, 7, 12.5, &storage);
  EXPECT_EQ(c.command_id, 7u);
  EXPECT_EQ(c.header.stamp_ns, Time::FromSeconds(12.5).ns);
  EXPECT_EQ(c.mode, rover_apl_MOBILITY_AUTONAV_VISODOM);
  EXPECT_EQ(c.goal.x, 25);
  EXPECT_EQ(c.goal.y, -1);
  EXPECT_EQ(c.tolerance, 0.5);
  EXPECT_EQ(c.time_budget_s, 600);
  EXPECT_EQ(c.max_steps, 40);
  EXPECT_EQ(c.think, rover_apl_THINK_DRIVE_WHILE_THINKING);  // on the wire
  ASSERT_EQ(c.keep_out._length, 1u);
  EXPECT_STREQ(c.keep_out._buffer[0].name, "pit");
  ASSERT_EQ(c.keep_out._buffer[0].vertices._length, 3u);
  EXPECT_EQ(c.keep_out._buffer[0].vertices._buffer[2].x, 12);
  EXPECT_EQ(c.primitives._length, 0u);

  for (const auto& [type, vo, mode] :
       std::vector<std::tuple<MobilityTaskType, bool, msg::MobilityMode>>{
           {MobilityTaskType::kAutonav, false, msg::MobilityMode::kAutoNav},
           {MobilityTaskType::kGoToWaypoint, false, msg::MobilityMode::kGoToWaypoint},
           {MobilityTaskType::kGoToWaypoint, true, msg::MobilityMode::kVisOdomGoToWaypoint},
           {MobilityTaskType::kGuarded, false, msg::MobilityMode::kGuarded},
           {MobilityTaskType::kGuarded, true, msg::MobilityMode::kGuardedVisOdom},
           {MobilityTaskType::kGuardedArc, false, msg::MobilityMode::kGuardedArc}}) {
    EXPECT_EQ(MobilityModeOf(type, vo), mode);
  }

  auto guarded = Parse(
      "task:\n  type: guarded\n  primitives:\n    - {primitive: arc, curvature: 0.5, distance: 3}\n"
      "    - {primitive: turn_in_place, angle_deg: -90}\n");
  ASSERT_TRUE(guarded.ok());
  const rover_apl_MobilityCommand g = MakeMobilityCommand(*guarded, 1, 0, &storage);
  ASSERT_EQ(g.primitives._length, 2u);
  EXPECT_EQ(g.primitives._buffer[0].primitive, rover_dl_PRIMITIVE_ARC);
  EXPECT_EQ(g.primitives._buffer[0].curvature, 0.5);
  EXPECT_EQ(g.primitives._buffer[0].distance, 3);
  EXPECT_EQ(g.primitives._buffer[1].primitive, rover_dl_PRIMITIVE_TURN_IN_PLACE);
  EXPECT_NEAR(g.primitives._buffer[1].angle, -std::numbers::pi / 2, 1e-12);
}

TEST(MobilityTask, OutcomesMatchTheirExpectation) {
  using F = msg::MobilityFault;
  using S = msg::MobilityState;
  msg::MobilityStatus s;
  s.state = S::kSucceeded;
  EXPECT_EQ(OutcomeName(s), "reached");
  EXPECT_TRUE(OutcomeMatches("reached", s));
  EXPECT_FALSE(OutcomeMatches("NOPATH", s));
  s.state = S::kFailed;
  s.fault = F::kNoPath;
  EXPECT_EQ(OutcomeName(s), "NOPATH");
  EXPECT_TRUE(OutcomeMatches("NOPATH", s));
  EXPECT_TRUE(OutcomeMatches("vetoed", s));
  EXPECT_FALSE(OutcomeMatches("reached", s));
  s.fault = F::kWaypointTimeout;
  EXPECT_EQ(OutcomeName(s), "WAYPT_TIMEOUT");  // core/msg's name
  EXPECT_TRUE(OutcomeMatches("WAYPT-TIMEOUT", s));  // MER's spelling, as seed 000 writes it
  EXPECT_FALSE(OutcomeMatches("vetoed", s));
  // The name-only form the kinematic tool uses agrees.
  EXPECT_TRUE(OutcomeNameMatches("vetoed", "NOPATH"));
  EXPECT_TRUE(OutcomeNameMatches("KEEPOUT", "KEEPOUT"));
  EXPECT_FALSE(OutcomeNameMatches("vetoed", "WAYPT_TIMEOUT"));
  EXPECT_FALSE(OutcomeNameMatches("reached", "NOPATH"));
  s.state = S::kRejected;
  s.fault = F::kNone;
  EXPECT_EQ(OutcomeName(s), "BAD_COMMAND");
  // A running status is never an outcome.
  s.state = S::kRunning;
  EXPECT_FALSE(OutcomeMatches("reached", s));
  // Every name is core/msg's, in its order.
  ASSERT_EQ(MobilityFaultNames().size(), static_cast<std::size_t>(msg::kMobilityFaultCount));
  for (int i = 0; i < msg::kMobilityFaultCount; ++i) {
    EXPECT_EQ(MobilityFaultNames()[static_cast<std::size_t>(i)],
              msg::MobilityFaultName(static_cast<F>(i)));
  }
  EXPECT_EQ(FaultClassProse(msg::FaultClass::kMotionError), "motion error");
  EXPECT_EQ(ScenarioSpelling(msg::MobilityModeName(msg::MobilityMode::kVisOdomGoToWaypoint)),
            "visodom_go_to_waypoint");
}

// A fake apl-mobility: hears commands, sends RUNNING at once and the scripted terminal status
// `after_s` simulated seconds later, with a goodness map and one arc vote on the way.
struct Script {
  rover_apl_MobilityState state = rover_apl_MOBILITY_SUCCEEDED;
  rover_apl_MobilityFault fault = rover_apl_MOBFAULT_NONE;
  rover_apl_FaultClass fault_class = rover_apl_FAULT_NONE;
  std::string message;
  double after_s = 2.0;
  bool answer = true;
};

class FakeMobility {
 public:
  FakeMobility(int domain, ScriptedClock* clock) : clock_(clock) {
    participant_ = dds::Participant::Create(domain).value();
    commands_ = dds::Reader<rover_apl_MobilityCommand>::Create(participant_, "apl/mobility_command")
                    .value();
    status_ =
        dds::Writer<rover_apl_MobilityStatus>::Create(participant_, "apl/mobility_status").value();
    map_ = dds::Writer<rover_apl_GoodnessMap>::Create(participant_, "apl/goodness_map").value();
    votes_ = dds::Writer<rover_apl_ArcVotes>::Create(participant_, "apl/arc_votes").value();
  }

  void Step() {
    clock_->Tick();
    commands_.TakeEach([&](const dds::Sample<rover_apl_MobilityCommand>& c) {
      Received r;
      r.command_id = c->command_id;
      r.mode = c->mode;
      r.goal = {c->goal.x, c->goal.y};
      r.tolerance = c->tolerance;
      r.time_budget_s = c->time_budget_s;
      r.zones = c->keep_out._length;
      r.primitives = c->primitives._length;
      received.push_back(r);
      if (c->mode == rover_apl_MOBILITY_STOP) {
        stopped = true;
        return;
      }
      running_ = c->command_id;
      started_at_ = clock_->now();
      Send(c->command_id, rover_apl_MOBILITY_RUNNING, rover_apl_MOBFAULT_NONE,
           rover_apl_FAULT_NONE, "");
      PublishMapAndVotes(c->command_id);
    });
    if (running_ && script.answer && clock_->now() - started_at_ >= script.after_s - 1e-9) {
      Send(*running_, script.state, script.fault, script.fault_class, script.message);
      running_.reset();
    }
  }

  struct Received {
    std::uint32_t command_id = 0;
    rover_apl_MobilityMode mode{};
    Eigen::Vector2d goal;
    double tolerance = 0, time_budget_s = 0;
    std::uint32_t zones = 0, primitives = 0;
  };
  std::vector<Received> received;
  Script script;
  bool stopped = false;

 private:
  void Send(std::uint32_t id, rover_apl_MobilityState state, rover_apl_MobilityFault fault,
            rover_apl_FaultClass cls, const std::string& message) {
    rover_apl_MobilityStatus s{};
    s.command_id = id;
    s.state = state;
    s.fault = fault;
    s.fault_class = cls;
    s.steps = 5;
    s.images = 6;
    s.distance_to_goal = state == rover_apl_MOBILITY_SUCCEEDED ? 0.3 : 4.0;
    dds::CopyString(s.message, message);
    (void)status_.Write(s);
  }
  void PublishMapAndVotes(std::uint32_t id) {
    rover_apl_GoodnessMap m{};
    m.origin_x = -1;
    m.origin_y = -1;
    m.resolution = 0.2;
    m.width = 10;
    m.height = 10;
    std::vector<std::uint8_t> good(100, 200), certainty(100, 255), flags(100, 1);
    good[55] = 0;
    dds::BorrowSequence(m.goodness, good);
    dds::BorrowSequence(m.certainty, certainty);
    dds::BorrowSequence(m.flags, flags);
    (void)map_.Write(m);
    rover_apl_ArcVotes v{};
    v.command_id = id;
    v.rover_pose.orientation.w = 1;
    std::vector<rover_apl_ArcVote> votes(2);
    votes[1].kind = rover_apl_CANDIDATE_ARC;
    votes[1].curvature = 0.25;
    votes[1].direction = 1;
    dds::BorrowSequence(v.votes, votes);
    v.chosen = 1;
    (void)votes_.Write(v);
  }

  ScriptedClock* clock_;
  dds::Participant participant_;
  dds::Reader<rover_apl_MobilityCommand> commands_;
  dds::Writer<rover_apl_MobilityStatus> status_;
  dds::Writer<rover_apl_GoodnessMap> map_;
  dds::Writer<rover_apl_ArcVotes> votes_;
  std::optional<std::uint32_t> running_;
  double started_at_ = 0;
};

class MobilityRunTest : public ::testing::Test {
 protected:
  MobilityRunTest() : clock_(run_.participant()), mobility_(run_.domain(), &clock_) {
    run_.loop().AddCheck([this] {
      mobility_.Step();
      return std::string();
    });
  }
  TaskOutcome Run(const std::string& task_yaml) {
    auto spec = Parse(task_yaml);
    EXPECT_TRUE(spec.ok()) << spec.status().message();
    task_ = std::make_unique<MobilityTask>(*spec, 1, 2, 0);
    TaskContext ctx = run_.Context();
    EXPECT_TRUE(task_->Open(ctx).ok());
    EXPECT_EQ(ctx.WaitUntil([&] { return task_->Ready(); }), "");
    TaskOutcome out = task_->Run(ctx);
    // Let the map and votes arrive, as the runner does after the task.
    const double until = run_.loop().now() + 0.5;
    (void)run_.loop().WaitUntil([&] { return run_.loop().now() >= until; });
    return out;
  }

  RunFixture run_;
  ScriptedClock clock_;
  FakeMobility mobility_;
  std::unique_ptr<MobilityTask> task_;
};

const char* kAutonav =
    "task:\n  type: autonav\n  goal: {x: 20, y: 3, tolerance: 0.5}\n  time_budget_s: 100\n";

TEST_F(MobilityRunTest, SendsOneCommandWaitsForItsVerdictAndPassesOnReached) {
  const TaskOutcome out = Run(kAutonav);
  EXPECT_EQ(out.failure, "");
  ASSERT_EQ(mobility_.received.size(), 1u);
  const auto& c = mobility_.received[0];
  EXPECT_EQ(c.command_id, MobilityTask::kCommandId);
  EXPECT_EQ(c.mode, rover_apl_MOBILITY_AUTONAV);
  EXPECT_EQ(c.goal, Eigen::Vector2d(20, 3));
  EXPECT_EQ(c.tolerance, 0.5);
  EXPECT_EQ(c.time_budget_s, 100);
  ASSERT_EQ(out.steps.size(), 1u);
  EXPECT_EQ(out.steps[0].primitive, "autonav");
  EXPECT_EQ(out.steps[0].state, "succeeded");
  EXPECT_EQ(out.steps[0].termination, "reached");
  // It waited the fake's 2 simulated seconds for the verdict, not less.
  EXPECT_GE(out.steps[0].sim_end_s - out.steps[0].sim_start_s, 2.0 - 1e-6);
  const RunResult& r = run_.result();
  ASSERT_TRUE(r.mobility.has_value());
  EXPECT_EQ(r.mobility->task, "autonav");
  EXPECT_EQ(r.mobility->outcome, "reached");
  EXPECT_EQ(r.mobility->fault, "NONE");
  EXPECT_EQ(r.mobility->fault_class, "none");
  EXPECT_EQ(r.mobility->steps, 5u);
  EXPECT_EQ(r.mobility->images, 6u);
  EXPECT_DOUBLE_EQ(r.mobility->distance_to_goal, 0.3);
  // The goodness map and the chosen arc were recorded.
  ASSERT_TRUE(r.mobility->last_map.has_value());
  EXPECT_EQ(r.mobility->last_map->width, 10);
  EXPECT_EQ(r.mobility->last_map->goodness[55], 0);
  ASSERT_EQ(r.mobility->arcs.size(), 1u);
  EXPECT_DOUBLE_EQ(r.mobility->arcs[0].curvature, 0.25);
  EXPECT_EQ(task_->PlannedPath(), (std::vector<Eigen::Vector2d>{{1, 2}, {20, 3}}));
}

TEST_F(MobilityRunTest, AFaultWhereReachedWasExpectedFailsTheRunNamingIt) {
  mobility_.script = {rover_apl_MOBILITY_FAILED, rover_apl_MOBFAULT_NOPATH,
                      rover_apl_FAULT_GOAL_ERROR, "every arc forbidden", 3.0, true};
  const TaskOutcome out = Run(kAutonav);
  EXPECT_EQ(out.failure,
            "autonav ended failed NOPATH (goal error), expected reached: every arc forbidden");
  EXPECT_EQ(run_.result().mobility->fault_class, "goal error");
  EXPECT_EQ(run_.result().mobility->outcome, "NOPATH");
}

TEST_F(MobilityRunTest, TheExpectedFaultPasses) {
  mobility_.script = {rover_apl_MOBILITY_FAILED, rover_apl_MOBFAULT_NOPROGRESS,
                      rover_apl_FAULT_GOAL_ERROR, "limit cycle", 3.0, true};
  const TaskOutcome out = Run(std::string(kAutonav) + "  expect: NOPROGRESS\n");
  EXPECT_EQ(out.failure, "");
  EXPECT_EQ(out.steps[0].termination, "NOPROGRESS");
}

TEST_F(MobilityRunTest, ReachingTheGoalWhenAFaultWasExpectedFails) {
  const TaskOutcome out = Run(std::string(kAutonav) + "  expect: KEEPOUT\n");
  EXPECT_EQ(out.failure, "autonav ended succeeded reached, expected KEEPOUT");
}

TEST_F(MobilityRunTest, GuardedVetoPassesWhenExpected) {
  mobility_.script = {rover_apl_MOBILITY_FAILED, rover_apl_MOBFAULT_NOPATH,
                      rover_apl_FAULT_GOAL_ERROR, "primitive 1 vetoed", 1.0, true};
  const TaskOutcome out =
      Run("task:\n  type: guarded\n  primitives: [{primitive: straight, distance: 8}]\n"
          "  expect: vetoed\n");
  EXPECT_EQ(out.failure, "");
  ASSERT_EQ(mobility_.received.size(), 1u);
  EXPECT_EQ(mobility_.received[0].mode, rover_apl_MOBILITY_GUARDED);
  EXPECT_EQ(mobility_.received[0].primitives, 1u);
  // The planned path is the dead-reckoned primitive from the start (1, 2).
  const auto path = task_->PlannedPath();
  EXPECT_NEAR(path.back().x(), 9.0, 1e-9);
  EXPECT_NEAR(path.back().y(), 2.0, 1e-9);
}

TEST_F(MobilityRunTest, NoVerdictWithinTheBudgetSendsStopAndFails) {
  mobility_.script.answer = false;
  const TaskOutcome out =
      Run("task:\n  type: goto_waypoint\n  goal: {x: 5, y: 0}\n  time_budget_s: 5\n");
  EXPECT_EQ(out.failure,
            "no terminal apl/mobility_status within the command's time budget of 5 s plus 30 s "
            "(STOP sent)");
  ASSERT_EQ(out.steps.size(), 1u);
  EXPECT_EQ(out.steps[0].state, "interrupted");
  EXPECT_GE(out.steps[0].sim_end_s - out.steps[0].sim_start_s, 35.0 - 1e-6);
  EXPECT_TRUE(mobility_.stopped);
  EXPECT_EQ(run_.result().mobility->outcome, "none");
}

}  // namespace
}  // namespace rover::deploy::runner
