#include "rover/dl/mast/mast_executor.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::dl::mast {
namespace {

Time T(double s) { return Time::FromSeconds(s); }

class MastExecutorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto e = MastExecutor::Create(hwconfig::RoverDescription{}, MastOptions{});
    ASSERT_TRUE(e.ok()) << e.status().message();
    exec_.emplace(std::move(*e));
  }
  void Joints(double t, double pan, double tilt) { exec_->OnJoints({T(t), pan, tilt, true}); }
  MastCommand Angles(std::uint32_t id, double pan, double tilt) {
    MastCommand c;
    c.command_id = id;
    c.pointing = MastPointing::kAngles;
    c.pan = pan;
    c.tilt = tilt;
    return c;
  }
  MastOutput Done(std::uint32_t motor_id, double t) {
    MotorReport r;
    r.command_id = motor_id;
    r.state = MotorGroupState::kDone;
    return exec_->OnMotorStatus(r, T(t));
  }
  std::optional<MastExecutor> exec_;
};

TEST_F(MastExecutorTest, AnglesCommandMovesBothMastMotorsAndArrives) {
  EXPECT_EQ(exec_->status().state, MastState::kIdle);
  Joints(1.0, 0.0, 0.0);
  MastOutput out = exec_->Submit(Angles(5, 0.4, -0.3), T(1.0));
  ASSERT_EQ(out.motor_commands.size(), 1u);
  const MastMotorCommand& m = out.motor_commands[0];
  EXPECT_EQ(m.mode, MotorMode::kPosition);
  EXPECT_EQ(m.motor_mask, (1u << 10) | (1u << 11));
  EXPECT_EQ(m.command_id, kMotorIdBase);
  EXPECT_DOUBLE_EQ(m.pan_goal, 0.4);
  EXPECT_DOUBLE_EQ(m.tilt_goal, -0.3);
  EXPECT_DOUBLE_EQ(m.max_rate, MastOptions{}.speed);
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_EQ(out.statuses[0].state, MastState::kMoving);
  EXPECT_EQ(out.statuses[0].command_id, 5u);

  // Periodic MOVING statuses at status_rate_hz (2 Hz) on the 8 Hz step.
  int moving = 0;
  for (int k = 1; k <= 8; ++k) {
    const double t = 1.0 + k * 0.125;
    Joints(t, 0.05 * k, -0.03 * k);
    for (const MastStatus& s : exec_->Step(T(t)).statuses) {
      EXPECT_EQ(s.state, MastState::kMoving);
      ++moving;
    }
  }
  EXPECT_EQ(moving, 2);
  EXPECT_NEAR(exec_->status().pan, 0.4, 1e-12);  // measured

  // DONE from the motor driver with the joints at the goal: AT_GOAL at once.
  Joints(2.05, 0.4, -0.3);
  out = Done(m.command_id, 2.1);
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_EQ(out.statuses[0].state, MastState::kAtGoal);
  EXPECT_TRUE(exec_->Step(T(2.2)).statuses.empty());  // no more statuses once there
}

TEST_F(MastExecutorTest, IgnoresOtherGroupsAndWaitsForTheJointsAfterDone) {
  Joints(1.0, 0.0, 0.0);
  const std::uint32_t id = exec_->Submit(Angles(1, 0.2, 0.0), T(1.0)).motor_commands[0].command_id;
  EXPECT_TRUE(Done(3, 1.5).statuses.empty());  // a locomotion group
  EXPECT_TRUE(Done(id, 1.5).statuses.empty());  // joints not there yet
  Joints(1.6, 0.199, 0.0);
  const MastOutput out = exec_->Step(T(1.625));
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_EQ(out.statuses[0].state, MastState::kAtGoal);
}

