// ddl-motor in-process on an isolated DDS domain under a simulated clock: the test plays the
// motor controllers (hw/motor_telemetry from a kinematic fake that follows hw/motor_goals) and
// DL (ddl/motor_command), and checks hw/motor_goals and ddl/motor_status.
#include "motor_service.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "rover/ddl/motor/sync_planner.hpp"
#include "rover/testing/service_harness.hpp"

namespace rover::ddl::motor {
namespace {

using testing::ServiceHarness;

// Motor controllers that reach position goals at the commanded rate (no acceleration ramp, so
// always ahead of the driver's planned profile). A jammed motor does not move; with
// `flag_stall` the controller latches the stall flag once it applied the goals.
struct FakeControllers {
  HardwareConfig hw;
  std::array<double, hw::kNumMotors> counts{};
  std::array<double, hw::kNumMotors> target{};
  std::array<double, hw::kNumMotors> rate{};  // [counts/s]
  std::array<double, hw::kNumMotors> velocity{};
  std::array<bool, hw::kNumMotors> moving{};
  std::array<std::uint16_t, hw::kNumMotors> flags{};
  std::uint32_t applied = 0;
  int jammed = -1;
  bool flag_stall = false;

  void Apply(const rover_hw_MotorGoals& g) {
    applied = g.command_id;
    for (int i = 0; i < hw::kNumMotors; ++i) {
      const auto k = static_cast<std::size_t>(i);
      const rover_hw_MotorGoal& goal = g.goals[i];
      if (goal.mode == rover_hw_MOTOR_POSITION) {
        target[k] = goal.position;
        rate[k] = goal.velocity;
        moving[k] = true;
      } else if (goal.mode == rover_hw_MOTOR_BRAKE) {
        moving[k] = false;
      }
    }
  }
  void Step(double dt) {
    for (std::size_t k = 0; k < counts.size(); ++k) {
      velocity[k] = 0.0;
      if (!moving[k]) continue;
      if (static_cast<int>(k) == jammed) {
        if (flag_stall) flags[k] |= hw::kMotorFlagStall;
        continue;
      }
      const double d = target[k] - counts[k];
      const double step = std::min(std::abs(d), rate[k] * dt);
      counts[k] += d >= 0 ? step : -step;
      velocity[k] = (d >= 0 ? step : -step) / dt;
      if (std::abs(target[k] - counts[k]) < 0.5) moving[k] = false;
    }
  }
  rover_hw_MotorTelemetry Telemetry(Time t) const {
    rover_hw_MotorTelemetry m{};
    m.header.stamp_ns = t.ns;
    m.command_id = applied;
    for (std::size_t k = 0; k < counts.size(); ++k) {
      m.motors[k].position = static_cast<std::int32_t>(std::lround(counts[k]));
      m.motors[k].velocity = static_cast<std::int32_t>(std::lround(velocity[k]));
      m.motors[k].current_adc =
          static_cast<std::uint16_t>(std::lround(hw.telemetry.CountsFromCurrent(0.2)));
      m.motors[k].temperature_adc =
          static_cast<std::uint16_t>(std::lround(hw.telemetry.CountsFromTemperature(20.0)));
      m.motors[k].flags = static_cast<std::uint16_t>(hw::kMotorFlagEnabled | flags[k]);
    }
    return m;
  }
};

class MotorServiceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    harness_ = std::make_unique<ServiceHarness>(service_, "ddl-motor-test");
    ASSERT_TRUE(harness_->ok()) << harness_->status().message();
    telemetry_ = harness_->Writer<rover_hw_MotorTelemetry>("hw/motor_telemetry");
    command_ = harness_->Writer<rover_ddl_MotorCommand>("ddl/motor_command");
    goals_ = harness_->Reader<rover_hw_MotorGoals>("hw/motor_goals");
    status_ = harness_->Reader<rover_ddl_MotorStatus>("ddl/motor_status");
  }
  void TearDown() override { harness_.reset(); }

