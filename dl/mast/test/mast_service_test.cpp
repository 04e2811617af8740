// dl-mast in-process: the service in the shared ServiceHarness (isolated domain, simulated run
// clock) with the fake mast motors of tests/support/fakes playing ddl-motor and ddl-joints and
// the fake dl-pose; the test plays the APL (dl/mast_command in, dl/mast_status out).
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "mast_service.hpp"
#include "rover/geometry/transforms.hpp"
#include "rover/msg/mast_idl.hpp"
#include "rover/testing/fakes/fake_mast.hpp"
#include "rover/testing/fakes/fake_pose.hpp"
#include "rover/testing/service_harness.hpp"

namespace rover::dl::mast {
namespace {

constexpr double kStep = 0.02;  // 50 Hz joint state and sim/clock

class MastServiceTest : public ::testing::Test {
 protected:
  void Start(std::vector<std::string> overrides = {}) {
    h_ = std::make_unique<testing::ServiceHarness>(service_, "dl-mast-test", std::move(overrides));
    ASSERT_TRUE(h_->ok()) << h_->status().message();
    joint_w_ = h_->Writer<rover_ddl_JointState>("ddl/joint_state");
    motor_status_w_ = h_->Writer<rover_ddl_MotorStatus>("ddl/motor_status");
    command_w_ = h_->Writer<rover_dl_MastCommand>("dl/mast_command");
    motor_r_ = h_->Reader<rover_ddl_MotorCommand>("ddl/motor_command");
    status_r_ = h_->Reader<rover_dl_MastStatus>("dl/mast_status");
    ASSERT_TRUE(pose_.Create(h_->peer()).ok());
    ASSERT_TRUE(h_->SpinUntil([&] { return pose_.Matched(); }));
  }

