#pragma once
// The dl-locomotion service tests' rig (locomotion_service_test.cpp, rover_drive_test.cpp): the
// service in the shared ServiceHarness (isolated domain, simulated run clock) with the fake rover
// of tests/support/fakes playing the DDL below it: the rig applies the service's
// ddl/motor_command to the fake rover and publishes its ddl/joint_state at 50 Hz and dl/pose at
// 10 Hz; the test plays the APL (dl/drive_command in, dl/drive_status out). Deterministic: no
// randomness, time advances only in Advance() and StepOnce().
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "locomotion_service.hpp"
#include "rover/testing/fakes/fake_rover.hpp"
#include "rover/testing/service_harness.hpp"

namespace rover::dl::locomotion::testing_support {

class LocomotionRig {
 public:
  static constexpr double kStep = 0.02;  // 50 Hz joint state and sim/clock

  void Start(std::vector<std::string> overrides = {}) {
    h_ = std::make_unique<testing::ServiceHarness>(service_, "dl-locomotion-test",
                                                   std::move(overrides));
    ASSERT_TRUE(h_->ok()) << h_->status().message();
    joint_w_ = h_->Writer<rover_ddl_JointState>("ddl/joint_state");
    pose_w_ = h_->Writer<rover_dl_PoseEstimate>("dl/pose");
    command_w_ = h_->Writer<rover_dl_DriveCommand>("dl/drive_command");
    motor_status_w_ = h_->Writer<rover_ddl_MotorStatus>("ddl/motor_status");
    motor_r_ = h_->Reader<rover_ddl_MotorCommand>("ddl/motor_command");
    status_r_ = h_->Reader<rover_dl_DriveStatus>("dl/drive_status");
  }

  void Stop() { h_.reset(); }

  /// Advances the run clock by `seconds` in 20 ms steps: the fake rover moves, joint state
  /// (50 Hz) and pose (10 Hz) are published, then sim/clock; the service runs until it has seen
  /// the new time; its motor commands are applied to the fake rover. Stops early (returns true)
  /// when `until` holds.
  bool Advance(double seconds, const std::function<bool()>& until = nullptr) {
    const int steps = static_cast<int>(std::lround(seconds / kStep));
    for (int i = 0; i < steps; ++i) {
      StepOnce();
      if (until && until()) return true;
    }
    return false;
  }

  void StepOnce() {
    ++step_;
    now_ = Time{step_ * 20'000'000};  // integer ns: no rounding drift against timer periods
    rover_.Step(kStep);
    if (publish_joints_) {
      EXPECT_TRUE(joint_w_.Write(rover_.Joints(now_)).ok());
    }
    if (publish_pose_ && step_ % 5 == 0) {
      EXPECT_TRUE(pose_w_.Write(rover_.Pose(now_)).ok());
    }
    EXPECT_TRUE(h_->AdvanceTo(now_));
    Collect();
  }

  /// Takes what the service published; applies motor commands to the fake rover.
  void Collect() {
    for (auto& m : motor_r_.Take(64)) {
      rover_.Apply(m.data());
      motor_commands_.push_back(m.data());
    }
    for (auto& s : status_r_.Take(64)) statuses_.push_back(s.data());
  }

  /// Sends a command and lets the service take it (spins until a status for it appears).
  void Send(const rover_dl_DriveCommand& c) {
    ASSERT_TRUE(command_w_.Write(c).ok());
    ASSERT_TRUE(h_->SpinUntil([&] {
      Collect();
      return !StatusesOf(c.command_id).empty();
    }));
  }

  static rover_dl_DriveCommand Command(std::uint32_t id, rover_dl_DrivePrimitive p,
                                       double curvature = 0.0, double distance = 0.0,
                                       double angle = 0.0, double speed = 0.0) {
    rover_dl_DriveCommand c{};
    c.command_id = id;
    c.primitive = p;
    c.curvature = curvature;
    c.distance = distance;
    c.angle = angle;
    c.speed = speed;
    return c;
  }

  std::vector<rover_dl_DriveStatus> StatusesOf(std::uint32_t id) const {
    std::vector<rover_dl_DriveStatus> out;
    for (const auto& s : statuses_) {
      if (s.command_id == id) out.push_back(s);
    }
    return out;
  }

  bool Terminal(std::uint32_t id) const {
    for (const auto& s : StatusesOf(id)) {
      if (s.state == rover_dl_DRIVE_DONE || s.state == rover_dl_DRIVE_FAILED ||
          s.state == rover_dl_DRIVE_REJECTED) {
        return true;
      }
    }
    return false;
  }

  testing::FakeRover& rover() { return rover_; }
  Time now() const { return now_; }
  ServiceContext& ctx() { return h_->ctx(); }
  LocomotionService& service() { return service_; }
  std::vector<rover_ddl_MotorCommand>& motor_commands() { return motor_commands_; }
  std::vector<rover_dl_DriveStatus>& statuses() { return statuses_; }
  int domain() const { return h_->domain(); }
  void set_publish_joints(bool on) { publish_joints_ = on; }
  void set_publish_pose(bool on) { publish_pose_ = on; }
  dds::Writer<rover_dl_DriveCommand>& command_writer() { return command_w_; }

 private:
  LocomotionService service_;  // outlives the harness that runs it
  std::unique_ptr<testing::ServiceHarness> h_;
  dds::Writer<rover_ddl_JointState> joint_w_;
  dds::Writer<rover_dl_PoseEstimate> pose_w_;
  dds::Writer<rover_dl_DriveCommand> command_w_;
  dds::Writer<rover_ddl_MotorStatus> motor_status_w_;
  dds::Reader<rover_ddl_MotorCommand> motor_r_;
  dds::Reader<rover_dl_DriveStatus> status_r_;
  testing::FakeRover rover_;
  std::int64_t step_ = 0;
  Time now_;
  bool publish_joints_ = true;
  bool publish_pose_ = true;
  std::vector<rover_ddl_MotorCommand> motor_commands_;
  std::vector<rover_dl_DriveStatus> statuses_;
};

}  // namespace rover::dl::locomotion::testing_support
