#include "rover/ddl/motor/motor_group_manager.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace rover::ddl::motor {
namespace {

// A kinematic stand-in for the motor controllers: applies hw goals, runs trapezoidal profiles
// with MotorSpec::max_acceleration, reports telemetry in counts and ADC counts.
class FakeController {
 public:
  explicit FakeController(const HardwareConfig& config) : config_(config) {}

  struct Motor {
    double pos = 0.0, vel = 0.0;
    hw::MotorGoal goal;
    bool frozen = false;        // stalled: does not move
    double speed_factor = 1.0;  // < 1: sluggish
    double current = 0.2, temperature = 20.0;
    std::uint16_t latched = 0;
  };

  void Apply(const hw::MotorGoals& goals) {
    if (drop_goals) return;
    for (int m = 0; m < hw::kNumMotors; ++m) {
      const auto k = static_cast<std::size_t>(m);
      if (goals.goals[k].mode == hw::MotorMode::kIdle) continue;
      motors[k].goal = goals.goals[k];
      motors[k].latched = 0;  // a new goal clears latched faults
    }
    applied_id = goals.command_id;
  }

  void Step(double dt) {
    for (int m = 0; m < hw::kNumMotors; ++m) {
      const auto k = static_cast<std::size_t>(m);
      Motor& x = motors[k];
      const MotorSpec& s = config_.motors[k];
      const double cpr = s.CountsPerRad();
      const double a = s.max_acceleration;
      double v_cmd = 0.0;
      switch (x.goal.mode) {
        case hw::MotorMode::kPosition: {
          const double e = x.goal.position / cpr - x.pos;
          const double vmax = x.goal.velocity / cpr;
          // Decelerate so as to stop at the goal (trapezoid).
          v_cmd = std::copysign(std::min(vmax, std::sqrt(2.0 * a * std::abs(e))), e);
          if (std::abs(e) < 1e-6) v_cmd = 0.0;
          break;
        }
        case hw::MotorMode::kVelocity:
          v_cmd = x.goal.velocity / cpr;
          break;
        case hw::MotorMode::kIdle:
        case hw::MotorMode::kBrake:
          v_cmd = 0.0;
          break;
      }
      const double dv = std::clamp(v_cmd - x.vel, -a * dt, a * dt);
      x.vel = x.goal.mode == hw::MotorMode::kBrake ? 0.0 : x.vel + dv;
      if (x.frozen) x.vel = 0.0;
      x.pos += x.vel * dt * x.speed_factor;
      if (x.goal.mode == hw::MotorMode::kPosition) {
        const double goal = x.goal.position / cpr;
        const double before = x.pos - x.vel * dt * x.speed_factor;
        if ((before - goal) * (x.pos - goal) < 0.0) {  // crossed the goal: land on it
          x.pos = goal;
          x.vel = 0.0;
        }
      }
    }
  }

  hw::MotorTelemetry Telemetry(Time stamp) const {
    hw::MotorTelemetry t;
    t.stamp_ns = stamp.ns;
    t.command_id = applied_id;
    for (int m = 0; m < hw::kNumMotors; ++m) {
      const auto k = static_cast<std::size_t>(m);
      const Motor& x = motors[k];
      const double cpr = config_.motors[k].CountsPerRad();
      t.motors[k].position = hw::WrapCounter(std::llround(x.pos * cpr));
      t.motors[k].velocity = static_cast<std::int32_t>(std::llround(x.vel * x.speed_factor * cpr));
      t.motors[k].current_adc = static_cast<std::uint16_t>(
          std::lround(std::clamp(config_.telemetry.CountsFromCurrent(x.current), 0.0, 4095.0)));
      t.motors[k].temperature_adc = static_cast<std::uint16_t>(std::lround(
          std::clamp(config_.telemetry.CountsFromTemperature(x.temperature), 0.0, 4095.0)));
      t.motors[k].flags = x.latched;
    }
    return t;
  }

  std::array<Motor, hw::kNumMotors> motors{};
  std::uint32_t applied_id = 0;
  bool drop_goals = false;