  // One 10 ms step of simulated time: controllers follow the goals received so far, the clock
  // moves, telemetry goes out (unless `silent`), the service runs, outputs are collected.
  void Step(bool silent = false) {
    for (auto& g : goals_.Take()) {
      fake_.Apply(g.data());
      goal_log_.push_back(g.data());
    }
    fake_.Step(0.01);
    now_ = now_ + Seconds(0.01);
    ASSERT_TRUE(harness_->AdvanceTo(now_));
    if (!silent) {
      ASSERT_TRUE(telemetry_.Write(fake_.Telemetry(now_)).ok());
    }
    harness_->Spin();
    for (auto& s : status_.Take()) statuses_.push_back(s.data());
  }
  // Steps until `cond` holds, at most `max_s` simulated seconds.
  bool StepUntil(const std::function<bool()>& cond, double max_s, bool silent = false) {
    const Time end = now_ + Seconds(max_s);
    while (now_ < end) {
      Step(silent);
      if (cond()) return true;
    }
    return false;
  }
  const rover_ddl_MotorStatus* Final(std::uint32_t id) const {
    for (const auto& s : statuses_) {
      if (s.command_id == id &&
          (s.state == rover_ddl_GROUP_DONE || s.state == rover_ddl_GROUP_FAULT ||
           s.state == rover_ddl_GROUP_REJECTED)) {
        return &s;
      }
    }
    return nullptr;
  }
  // Spins (wall time only bounds the wait) until a heartbeat satisfying `pred` arrives.
  bool WaitHeartbeat(const std::function<bool(const rover_sys_Heartbeat&)>& pred) {
    return harness_->SpinUntil(
        [&] { return !harness_->heartbeats().empty() && pred(harness_->heartbeats().back()); });
  }
  bool Healthy() const {
    return !harness_->heartbeats().empty() &&
           harness_->heartbeats().back().health == rover_HEALTH_OK;
  }
  // Runs telemetry until the service reports healthy (it has fresh telemetry to plan from).
  void WaitForTelemetry() {
    ASSERT_TRUE(StepUntil([&] { return Healthy(); }, 2.0));
  }

  rover_ddl_MotorCommand PositionCommand(std::uint32_t id) const {
    rover_ddl_MotorCommand c{};
    c.command_id = id;
    c.mode = rover_ddl_GROUP_POSITION;
    return c;
  }

  MotorService service_;
  std::unique_ptr<ServiceHarness> harness_;
  dds::Writer<rover_hw_MotorTelemetry> telemetry_;
  dds::Writer<rover_ddl_MotorCommand> command_;
  dds::Reader<rover_hw_MotorGoals> goals_;
  dds::Reader<rover_ddl_MotorStatus> status_;
  FakeControllers fake_;
  Time now_ = Time::FromSeconds(1.0);
  std::vector<rover_ddl_MotorStatus> statuses_;
  std::vector<rover_hw_MotorGoals> goal_log_;
};