TEST_F(MastExecutorTest, DoneButJointsElsewhereFaultsAfterTheSettleTime) {
  Joints(1.0, 0.0, 0.0);
  const std::uint32_t id = exec_->Submit(Angles(1, 0.2, 0.0), T(1.0)).motor_commands[0].command_id;
  Done(id, 1.5);
  for (double t = 1.5; t < 2.4; t += 0.125) {
    Joints(t, 0.1, 0.0);
    EXPECT_NE(exec_->status().state, MastState::kFault);
    exec_->Step(T(t));
  }
  Joints(2.7, 0.1, 0.0);
  const MastOutput out = exec_->Step(T(2.7));
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_EQ(out.statuses[0].state, MastState::kFault);
  EXPECT_NE(out.statuses[0].message.find("not within tolerance"), std::string::npos);
  ASSERT_EQ(out.motor_commands.size(), 1u);
  EXPECT_EQ(out.motor_commands[0].mode, MotorMode::kStop);
}

TEST_F(MastExecutorTest, RejectsBadCommandsNamingFieldAndValue) {
  auto reject = [&](const MastCommand& c, double t, const std::string& needle) {
    const MastOutput out = exec_->Submit(c, T(t));
    EXPECT_TRUE(out.motor_commands.empty());
    ASSERT_EQ(out.statuses.size(), 1u);
    EXPECT_EQ(out.statuses[0].state, MastState::kRejected);
    EXPECT_EQ(out.statuses[0].command_id, c.command_id);
    EXPECT_NE(out.statuses[0].message.find(needle), std::string::npos) << out.statuses[0].message;
  };
  reject(Angles(1, 0.1, 0.1), 1.0, "no ddl/joint_state");
  Joints(1.0, 0.0, 0.0);
  reject(Angles(2, 0.1, 0.1), 2.0, "ddl/joint_state is stale (latest 1 s old");
  Joints(2.0, 0.0, 0.0);
  reject(Angles(3, std::nan(""), 0.1), 2.0, "pan is nan");
  reject(Angles(4, 0.1, INFINITY), 2.0, "tilt is inf");
  reject(Angles(5, 3.1, 0.0), 2.0, "pan = 177.6 deg, outside [-175, 175] deg");
  reject(Angles(6, 0.0, -1.5), 2.0, "tilt = -85.94 deg");
  MastCommand c = Angles(7, 0.0, 0.0);
  c.timeout_s = -1.0;
  reject(c, 2.0, "timeout_s = -1 s is outside [0, 120]");
  c.timeout_s = std::nan("");
  reject(c, 2.0, "timeout_s is nan");
  c = Angles(8, 0.0, 0.0);
  c.pointing = static_cast<MastPointing>(7);
  reject(c, 2.0, "pointing = 7 is not a MastPointing value");
  c.pointing = MastPointing::kLookAt;
  c.look_at = Eigen::Vector3d(5.0, 0.0, 0.0);
  reject(c, 2.0, "look_at needs dl/pose, none received yet");
  exec_->OnPose({T(0.5), Eigen::Isometry3d::Identity()});
  reject(c, 2.0, "look_at needs a fresh dl/pose (latest 1.5 s old");
  exec_->OnPose({T(2.0), Eigen::Isometry3d::Identity()});
  c.look_at = Eigen::Vector3d(-3.0, 0.0, 1.5);
  reject(c, 2.0, "look_at [-3, 0, 1.5] needs pan = 180 deg");
  EXPECT_EQ(exec_->status().state, MastState::kRejected);
}

