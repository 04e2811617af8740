// dl-arm in-process: the service in the shared ServiceHarness (isolated domain, simulated run
// clock) with the fake arm of tests/support/fakes playing ddl-motor and ddl-joints; the test
// plays the APL (dl/arm_command in, dl/arm_status out).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "arm_service.hpp"
#include "rover/msg/arm_idl.hpp"
#include "rover/testing/fakes/fake_arm.hpp"
#include "rover/testing/service_harness.hpp"

namespace rover::dl::arm {
namespace {

constexpr double kServiceStep = 0.02;  // 50 Hz joint state and sim/clock

class ArmServiceTest : public ::testing::Test {
 protected:
  void Start(std::vector<std::string> overrides = {}) {
    h_ = std::make_unique<testing::ServiceHarness>(service_, "dl-arm-test", std::move(overrides));
    ASSERT_TRUE(h_->ok()) << h_->status().message();
    joint_w_ = h_->Writer<rover_ddl_JointState>("ddl/joint_state");
    motor_status_w_ = h_->Writer<rover_ddl_MotorStatus>("ddl/motor_status");
    command_w_ = h_->Writer<rover_dl_ArmCommand>("dl/arm_command");
    motor_r_ = h_->Reader<rover_ddl_MotorCommand>("ddl/motor_command");
    status_r_ = h_->Reader<rover_dl_ArmStatus>("dl/arm_status");
  }

  // Advances the run clock by `seconds` in 20 ms steps (the fake arm moves, joints go out, then
  // sim/clock); stops early when `until` holds.
  bool Advance(double seconds, const std::function<bool()>& until = nullptr) {
    const int steps = static_cast<int>(std::lround(seconds / kServiceStep));
    for (int i = 0; i < steps; ++i) {
      ++step_;
      const Time now{step_ * 20'000'000};
      arm_.Step(kServiceStep);
      if (publish_joints_) {
        EXPECT_TRUE(joint_w_.Write(arm_.Joints(now)).ok());
      }
      if (auto s = arm_.TakeStatus(now)) {
        EXPECT_TRUE(motor_status_w_.Write(*s).ok());
      }
      EXPECT_TRUE(h_->AdvanceTo(now));
      Collect();
      if (until && until()) return true;
    }
    return false;
  }

  void Collect() {
    for (auto& m : motor_r_.Take(64)) {
      arm_.Apply(m.data());
      motor_commands_.push_back(m.data());
    }
    for (auto& s : status_r_.Take(64)) statuses_.push_back(s.data());
  }

  // Sends a command and spins until a status for it arrives; returns that status.
  rover_dl_ArmStatus Send(const rover_dl_ArmCommand& c) {
    EXPECT_TRUE(command_w_.Write(c).ok());
    const std::size_t before = statuses_.size();
    EXPECT_TRUE(h_->SpinUntil([&] {
      Collect();
      for (std::size_t i = before; i < statuses_.size(); ++i) {
        if (statuses_[i].command_id == c.command_id) return true;
      }
      return false;
    }));
    for (std::size_t i = before; i < statuses_.size(); ++i) {
      if (statuses_[i].command_id == c.command_id) return statuses_[i];
    }
    return {};
  }

  static rover_dl_ArmCommand Command(std::uint32_t id, rover_dl_ArmMode mode) {
    rover_dl_ArmCommand c{};
    c.command_id = id;
    c.mode = mode;
    return c;
  }

  static rover_dl_ArmCommand Place(std::uint32_t id, const Eigen::Vector3d& target) {
    rover_dl_ArmCommand c = Command(id, rover_dl_ARM_MODE_PLACE);
    c.target = {target.x(), target.y(), target.z()};
    return c;
  }

  bool Last(rover_dl_ArmState state) const {
    return !statuses_.empty() && statuses_.back().state == state;
  }