TEST_F(MotorServiceTest, PositionCommandBecomesGoalsAndEndsDone) {
  fake_.counts[hw::kSteerLF] = 1000;  // start off zero
  WaitForTelemetry();
  rover_ddl_MotorCommand c = PositionCommand(7);
  c.motor_mask = (1u << hw::kDriveLF) | (1u << hw::kSteerLF);
  c.goal[hw::kDriveLF] = 1.0;  // [rad]
  c.goal[hw::kSteerLF] = 0.3;  // [rad]
  ASSERT_TRUE(command_.Write(c).ok());
  ASSERT_TRUE(StepUntil([&] { return Final(7) != nullptr; }, 6.0));
  const rover_ddl_MotorStatus* done = Final(7);
  EXPECT_EQ(done->state, rover_ddl_GROUP_DONE) << done->message;
  EXPECT_EQ(done->fault, rover_ddl_MOTOR_FAULT_NONE);
  EXPECT_EQ(done->fault_motor, -1);
  EXPECT_NEAR(done->position[hw::kDriveLF], 1.0, 0.005);
  EXPECT_NEAR(done->position[hw::kSteerLF], 0.3, 0.005);
  EXPECT_STREQ(done->header.frame_id, "rover");

  // The goals: one message starts the group, in encoder counts at synchronised rates.
  ASSERT_FALSE(goal_log_.empty());
  const rover_hw_MotorGoals& g = goal_log_.front();
  const double drive_cpr = fake_.hw.motors[hw::kDriveLF].CountsPerRad();
  const double steer_cpr = fake_.hw.motors[hw::kSteerLF].CountsPerRad();
  EXPECT_EQ(g.goals[hw::kDriveLF].mode, rover_hw_MOTOR_POSITION);
  EXPECT_EQ(g.goals[hw::kDriveLF].position, std::lround(1.0 * drive_cpr));
  EXPECT_EQ(g.goals[hw::kSteerLF].position, std::lround(0.3 * steer_cpr));
  EXPECT_EQ(g.goals[hw::kDriveRF].mode, rover_hw_MOTOR_IDLE);  // not in the group
  // Synchronised: both trapezoidal profiles (controller acceleration, cruise rate from the goal)
  // end together, 2.25 s for the drive at its 0.5 rad/s default rate and 2 rad/s^2.
  const double t_drive = ProfileDuration(1.0, g.goals[hw::kDriveLF].velocity / drive_cpr,
                                         fake_.hw.motors[hw::kDriveLF].max_acceleration);
  const double t_steer =
      ProfileDuration(0.3 - 1000 / steer_cpr, g.goals[hw::kSteerLF].velocity / steer_cpr,
                      fake_.hw.motors[hw::kSteerLF].max_acceleration);
  EXPECT_NEAR(t_drive, 2.25, 1e-3);
  EXPECT_NEAR(t_steer, t_drive, 1e-3);
  // Statuses went RUNNING before DONE, and the group's motors were braked at the end.
  bool running = false;
  for (const auto& s : statuses_)
    running |= s.command_id == 7 && s.state == rover_ddl_GROUP_RUNNING;
  EXPECT_TRUE(running);
  Step();
  EXPECT_EQ(goal_log_.back().goals[hw::kDriveLF].mode, rover_hw_MOTOR_BRAKE);
  // The latched status keeps coming at 8 Hz while idle: over 1 s, about 8 samples.
  const std::size_t before = statuses_.size();
  const Time t0 = now_;
  while (now_ < t0 + Seconds(1.0)) Step();
  const std::size_t n = statuses_.size() - before;
  EXPECT_GE(n, 7u);
  EXPECT_LE(n, 9u);
  EXPECT_EQ(statuses_.back().state, rover_ddl_GROUP_DONE);  // the last final status repeats
}

TEST_F(MotorServiceTest, ControllerStallFaultsTheGroupNamingTheMotor) {
  WaitForTelemetry();
  fake_.jammed = hw::kDriveRF;
  fake_.flag_stall = true;
  rover_ddl_MotorCommand c = PositionCommand(8);
  c.motor_mask = (1u << hw::kDriveLF) | (1u << hw::kDriveRF);
  c.goal[hw::kDriveLF] = 2.0;
  c.goal[hw::kDriveRF] = 2.0;
  ASSERT_TRUE(command_.Write(c).ok());
  ASSERT_TRUE(StepUntil([&] { return Final(8) != nullptr; }, 3.0));
  const rover_ddl_MotorStatus* f = Final(8);
  EXPECT_EQ(f->state, rover_ddl_GROUP_FAULT);
  EXPECT_EQ(f->fault, rover_ddl_MOTOR_FAULT_STALL);
  EXPECT_EQ(f->fault_motor, hw::kDriveRF);
  EXPECT_NE(std::string(f->message).find("motor 3 (drive_rf)"), std::string::npos) << f->message;
  // Every motor of the group is braked.
  Step();
  const rover_hw_MotorGoals& last = goal_log_.back();
  EXPECT_EQ(last.goals[hw::kDriveLF].mode, rover_hw_MOTOR_BRAKE);
  EXPECT_EQ(last.goals[hw::kDriveRF].mode, rover_hw_MOTOR_BRAKE);
}

TEST_F(MotorServiceTest, SimulatorResetStopsTheGroupAndTheDriverCarriesOn) {
  WaitForTelemetry();
  rover_ddl_MotorCommand c = PositionCommand(11);
  c.motor_mask = 1u << hw::kDriveLM;
  c.goal[hw::kDriveLM] = 3.0;
  ASSERT_TRUE(command_.Write(c).ok());
  ASSERT_TRUE(StepUntil([&] { return fake_.applied != 0; }, 1.0));
  // The simulator resets: its clock restarts near zero; the controllers keep echoing the old
  // hardware command id.
  now_ = Time::FromSeconds(0.02);
  ASSERT_TRUE(StepUntil([&] { return Final(11) != nullptr; }, 0.5));
  EXPECT_EQ(Final(11)->state, rover_ddl_GROUP_FAULT);
  EXPECT_EQ(Final(11)->fault, rover_ddl_MOTOR_FAULT_STOPPED);
  EXPECT_NE(std::string(Final(11)->message).find("simulator reset"), std::string::npos);
  Step();
  EXPECT_EQ(goal_log_.back().goals[hw::kDriveLM].mode, rover_hw_MOTOR_BRAKE);
  // Telemetry stamped after the reset is accepted at once: a new move plans and completes.
  c = PositionCommand(12);
  c.motor_mask = 1u << hw::kMastPan;
  c.goal[hw::kMastPan] = 0.4;
  ASSERT_TRUE(command_.Write(c).ok());
  ASSERT_TRUE(StepUntil([&] { return Final(12) != nullptr; }, 4.0));
  EXPECT_EQ(Final(12)->state, rover_ddl_GROUP_DONE) << Final(12)->message;
}