 private:
  HardwareConfig config_;
};

// Drives manager + fake controller on a 1 ms loop: telemetry at 100 Hz, Tick at 8 Hz.
class Harness {
 public:
  Harness() : plant(config) {
    auto m = MotorGroupManager::Create(config);
    EXPECT_TRUE(m.ok());
    manager.emplace(std::move(*m));
    RunFor(0.05);  // some telemetry first
  }

  void Absorb(const ManagerOutput& out) {
    if (out.goals) {
      plant.Apply(*out.goals);
      last_goals = *out.goals;
    }
    for (const auto& s : out.statuses) statuses.push_back(s);
  }

  ManagerOutput Command(const MotorCommand& c) {
    ManagerOutput out = manager->HandleCommand(c, now);
    Absorb(out);
    return out;
  }

  // Runs until `until` returns true or `seconds` elapse; returns false on time-out.
  template <class Pred>
  bool RunUntil(double seconds, Pred until) {
    const std::int64_t end = now.ns + std::llround(seconds * 1e9);
    while (now.ns < end) {
      now = now + Duration{1'000'000};
      plant.Step(1e-3);
      if (telemetry_on && now.ns % 10'000'000 == 0) {
        Absorb(manager->HandleTelemetry(plant.Telemetry(now), now));
      }
      if (now.ns % 125'000'000 == 0) Absorb(manager->Tick(now));
      for (int m = 0; m < hw::kNumMotors; ++m) {
        const auto k = static_cast<std::size_t>(m);
        if (finish[k] < 0.0 && target[k].has_value() &&
            std::abs(plant.motors[k].pos - *target[k]) < 1e-3) {
          finish[k] = now.seconds();
        }
      }
      if (until()) return true;
    }
    return false;
  }
  void RunFor(double seconds) {
    RunUntil(seconds, [] { return false; });
  }

  const MotorStatus* Final(std::uint32_t id) const {
    for (auto it = statuses.rbegin(); it != statuses.rend(); ++it) {
      if (it->command_id == id && it->state != GroupState::kRunning &&
          it->state != GroupState::kIdle) {
        return &*it;
      }
    }
    return nullptr;
  }