TEST_F(MastExecutorTest, LookAtUsesThePoseAndARejectionLeavesARunningMoveAlone) {
  Joints(1.0, 0.0, 0.0);
  exec_->OnPose({T(1.0), Eigen::Isometry3d::Identity()});
  MastCommand c;
  c.command_id = 9;
  c.pointing = MastPointing::kLookAt;
  c.look_at = Eigen::Vector3d(0.35, 3.0, 1.5);  // level with the head, 3 m to the left
  MastOutput out = exec_->Submit(c, T(1.0));
  ASSERT_EQ(out.motor_commands.size(), 1u);
  EXPECT_NEAR(out.motor_commands[0].pan_goal, M_PI / 2, 1e-9);
  EXPECT_NEAR(out.motor_commands[0].tilt_goal, 0.0, 1e-9);
  out = exec_->Submit(Angles(10, 9.0, 0.0), T(1.1));
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_EQ(out.statuses[0].state, MastState::kRejected);
  EXPECT_EQ(exec_->status().state, MastState::kMoving);
  EXPECT_EQ(exec_->status().command_id, 9u);
  // A good new command supersedes the running one.
  out = exec_->Submit(Angles(11, 0.0, 0.0), T(1.2));
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_NE(out.statuses[0].message.find("supersedes command 9"), std::string::npos);
  EXPECT_EQ(out.motor_commands[0].command_id, kMotorIdBase + 1);
}

TEST_F(MastExecutorTest, TimeoutAndStaleJointsFaultAndStopTheMotors) {
  Joints(1.0, 0.0, 0.0);
  MastCommand c = Angles(1, 1.0, 0.0);
  c.timeout_s = 2.0;
  exec_->Submit(c, T(1.0));
  MastOutput out;
  for (double t = 1.125; t < 3.5 && out.motor_commands.empty(); t += 0.125) {
    Joints(t, 0.1, 0.0);
    out = exec_->Step(T(t));
  }
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_EQ(out.statuses[0].state, MastState::kFault);
  EXPECT_NE(out.statuses[0].message.find("timeout after 2.125 s"), std::string::npos)
      << out.statuses[0].message;
  EXPECT_EQ(out.motor_commands[0].mode, MotorMode::kStop);

  Joints(4.0, 0.1, 0.0);
  exec_->Submit(Angles(2, 0.0, 0.0), T(4.0));
  out = exec_->Step(T(4.6));
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_EQ(out.statuses[0].state, MastState::kFault);
  EXPECT_NE(out.statuses[0].message.find("went stale"), std::string::npos);
}

TEST_F(MastExecutorTest, MotorDriverFaultNamesTheMotor) {
  Joints(1.0, 0.0, 0.0);
  const std::uint32_t id = exec_->Submit(Angles(1, 0.5, 0.0), T(1.0)).motor_commands[0].command_id;
  MotorReport r;
  r.command_id = id;
  r.state = MotorGroupState::kFault;
  r.fault = "STALL";
  r.fault_motor = 10;
  r.message = "no progress";
  const MastOutput out = exec_->OnMotorStatus(r, T(1.5));
  ASSERT_EQ(out.statuses.size(), 1u);
  EXPECT_EQ(out.statuses[0].state, MastState::kFault);
  EXPECT_EQ(out.statuses[0].message, "motor driver FAULT STALL on mast_pan: no progress");
  EXPECT_TRUE(exec_->Stop("why", T(1.6)).statuses.empty());  // not moving any more
}

TEST_F(MastExecutorTest, IgnoresBadJointSamples) {
  Joints(1.0, 0.1, 0.2);
  exec_->OnJoints({T(1.1), std::nan(""), 0.0, true});
  exec_->OnJoints({T(1.1), 0.5, 0.5, false});
  exec_->OnJoints({T(0.9), 0.7, 0.7, true});  // older
  EXPECT_DOUBLE_EQ(exec_->status().pan, 0.1);
  EXPECT_DOUBLE_EQ(exec_->status().tilt, 0.2);
  EXPECT_STREQ(MastStateName(MastState::kAtGoal), "AT_GOAL");
  EXPECT_STREQ(MastStateName(static_cast<MastState>(42)), "?");
}

TEST(MastExecutor, CreateRefusesInvalidOptions) {
  MastOptions o;
  o.speed = -1.0;
  auto e = MastExecutor::Create(hwconfig::RoverDescription{}, o);
  ASSERT_FALSE(e.ok());
  EXPECT_EQ(e.status().message().rfind("speed", 0), 0u);
}

}  // namespace
}  // namespace rover::dl::mast