TEST_F(MotorServiceTest, BadCommandsAreRejectedWithAReasonAndTheServiceCarriesOn) {
  // Before any telemetry: nothing to plan from.
  rover_ddl_MotorCommand c = PositionCommand(1);
  c.motor_mask = 1u << hw::kMastPan;
  c.goal[hw::kMastPan] = 0.2;
  ASSERT_TRUE(command_.Write(c).ok());
  ASSERT_TRUE(StepUntil([&] { return Final(1) != nullptr; }, 1.0, /*silent=*/true));
  EXPECT_EQ(Final(1)->state, rover_ddl_GROUP_REJECTED);
  EXPECT_EQ(Final(1)->fault, rover_ddl_MOTOR_FAULT_NO_TELEMETRY);
  ASSERT_TRUE(WaitHeartbeat([](const rover_sys_Heartbeat& h) { return h.count > 0; }));
  EXPECT_EQ(harness_->heartbeats().back().health, rover_HEALTH_STALE);
  EXPECT_STREQ(harness_->heartbeats().back().message, "hw/motor_telemetry: no sample yet");

  WaitForTelemetry();
  c = PositionCommand(2);
  c.motor_mask = 1u << hw::kMastTilt;
  c.goal[hw::kMastTilt] = std::nan("");
  ASSERT_TRUE(command_.Write(c).ok());
  // One command at a time: the test does not depend on how many statuses the latched topic's
  // history keeps.
  ASSERT_TRUE(StepUntil([&] { return Final(2) != nullptr; }, 1.0));
  c = PositionCommand(3);
  c.motor_mask = 1u << hw::kSteerRR;
  c.goal[hw::kSteerRR] = 2.5;  // beyond the +-1.6 rad limit
  ASSERT_TRUE(command_.Write(c).ok());
  ASSERT_TRUE(StepUntil([&] { return Final(3) != nullptr; }, 1.0));
  EXPECT_EQ(Final(2)->state, rover_ddl_GROUP_REJECTED);
  EXPECT_EQ(Final(2)->fault, rover_ddl_MOTOR_FAULT_BAD_COMMAND);
  EXPECT_EQ(Final(2)->fault_motor, hw::kMastTilt);
  EXPECT_NE(std::string(Final(2)->message).find("is not finite"), std::string::npos);
  EXPECT_EQ(Final(3)->fault, rover_ddl_MOTOR_FAULT_BAD_COMMAND);
  EXPECT_NE(std::string(Final(3)->message).find("outside [-1.6, 1.6]"), std::string::npos)
      << Final(3)->message;
  EXPECT_TRUE(goal_log_.empty());  // nothing was sent to the motors

  // Telemetry stamped far in the future is dropped; the service is still healthy.
  rover_hw_MotorTelemetry bad = fake_.Telemetry(now_ + Seconds(100.0));
  ASSERT_TRUE(telemetry_.Write(bad).ok());
  ASSERT_TRUE(StepUntil([&] { return Healthy(); }, 0.5));
  // Telemetry stops: STALE after telemetry_timeout_s (0.5 s).
  ASSERT_TRUE(StepUntil(
      [&] {
        return !harness_->heartbeats().empty() &&
               harness_->heartbeats().back().health == rover_HEALTH_STALE;
      },
      1.0,
      /*silent=*/true));
  EXPECT_STREQ(harness_->heartbeats().back().message,
               "hw/motor_telemetry: no sample for more than 0.5 s");
}

}  // namespace
}  // namespace rover::ddl::motor