  HardwareConfig config;
  FakeController plant;
  std::optional<MotorGroupManager> manager;
  Time now{0};
  bool telemetry_on = true;
  std::vector<MotorStatus> statuses;
  hw::MotorGoals last_goals;
  std::array<std::optional<double>, hw::kNumMotors> target{};
  std::array<double, hw::kNumMotors> finish{-1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1, -1};
};

MotorCommand PositionCommand(std::uint32_t id,
                             std::initializer_list<std::pair<int, double>> goals) {
  MotorCommand c;
  c.command_id = id;
  c.mode = GroupMode::kPosition;
  for (const auto& [m, g] : goals) {
    c.motor_mask |= static_cast<std::uint16_t>(1u << m);
    c.goal[static_cast<std::size_t>(m)] = g;
  }
  return c;
}

MotorCommand DriveVelocity(std::uint32_t id, double rate) {
  MotorCommand c;
  c.command_id = id;
  c.mode = GroupMode::kVelocity;
  for (int m = hw::kDriveLF; m <= hw::kDriveRR; ++m) {
    c.motor_mask |= static_cast<std::uint16_t>(1u << m);
    c.goal[static_cast<std::size_t>(m)] = rate;
  }
  return c;
}

TEST(MotorGroupManager, SynchronisedMoveFinishesTogether) {
  Harness h;
  // Very different distances, rate limits and accelerations.
  MotorCommand c = PositionCommand(
      10, {{hw::kDriveLF, 1.2}, {hw::kDriveRR, -0.3}, {hw::kSteerLF, 0.4}, {hw::kMastPan, 0.9}});
  for (int m : {hw::kDriveLF, hw::kDriveRR, hw::kSteerLF, hw::kMastPan}) {
    h.target[static_cast<std::size_t>(m)] = c.goal[static_cast<std::size_t>(m)];
  }
  const double t0 = h.now.seconds();
  const ManagerOutput out = h.Command(c);
  ASSERT_TRUE(out.goals.has_value());
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_EQ(out.statuses[0].state, GroupState::kRunning);
  // One message starts every motor of the group; the others are left alone.
  for (int m = 0; m < hw::kNumMotors; ++m) {
    const bool in = (c.motor_mask >> m) & 1u;
    EXPECT_EQ(out.goals->goals[static_cast<std::size_t>(m)].mode,
              in ? hw::MotorMode::kPosition : hw::MotorMode::kIdle)
        << m;
  }
  // Planned rates differ (the short moves are slowed down).
  const double cpr0 = h.config.motors[0].CountsPerRad();
  const double cpr5 = h.config.motors[5].CountsPerRad();
  EXPECT_LT(out.goals->goals[5].velocity / cpr5, 0.5 * out.goals->goals[0].velocity / cpr0);

  ASSERT_TRUE(h.RunUntil(10.0, [&] { return h.Final(10) != nullptr; }));
  const MotorStatus* done = h.Final(10);
  EXPECT_EQ(done->state, GroupState::kDone) << done->message;
  EXPECT_EQ(done->fault, MotorFault::kNone);
  EXPECT_EQ(done->fault_motor, -1);
  // Drive LF at its default 0.5 rad/s over 1.2 rad: T* = 1.2 / 0.5 + 0.5 / 2 = 2.65 s.
  const double planned = 1.2 / 0.5 + 0.5 / 2.0;
  double lo = 1e9, hi = -1e9;
  for (int m : {hw::kDriveLF, hw::kDriveRR, hw::kSteerLF, hw::kMastPan}) {
    const double f = h.finish[static_cast<std::size_t>(m)] - t0;
    ASSERT_GT(f, 0.0) << m;
    lo = std::min(lo, f);
    hi = std::max(hi, f);
    EXPECT_NEAR(f, planned, 0.06) << hw::MotorName(m);
  }
  EXPECT_LT(hi - lo, 0.06);
  // Done brakes the group.
  ASSERT_TRUE(h.last_goals.goals[hw::kSteerLF].mode == hw::MotorMode::kBrake);
  EXPECT_EQ(h.last_goals.goals[hw::kDriveLM].mode, hw::MotorMode::kIdle);
  // Final positions within tolerance; status reports them in radians.
  EXPECT_NEAR(done->position[hw::kMastPan], 0.9, h.config.motors[hw::kMastPan].position_tolerance);
}

TEST(MotorGroupManager, OneStalledMotorStopsTheWholeGroup) {
  Harness h;
  MotorCommand c;
  c.command_id = 20;
  c.mode = GroupMode::kPosition;
  for (int m = hw::kDriveLF; m <= hw::kDriveRR; ++m) {
    c.motor_mask |= static_cast<std::uint16_t>(1u << m);
    c.goal[static_cast<std::size_t>(m)] = 3.0;
  }
  h.Command(c);
  h.RunFor(0.8);
  h.plant.motors[hw::kDriveRM].frozen = true;  // wheel jammed by a rock
  ASSERT_TRUE(h.RunUntil(5.0, [&] { return h.Final(20) != nullptr; }));
  const MotorStatus* s = h.Final(20);
  EXPECT_EQ(s->state, GroupState::kFault);
  EXPECT_EQ(s->fault, MotorFault::kStall);
  EXPECT_EQ(s->fault_motor, hw::kDriveRM);
  EXPECT_NE(s->message.find("drive_rm"), std::string::npos) << s->message;
  EXPECT_LE(s->message.size(), 127u);
  for (int m = hw::kDriveLF; m <= hw::kDriveRR; ++m) {
    EXPECT_EQ(h.last_goals.goals[static_cast<std::size_t>(m)].mode, hw::MotorMode::kBrake) << m;
  }
  // Detected within about one stall window (+ tick) of the jam.
  EXPECT_LT(h.now.seconds(), 0.05 + 0.8 + 1.0 + 0.3);
  EXPECT_FALSE(h.manager->busy());
}

// A wheel that got ahead of its plan (pushed over a rock's far side, say) and then makes no
// progress for a whole window while the plan catches up is not stuck: it is where the plan says
// it should be. (Two autonav runs ended MOT this way: "moved -0.0086 rad of 0.0218 rad planned
// in 1 s".) Stuck is behind the plan as well.
TEST(MotorGroupManager, AWheelAheadOfItsPlanThatWaitsIsNotAStall) {
  Harness h;
  h.Command(DriveVelocity(21, 0.4));
  h.RunFor(1.0);
  auto& wheel = h.plant.motors[hw::kDriveRM];
  wheel.pos += 0.5;  // ahead of the plan by 0.5 rad (1.25 s at 0.4 rad/s)
  wheel.frozen = true;
  h.RunFor(1.2);  // a whole stall window without progress; the plan catches up to 0.02 rad
  EXPECT_EQ(h.Final(21), nullptr) << h.Final(21)->message;
  wheel.frozen = false;
  h.RunFor(1.0);
  EXPECT_EQ(h.Final(21), nullptr) << h.Final(21)->message;
  // Held on: now it falls behind, and is a stall once 0.2 rad behind.
  wheel.frozen = true;
  ASSERT_TRUE(h.RunUntil(3.0, [&] { return h.Final(21) != nullptr; }));
  EXPECT_EQ(h.Final(21)->fault, MotorFault::kStall);
  EXPECT_NE(h.Final(21)->message.find("behind its plan"), std::string::npos)
      << h.Final(21)->message;
}

TEST(MotorGroupManager, ControllerFaultFlagStopsTheGroupAtOnce) {
  Harness h;
  h.Command(DriveVelocity(30, 0.4));
  h.RunFor(0.5);
  h.plant.motors[hw::kDriveLR].latched = hw::kMotorFlagOverCurrent;
  ASSERT_TRUE(h.RunUntil(0.05, [&] { return h.Final(30) != nullptr; }));
  const MotorStatus* s = h.Final(30);
  EXPECT_EQ(s->fault, MotorFault::kOverCurrent);
  EXPECT_EQ(s->fault_motor, hw::kDriveLR);
  for (int m = hw::kDriveLF; m <= hw::kDriveRR; ++m) {
    EXPECT_EQ(h.last_goals.goals[static_cast<std::size_t>(m)].mode, hw::MotorMode::kBrake);
  }
}

TEST(MotorGroupManager, DriverSideCurrentAndTemperatureLimits) {
  {
    Harness h;
    h.Command(DriveVelocity(31, 0.4));
    h.RunFor(0.3);
    h.plant.motors[hw::kDriveLM].current = 1.6;  // above the 1.3 A limit, no controller trip
    ASSERT_TRUE(h.RunUntil(1.0, [&] { return h.Final(31) != nullptr; }));
    const MotorStatus* s = h.Final(31);
    EXPECT_EQ(s->fault, MotorFault::kOverCurrent);
    EXPECT_EQ(s->fault_motor, hw::kDriveLM);
    EXPECT_NEAR(s->current[hw::kDriveLM], 1.6, 1e-3);
  }
  {
    Harness h;
    h.Command(PositionCommand(32, {{hw::kMastTilt, 0.5}, {hw::kMastPan, -1.0}}));
    h.RunFor(0.3);
    h.plant.motors[hw::kMastTilt].temperature = 115.0;
    ASSERT_TRUE(h.RunUntil(1.0, [&] { return h.Final(32) != nullptr; }));
    const MotorStatus* s = h.Final(32);
    EXPECT_EQ(s->fault, MotorFault::kOverTemp);
    EXPECT_EQ(s->fault_motor, hw::kMastTilt);
  }
}

TEST(MotorGroupManager, TimeoutNamesTheLaggingMotor) {
  Harness h;
  MotorCommand c = PositionCommand(40, {{hw::kSteerLF, 0.5}, {hw::kSteerRR, -0.5}});
  c.timeout_s = 2.0;                                 // planned 0.5 / 0.4 + 0.2 = 1.45 s
  h.plant.motors[hw::kSteerRR].speed_factor = 0.45;  // slow, but not stalled
  h.Command(c);
  ASSERT_TRUE(h.RunUntil(5.0, [&] { return h.Final(40) != nullptr; }));
  const MotorStatus* s = h.Final(40);
  EXPECT_EQ(s->state, GroupState::kFault);
  EXPECT_EQ(s->fault, MotorFault::kTimeout) << s->message;
  EXPECT_EQ(s->fault_motor, hw::kSteerRR);
  EXPECT_NEAR(h.now.seconds(), 0.05 + 2.0, 0.13);
}

TEST(MotorGroupManager, VelocityGroupEndsAtItsTimeout) {
  Harness h;
  MotorCommand c = DriveVelocity(41, -0.3);
  c.timeout_s = 1.0;
  h.Command(c);
  ASSERT_TRUE(h.RunUntil(3.0, [&] { return h.Final(41) != nullptr; }));
  EXPECT_EQ(h.Final(41)->state, GroupState::kDone);
  EXPECT_LT(h.plant.motors[0].pos, -0.2);
  EXPECT_EQ(h.last_goals.goals[0].mode, hw::MotorMode::kBrake);
}

TEST(MotorGroupManager, BadCommandsAreRejectedWithTypedReasons) {
  Harness h;
  struct Case {
    MotorCommand command;
    CommandError error;
    int motor;
  };
  std::vector<Case> cases;
  MotorCommand c = PositionCommand(50, {{hw::kDriveLF, std::nan("")}});
  cases.push_back({c, CommandError::kNonFiniteGoal, hw::kDriveLF});
  // (kUnknownMotor: every bit of the 16-bit mask names a motor since the arm's four joined the
  // twelve; the check stays for a bus with fewer.)
  c = PositionCommand(52, {});
  cases.push_back({c, CommandError::kEmptyMask, -1});
  c = PositionCommand(53, {{hw::kSteerRF, 2.0}});
  cases.push_back({c, CommandError::kGoalOutOfRange, hw::kSteerRF});
  c = PositionCommand(54, {{hw::kDriveRM, 1.0}});
  c.max_rate[hw::kDriveRM] = 5.0;
  cases.push_back({c, CommandError::kRateAboveLimit, hw::kDriveRM});
  c = DriveVelocity(55, 2.0);
  cases.push_back({c, CommandError::kRateAboveLimit, hw::kDriveLF});
  c = PositionCommand(56, {{hw::kDriveLF, 1.0}});
  c.max_rate[0] = -0.1;
  cases.push_back({c, CommandError::kBadRate, hw::kDriveLF});
  c = PositionCommand(57, {{hw::kDriveLF, 1.0}});
  c.timeout_s = std::numeric_limits<double>::infinity();
  cases.push_back({c, CommandError::kBadTimeout, -1});
  c = PositionCommand(58, {{hw::kDriveLF, 1.0}});
  c.timeout_s = 0.5;  // the move needs 2.25 s
  cases.push_back({c, CommandError::kTimeoutTooShort, -1});
  c = PositionCommand(59, {{hw::kDriveLF, 1.0}});
  c.mode = static_cast<GroupMode>(7);
  cases.push_back({c, CommandError::kUnknownMode, -1});

  for (const Case& k : cases) {
    const ManagerOutput out = h.Command(k.command);
    ASSERT_EQ(out.statuses.size(), 1u);
    const MotorStatus& s = out.statuses[0];
    EXPECT_EQ(s.state, GroupState::kRejected) << k.command.command_id;
    EXPECT_EQ(s.fault, MotorFault::kBadCommand) << k.command.command_id;
    EXPECT_EQ(s.error, k.error) << k.command.command_id << ": " << s.message;
    EXPECT_EQ(s.fault_motor, k.motor) << k.command.command_id;
    EXPECT_FALSE(s.message.empty());
    EXPECT_FALSE(out.goals.has_value()) << "a rejected command moves nothing";
  }
  EXPECT_FALSE(h.manager->busy());
}

TEST(MotorGroupManager, NoTelemetryRejectsAndStopsRunningGroups) {
  auto m = MotorGroupManager::Create(HardwareConfig());
  ASSERT_TRUE(m.ok());
  const ManagerOutput out = m->HandleCommand(DriveVelocity(60, 0.2), Time{0});
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_EQ(out.statuses[0].state, GroupState::kRejected);
  EXPECT_EQ(out.statuses[0].fault, MotorFault::kNoTelemetry);
  EXPECT_EQ(out.statuses[0].error, CommandError::kNoTelemetry);

  Harness h;
  h.Command(DriveVelocity(61, 0.2));
  h.RunFor(0.3);
  h.telemetry_on = false;  // the telemetry link dies
  ASSERT_TRUE(h.RunUntil(2.0, [&] { return h.Final(61) != nullptr; }));
  EXPECT_EQ(h.Final(61)->fault, MotorFault::kNoTelemetry);
  EXPECT_EQ(h.last_goals.goals[hw::kDriveRR].mode, hw::MotorMode::kBrake);

  Harness g;
  g.plant.drop_goals = true;  // the controller never applies (echoes) the goals
  g.Command(DriveVelocity(62, 0.2));
  ASSERT_TRUE(g.RunUntil(2.0, [&] { return g.Final(62) != nullptr; }));
  EXPECT_EQ(g.Final(62)->fault, MotorFault::kNoTelemetry);
  EXPECT_NE(g.Final(62)->message.find("acknowledge"), std::string::npos);
}

TEST(MotorGroupManager, StaleLatchedFlagsBeforeTheGoalsAreAppliedAreIgnored) {
  Harness h;
  h.plant.motors[hw::kDriveLF].latched = hw::kMotorFlagStall;  // from an earlier move
  const MotorCommand c = DriveVelocity(63, 0.2);
  const ManagerOutput out = h.manager->HandleCommand(c, h.now);
  // Telemetry still carrying the old command id and the old flag.
  const ManagerOutput t = h.manager->HandleTelemetry(h.plant.Telemetry(h.now), h.now);
  EXPECT_TRUE(t.statuses.empty());
  EXPECT_TRUE(h.manager->busy());
  h.Absorb(out);  // now the controller applies the goals (and clears the flag)
  h.RunFor(0.5);
  EXPECT_EQ(h.Final(63), nullptr);
  EXPECT_TRUE(h.manager->busy());
}

TEST(MotorGroupManager, ReorderedTelemetryIsIgnored) {
  Harness h;
  h.Command(DriveVelocity(64, 0.2));
  h.RunFor(0.3);
  hw::MotorTelemetry old = h.plant.Telemetry(h.now - Duration{50'000'000});
  old.motors[hw::kDriveRF].flags = hw::kMotorFlagOverTemp;
  EXPECT_TRUE(h.manager->HandleTelemetry(old, h.now).statuses.empty());
  EXPECT_TRUE(h.manager->busy());
  EXPECT_EQ(h.manager->latest()->stamp_ns, 300'000'000 + 50'000'000);
}

TEST(MotorGroupManager, ExplicitStopAndPreemption) {
  Harness h;
  h.Command(DriveVelocity(70, 0.3));
  h.Command(PositionCommand(71, {{hw::kMastPan, 1.0}}));
  h.RunFor(0.4);
  // A new drive command preempts the running drive group; the mast group keeps going.
  const ManagerOutput pre = h.Command(DriveVelocity(72, -0.3));
  ASSERT_NE(h.Final(70), nullptr);
  EXPECT_EQ(h.Final(70)->fault, MotorFault::kStopped);
  EXPECT_NE(h.Final(70)->message.find("72"), std::string::npos);
  EXPECT_EQ(pre.goals->goals[0].mode, hw::MotorMode::kVelocity);
  EXPECT_EQ(pre.goals->goals[hw::kMastPan].mode, hw::MotorMode::kIdle);
  EXPECT_EQ(h.Final(71), nullptr);
  h.RunFor(0.3);

  MotorCommand stop;
  stop.command_id = 73;
  stop.mode = GroupMode::kStop;
  stop.motor_mask = 0;  // everything
  const ManagerOutput out = h.Command(stop);
  ASSERT_TRUE(out.goals.has_value());
  for (const auto& g : out.goals->goals) EXPECT_EQ(g.mode, hw::MotorMode::kBrake);
  EXPECT_EQ(h.Final(72)->fault, MotorFault::kStopped);
  EXPECT_EQ(h.Final(71)->fault, MotorFault::kStopped);
  EXPECT_EQ(h.Final(73)->state, GroupState::kDone);
  EXPECT_FALSE(h.manager->busy());
  // The latched status keeps coming at 8 Hz.
  const ManagerOutput tick = h.manager->Tick(h.now + Duration{125'000'000});
  ASSERT_EQ(tick.statuses.size(), 1u);
  EXPECT_EQ(tick.statuses[0].command_id, 73u);
}

TEST(MotorGroupManager, RunningStatusAt8HzCarriesTelemetry) {
  Harness h;
  h.Command(PositionCommand(80, {{hw::kSteerLR, -0.6}}));
  const std::size_t before = h.statuses.size();
  h.RunFor(0.5);
  int running = 0;
  for (std::size_t i = before; i < h.statuses.size(); ++i) {
    if (h.statuses[i].state == GroupState::kRunning) ++running;
  }
  EXPECT_EQ(running, 4);  // ticks at 0.125, 0.25, 0.375, 0.5 s
  EXPECT_LT(h.statuses.back().position[hw::kSteerLR], -0.05);
  EXPECT_NEAR(h.statuses.back().temperature[0], 20.0, 0.1);
}

TEST(MotorGroupManager, ForgetTelemetryAfterAClockResetKeepsTheCommandIds) {
  Harness h;
  ASSERT_NE(h.Command(PositionCommand(1, {{hw::kSteerLF, 0.2}})).goals, std::nullopt);
  ASSERT_TRUE(h.RunUntil(5.0, [&] { return h.Final(1) != nullptr; }));
  const std::uint32_t old_id = h.last_goals.command_id;
  h.Absorb(h.manager->StopAll(h.now, "run clock went back"));
  h.manager->ForgetTelemetry();
  // The run clock restarts at 0; the controller still echoes the old hardware id.
  h.now = Time{0};
  const Time t0 = Time::FromSeconds(0.01);
  h.Absorb(h.manager->HandleTelemetry(h.plant.Telemetry(t0), t0));
  ASSERT_TRUE(h.manager->latest().has_value());
  EXPECT_EQ(h.manager->latest()->stamp_ns, t0.ns);  // accepted although older than before
  h.now = t0;
  h.plant.drop_goals = true;  // the controller does not apply the new goals
  ManagerOutput out = h.Command(PositionCommand(2, {{hw::kSteerLF, -0.2}}));
  ASSERT_TRUE(out.goals.has_value());
  EXPECT_GT(out.goals->command_id, old_id);  // the id sequence continues
  // The stale echo of the old id does not count as applying the new goals.
  ASSERT_TRUE(h.RunUntil(2.0, [&] { return h.Final(2) != nullptr; }));
  EXPECT_EQ(h.Final(2)->fault, MotorFault::kNoTelemetry);
  EXPECT_NE(h.Final(2)->message.find("did not acknowledge"), std::string::npos);
}

TEST(MotorGroupManager, CreateRejectsBadOptions) {
  MotorManagerOptions o;
  o.stall_window_s = -1.0;
  EXPECT_FALSE(MotorGroupManager::Create(HardwareConfig(), o).ok());
  HardwareConfig c;
  c.motors[3].gear_ratio = 0.0;
  EXPECT_FALSE(MotorGroupManager::Create(c).ok());
}

}  // namespace
}  // namespace rover::ddl::motor