  // Advances the run clock by `seconds` in 20 ms steps (fake motors move, joints and pose go out,
  // then sim/clock); stops early when `until` holds.
  bool Advance(double seconds, const std::function<bool()>& until = nullptr) {
    const int steps = static_cast<int>(std::lround(seconds / kStep));
    for (int i = 0; i < steps; ++i) {
      ++step_;
      const Time now{step_ * 20'000'000};
      mast_.Step(kStep);
      if (publish_joints_) {
        EXPECT_TRUE(joint_w_.Write(mast_.Joints(now)).ok());
      }
      if (step_ % 5 == 0) {
        EXPECT_TRUE(pose_.Publish(now).ok());
      }
      if (auto s = mast_.TakeStatus(now)) {
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
      mast_.Apply(m.data());
      motor_commands_.push_back(m.data());
    }
    for (auto& s : status_r_.Take(64)) statuses_.push_back(s.data());
  }

  // Sends a command and spins until a status for it arrives; returns that status.
  rover_dl_MastStatus Send(const rover_dl_MastCommand& c) {
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

  static rover_dl_MastCommand Angles(std::uint32_t id, double pan, double tilt) {
    rover_dl_MastCommand c{};
    c.command_id = id;
    c.pointing = rover_dl_MAST_POINT_ANGLES;
    c.pan = pan;
    c.tilt = tilt;
    return c;
  }

  bool Last(rover_dl_MastState state) const {
    return !statuses_.empty() && statuses_.back().state == state;
  }

  MastService service_;
  std::unique_ptr<testing::ServiceHarness> h_;
  dds::Writer<rover_ddl_JointState> joint_w_;
  dds::Writer<rover_ddl_MotorStatus> motor_status_w_;
  dds::Writer<rover_dl_MastCommand> command_w_;
  dds::Reader<rover_ddl_MotorCommand> motor_r_;
  dds::Reader<rover_dl_MastStatus> status_r_;
  testing::FakePose pose_;
  testing::FakeMast mast_;
  std::vector<rover_ddl_MotorCommand> motor_commands_;
  std::vector<rover_dl_MastStatus> statuses_;
  std::int64_t step_ = 0;
  bool publish_joints_ = true;
};

TEST_F(MastServiceTest, AnglesCommandDrivesTheMastMotorsToTheGoal) {
  Start();
  Advance(0.2);
  ASSERT_FALSE(statuses_.empty());  // the latched IDLE status of activation
  EXPECT_EQ(statuses_.front().state, rover_dl_MAST_IDLE);

  const rover_dl_MastStatus moving = Send(Angles(3, 0.6, -0.3));
  EXPECT_EQ(moving.state, rover_dl_MAST_MOVING);
  EXPECT_DOUBLE_EQ(moving.pan_goal, 0.6);
  EXPECT_DOUBLE_EQ(moving.tilt_goal, -0.3);
  ASSERT_EQ(motor_commands_.size(), 1u);
  const rover_ddl_MotorCommand& m = motor_commands_[0];
  EXPECT_EQ(m.mode, rover_ddl_GROUP_POSITION);
  EXPECT_EQ(m.motor_mask, 0x0C00);
  EXPECT_DOUBLE_EQ(m.goal[10], 0.6);
  EXPECT_DOUBLE_EQ(m.goal[11], -0.3);
  EXPECT_DOUBLE_EQ(m.max_rate[10], 0.6);  // mast.speed
  EXPECT_GE(m.command_id, kMotorIdBase);

  const std::size_t before = statuses_.size();
  ASSERT_TRUE(Advance(5.0, [&] { return Last(rover_dl_MAST_AT_GOAL); }));
  EXPECT_NEAR(mast_.pan(), 0.6, 1e-9);
  const rover_dl_MastStatus& done = statuses_.back();
  EXPECT_EQ(done.command_id, 3u);
  EXPECT_NEAR(done.pan, 0.6, 1e-9);  // measured
  EXPECT_NEAR(done.tilt, -0.3, 1e-9);
  // 1 s of moving at 0.6 rad/s: periodic MOVING statuses at 2 Hz in between.
  int periodic = 0;
  for (std::size_t i = before; i + 1 < statuses_.size(); ++i) {
    periodic += statuses_[i].state == rover_dl_MAST_MOVING;
  }
  EXPECT_GE(periodic, 1);
  EXPECT_LE(periodic, 3);
  EXPECT_EQ(h_->health(), rover_HEALTH_OK);
}

TEST_F(MastServiceTest, LookAtPointsTheNavcamAtTheSitePoint) {
  Start();
  Eigen::Isometry3d site_from_rover = Eigen::Isometry3d::Identity();
  site_from_rover.linear() = geometry::QuaternionFromRpy(0.02, -0.04, 1.2).toRotationMatrix();
  site_from_rover.translation() = Eigen::Vector3d(12.0, 5.0, 0.3);
  pose_.state.SetPose(site_from_rover);
  Advance(0.2);
  const Eigen::Vector3d target = site_from_rover * Eigen::Vector3d(3.0, 1.0, 0.0);
  rover_dl_MastCommand c{};
  c.command_id = 4;
  c.pointing = rover_dl_MAST_POINT_LOOK_AT;
  c.look_at = {target.x(), target.y(), target.z()};
  const rover_dl_MastStatus moving = Send(c);
  ASSERT_EQ(moving.state, rover_dl_MAST_MOVING) << moving.message;
  ASSERT_TRUE(Advance(5.0, [&] { return Last(rover_dl_MAST_AT_GOAL); }));
  // The NAVCAM boresight at the measured angles passes through the target.
  const hwconfig::RoverDescription rover;
  const Eigen::Isometry3d site_from_pair =
      site_from_rover * rover.NavcamPose(mast_.pan(), mast_.tilt());
  const Eigen::Vector3d to = site_from_pair.inverse() * target;
  EXPECT_GT(to.x(), 2.0);
  EXPECT_LT(std::hypot(to.y(), to.z()), 1e-6);
}

TEST_F(MastServiceTest, BadCommandsAreRejectedNamingFieldAndValueAndNothingMoves) {
  Start();
  Advance(0.2);
  EXPECT_NE(std::string(Send(Angles(1, std::nan(""), 0.0)).message).find("pan is nan"),
            std::string::npos);
  EXPECT_NE(std::string(Send(Angles(2, 0.0, 1.55)).message).find("tilt = 88.81 deg, outside"),
            std::string::npos);
  // A pointing value outside the IDL enum: Cyclone refuses to serialise it, another vendor's
  // writer might send it; if it arrives it is rejected. The conversion path without DDS:
  rover_dl_MastCommand c = Angles(3, 0.0, 0.0);
  c.pointing = static_cast<rover_dl_MastPointing>(9);
  if (command_w_.Write(c).ok()) {
    Advance(0.2);
    for (const auto& st : statuses_) {
      if (st.command_id != 3) continue;
      EXPECT_EQ(st.state, rover_dl_MAST_REJECTED);
      EXPECT_NE(std::string(st.message).find("pointing = 9"), std::string::npos) << st.message;
    }
  }
  EXPECT_EQ(static_cast<int>(msg::MastCommandFromIdl(c).pointing), 9);
  rover_dl_MastStatus s;
  c = Angles(4, 0.0, 0.0);
  c.timeout_s = 1e9;
  s = Send(c);
  EXPECT_EQ(s.state, rover_dl_MAST_REJECTED);
  EXPECT_NE(std::string(s.message).find("timeout_s = "), std::string::npos) << s.message;
  EXPECT_NE(std::string(s.message).find(" s is outside [0, 120]"), std::string::npos);
  c.pointing = rover_dl_MAST_POINT_LOOK_AT;
  c.command_id = 5;
  c.timeout_s = 0.0;
  c.look_at = {NAN, 0.0, 0.0};
  s = Send(c);
  EXPECT_EQ(s.state, rover_dl_MAST_REJECTED);
  EXPECT_NE(std::string(s.message).find("not finite"), std::string::npos) << s.message;
  EXPECT_TRUE(motor_commands_.empty());
  EXPECT_EQ(mast_.commands(), 0);

  // Stale joints: refused, naming the age.
  publish_joints_ = false;
  Advance(1.0);
  s = Send(Angles(6, 0.1, 0.0));
  EXPECT_EQ(s.state, rover_dl_MAST_REJECTED);
  EXPECT_NE(std::string(s.message).find("ddl/joint_state is stale"), std::string::npos)
      << s.message;
  // The service's own DEGRADED, and the input monitor's STALE (the worse) on sys/health.
  EXPECT_EQ(h_->health(), rover_HEALTH_STALE);
  EXPECT_EQ(h_->health_message().rfind("ddl/joint_state stale: ", 0), 0u) << h_->health_message();
  // And the service still serves a good command afterwards.
  publish_joints_ = true;
  Advance(0.1);
  EXPECT_EQ(Send(Angles(7, 0.1, 0.0)).state, rover_dl_MAST_MOVING);
}

TEST_F(MastServiceTest, JammedMotorsTimeOutAndStaleJointsFaultTheMove) {
  Start();
  Advance(0.2);
  mast_.jammed = true;
  rover_dl_MastCommand c = Angles(1, 1.0, 0.0);
  c.timeout_s = 1.0;
  ASSERT_EQ(Send(c).state, rover_dl_MAST_MOVING);
  ASSERT_TRUE(Advance(2.0, [&] { return Last(rover_dl_MAST_FAULT); }));
  EXPECT_NE(std::string(statuses_.back().message).find("timeout after"), std::string::npos)
      << statuses_.back().message;
  EXPECT_EQ(motor_commands_.back().mode, rover_ddl_GROUP_STOP);
  EXPECT_EQ(motor_commands_.back().motor_mask, 0x0C00);

  mast_.jammed = false;
  ASSERT_EQ(Send(Angles(2, -1.0, 0.0)).state, rover_dl_MAST_MOVING);
  publish_joints_ = false;
  ASSERT_TRUE(Advance(2.0, [&] { return Last(rover_dl_MAST_FAULT); }));
  EXPECT_NE(std::string(statuses_.back().message).find("went stale"), std::string::npos);
}

TEST_F(MastServiceTest, MotorDriverFaultOfTheMastGroupFaultsTheMove) {
  Start();
  Advance(0.2);
  mast_.jammed = true;
  ASSERT_EQ(Send(Angles(1, 1.0, 0.0)).state, rover_dl_MAST_MOVING);
  rover_ddl_MotorStatus fault{};
  fault.command_id = motor_commands_.back().command_id;
  fault.state = rover_ddl_GROUP_FAULT;
  fault.fault = rover_ddl_MOTOR_FAULT_STALL;
  fault.fault_motor = 11;
  dds::CopyString(fault.message, "tilt made no progress");
  ASSERT_TRUE(motor_status_w_.Write(fault).ok());
  ASSERT_TRUE(Advance(1.0, [&] { return Last(rover_dl_MAST_FAULT); }));
  EXPECT_EQ(std::string(statuses_.back().message),
            "motor driver FAULT STALL on mast_tilt: tilt made no progress");
}

TEST_F(MastServiceTest, InvalidParametersRefuseConfigurationNamingTheKey) {
  MastService service;
  testing::ServiceHarness h(service, "dl-mast-test", {"mast.tilt_max_deg=-85"});
  ASSERT_FALSE(h.ok());
  EXPECT_NE(h.status().message().find("mast.tilt_max_deg"), std::string::npos)
      << h.status().message();
}

}  // namespace
}  // namespace rover::dl::mast