  ArmService service_;
  std::unique_ptr<testing::ServiceHarness> h_;
  dds::Writer<rover_ddl_JointState> joint_w_;
  dds::Writer<rover_ddl_MotorStatus> motor_status_w_;
  dds::Writer<rover_dl_ArmCommand> command_w_;
  dds::Reader<rover_ddl_MotorCommand> motor_r_;
  dds::Reader<rover_dl_ArmStatus> status_r_;
  testing::FakeArm arm_;
  std::vector<rover_ddl_MotorCommand> motor_commands_;
  std::vector<rover_dl_ArmStatus> statuses_;
  std::int64_t step_ = 0;
  bool publish_joints_ = true;
};

TEST_F(ArmServiceTest, PlacementGoesAboveTheTargetDescendsAndStopsOnContact) {
  Start();
  const Eigen::Vector3d target(1.0, -0.1, 0.04);
  arm_.surface = target.z();
  Advance(0.2);
  ASSERT_FALSE(statuses_.empty());  // the latched IDLE status of activation
  EXPECT_EQ(statuses_.front().state, rover_dl_ARM_IDLE);
  EXPECT_EQ(h_->health(), rover_HEALTH_OK);

  const rover_dl_ArmStatus moving = Send(Place(3, target));
  ASSERT_EQ(moving.state, rover_dl_ARM_MOVING) << moving.message;
  EXPECT_TRUE(moving.stowed);  // the fake arm starts stowed
  ASSERT_EQ(motor_commands_.size(), 1u);
  const rover_ddl_MotorCommand& m = motor_commands_[0];
  EXPECT_EQ(m.mode, rover_ddl_GROUP_POSITION);
  EXPECT_EQ(m.motor_mask, 0xF000);
  EXPECT_GE(m.command_id, kMotorIdBase);
  EXPECT_DOUBLE_EQ(m.max_rate[12], 0.25);  // arm.speed
  const hwconfig::ArmDescription arm;
  const Result<ArmAngles> hover = arm.FaceDown(target + Eigen::Vector3d(0.0, 0.0, 0.06));
  ASSERT_TRUE(hover.ok());
  for (int j = 0; j < 4; ++j) {
    EXPECT_DOUBLE_EQ(m.goal[12 + j], (*hover)[static_cast<std::size_t>(j)]);
  }

  ASSERT_TRUE(Advance(120.0, [&] { return !Last(rover_dl_ARM_MOVING); }));
  const rover_dl_ArmStatus& placed = statuses_.back();
  ASSERT_EQ(placed.state, rover_dl_ARM_PLACED) << placed.message;
  EXPECT_EQ(placed.command_id, 3u);
  EXPECT_TRUE(placed.contact);
  EXPECT_FALSE(placed.stowed);
  EXPECT_NEAR(placed.tool_point.z, target.z(), 0.002);
  EXPECT_NEAR(arm_.face().z(), target.z(), 0.002);
  EXPECT_EQ(std::string(placed.message).rfind("placed: face at (", 0), 0u) << placed.message;
  // Three motor commands: above the target, the slow descent, the stop on contact.
  ASSERT_EQ(motor_commands_.size(), 3u);
  EXPECT_LT(motor_commands_[1].max_rate[12], 0.05);
  EXPECT_GT(motor_commands_[1].max_rate[12], 0.0);
  EXPECT_EQ(motor_commands_[2].mode, rover_ddl_GROUP_STOP);
  EXPECT_EQ(motor_commands_[2].motor_mask, 0xF000);
  EXPECT_FALSE(arm_.moving());

  // Back to stow: the lift, then the stowed pose.
  ASSERT_EQ(Send(Command(4, rover_dl_ARM_MODE_STOW)).state, rover_dl_ARM_MOVING);
  ASSERT_TRUE(Advance(120.0, [&] { return !Last(rover_dl_ARM_MOVING); }));
  EXPECT_EQ(statuses_.back().state, rover_dl_ARM_STOWED) << statuses_.back().message;
  EXPECT_TRUE(statuses_.back().stowed);
  EXPECT_FALSE(statuses_.back().contact);
  EXPECT_EQ(motor_commands_.size(), 5u);
}

TEST_F(ArmServiceTest, BadCommandsAreRejectedNamingTheReasonAndNothingMoves) {
  Start();
  Advance(0.2);
  rover_dl_ArmCommand c = Command(1, rover_dl_ARM_MODE_JOINTS);
  c.joints[2] = NAN;
  rover_dl_ArmStatus s = Send(c);
  EXPECT_EQ(s.state, rover_dl_ARM_REJECTED);
  EXPECT_NE(std::string(s.message).find("joints[2] is nan"), std::string::npos) << s.message;

  // Into the left front wheel: the message names the part.
  const hwconfig::RoverDescription rover;
  const Eigen::Vector3d on_wheel =
      rover.WheelCentre(hwconfig::kWheelLF) + Eigen::Vector3d(0.0, 0.0, rover.wheel_radius + 0.02);
  s = Send(Place(2, on_wheel));
  EXPECT_EQ(s.state, rover_dl_ARM_REJECTED);
  EXPECT_NE(std::string(s.message).find("wheel_LF"), std::string::npos) << s.message;

  c = Command(3, rover_dl_ARM_MODE_STOW);
  c.timeout_s = 1e9;
  s = Send(c);
  EXPECT_EQ(s.state, rover_dl_ARM_REJECTED);
  EXPECT_NE(std::string(s.message).find("timeout_s = "), std::string::npos) << s.message;
  EXPECT_NE(std::string(s.message).find(" s is outside [0, 600]"), std::string::npos);
  EXPECT_TRUE(motor_commands_.empty());
  EXPECT_EQ(arm_.commands(), 0);

  // Stale joints: refused, naming the age; the service still serves a good command afterwards.
  publish_joints_ = false;
  Advance(1.0);
  s = Send(Command(4, rover_dl_ARM_MODE_STOW));
  EXPECT_EQ(s.state, rover_dl_ARM_REJECTED);
  EXPECT_NE(std::string(s.message).find("ddl/joint_state is stale"), std::string::npos)
      << s.message;
  EXPECT_EQ(h_->health(), rover_HEALTH_STALE);
  publish_joints_ = true;
  Advance(0.1);
  EXPECT_EQ(Send(Command(5, rover_dl_ARM_MODE_STOW)).state, rover_dl_ARM_MOVING);
}

TEST_F(ArmServiceTest, MotorDriverFaultAndStopCommandEndTheMove) {
  Start();
  Advance(0.2);
  arm_.jammed = true;
  ASSERT_EQ(Send(Place(1, Eigen::Vector3d(1.0, 0.0, 0.0))).state, rover_dl_ARM_MOVING);
  rover_ddl_MotorStatus fault{};
  fault.command_id = motor_commands_.back().command_id;
  fault.state = rover_ddl_GROUP_FAULT;
  fault.fault = rover_ddl_MOTOR_FAULT_STALL;
  fault.fault_motor = 13;
  dds::CopyString(fault.message, "shoulder made no progress");
  ASSERT_TRUE(motor_status_w_.Write(fault).ok());
  ASSERT_TRUE(Advance(1.0, [&] { return Last(rover_dl_ARM_FAULT); }));
  EXPECT_EQ(std::string(statuses_.back().message),
            "motor driver FAULT STALL on arm_shoulder: shoulder made no progress");

  arm_.jammed = false;
  ASSERT_EQ(Send(Place(3, Eigen::Vector3d(1.0, 0.0, 0.0))).state, rover_dl_ARM_MOVING);
  Advance(1.0);
  const rover_dl_ArmStatus stopped = Send(Command(4, rover_dl_ARM_MODE_STOP));
  EXPECT_EQ(stopped.state, rover_dl_ARM_FAULT);
  EXPECT_EQ(std::string(stopped.message), "stopped by command 4");
  Advance(0.1);
  EXPECT_EQ(motor_commands_.back().mode, rover_ddl_GROUP_STOP);
  EXPECT_FALSE(arm_.moving());
}

TEST_F(ArmServiceTest, InvalidParametersRefuseConfigurationNamingTheKey) {
  ArmService service;
  testing::ServiceHarness h(service, "dl-arm-test", {"arm.status_rate_hz=20"});
  ASSERT_FALSE(h.ok());
  EXPECT_NE(h.status().message().find("arm.status_rate_hz"), std::string::npos)
      << h.status().message();
}

}  // namespace
}  // namespace rover::dl::arm
