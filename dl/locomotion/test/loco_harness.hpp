#pragma once
// Test harness for the dl-locomotion service: the service in-process on an isolated DDS domain
// with a simulated run clock that the test publishes on sim/clock, and a fake rover that plays
// the DDL: it follows ddl/motor_command (steer and drive motors move toward their goals at their
// rate limits, velocity goals integrate, STOP brakes) and publishes ddl/joint_state at 50 Hz and
// dl/pose at 10 Hz (heading integrated from the turn-in-place wheel rates). Deterministic: no
// randomness, time advances only in Advance().
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <vector>

#include "locomotion_service.hpp"
#include "rover/dl/locomotion/ackermann.hpp"
#include "rover/geometry/transforms.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::dl::testing_support {

/// The motors as the DDL would drive them, without dynamics beyond rate limits.
class FakeRover {
 public:
  FakeRover() { mode_.fill(rover_ddl_GROUP_STOP); }

  void Apply(const rover_ddl_MotorCommand& c) {
    const bool all = c.mode == rover_ddl_GROUP_STOP && c.motor_mask == 0;
    for (std::size_t m = 0; m < kNumMotors; ++m) {
      if (!all && ((c.motor_mask >> m) & 1u) == 0) continue;
      mode_[m] = c.mode;
      goal_[m] = c.goal[m];
      rate_[m] = c.max_rate[m] > 0.0 ? c.max_rate[m] : 0.5;
    }
  }

  void Step(double dt) {
    const RoverGeometry g;
    for (std::size_t m = 0; m < kNumMotors; ++m) {
      double& q = m < 6 ? wheel_[m] : (m < 10 ? steer_[m - 6] : spare_[m - 10]);
      if (mode_[m] == rover_ddl_GROUP_POSITION) {
        const double step = std::clamp(goal_[m] - q, -rate_[m] * dt, rate_[m] * dt);
        q += step;
      } else if (mode_[m] == rover_ddl_GROUP_VELOCITY) {
        q += goal_[m] * dt;
      }
    }
    // Heading from a turn in place: every wheel's rate is q_i w / r; use the LF wheel.
    if (mode_[0] == rover_ddl_GROUP_VELOCITY) {
      yaw_ += goal_[0] * g.wheel_radius / TurnInPlaceRadius(g, 0) * dt;
    }
  }

  rover_ddl_JointState Joints(Time t) const {
    rover_ddl_JointState j{};
    j.header.stamp_ns = t.ns;
    for (std::size_t i = 0; i < 6; ++i) j.wheel_angle[i] = wheel_[i];
    for (std::size_t i = 0; i < 4; ++i) j.steer_angle[i] = steer_[i];
    j.health = rover_HEALTH_OK;
    return j;
  }

  rover_dl_PoseEstimate Pose(Time t) const {
    rover_dl_PoseEstimate p{};
    p.header.stamp_ns = t.ns;
    const Eigen::Quaterniond q = geometry::QuaternionFromRpy(0.0, 0.0, yaw_);
    p.pose.orientation = {q.w(), q.x(), q.y(), q.z()};
    for (int i = 0; i < 6; ++i) p.covariance[i * 7] = 1e-4;
    return p;
  }

  const std::array<double, 6>& wheels() const { return wheel_; }
  const std::array<double, 4>& steers() const { return steer_; }
  double yaw() const { return yaw_; }

 private:
  std::array<double, 6> wheel_{};
  std::array<double, 4> steer_{};
  std::array<double, 2> spare_{};
  std::array<rover_ddl_GroupMode, kNumMotors> mode_{};
  std::array<double, kNumMotors> goal_{};
  std::array<double, kNumMotors> rate_{};
  double yaw_ = 0.0;
};

/// The service under test plus the test's own participant playing simulator, DDL and APL.
class LocoHarness {
 public:
  static constexpr double kStep = 0.02;  // 50 Hz joint state and sim/clock

  void Start(std::vector<std::string> overrides = {}) {
    lease_ = testing::IsolatedDomain();
    options_.name = "dl-locomotion-test";
    options_.domain = lease_.domain();
    options_.clock = "sim";
    options_.overrides = std::move(overrides);
    auto ctx = ServiceContext::Create(options_);
    ASSERT_TRUE(ctx.ok()) << ctx.status().message();
    ctx_ = std::move(*ctx);
    lifecycle_ = std::make_unique<Lifecycle>(service_, *ctx_, options_);
    ASSERT_TRUE(lifecycle_->Configure().ok()) << lifecycle_->last_error();
    ASSERT_TRUE(lifecycle_->Activate().ok()) << lifecycle_->last_error();

    auto p = dds::Participant::Create(lease_.domain());
    ASSERT_TRUE(p.ok()) << p.status().message();
    participant_ = std::move(*p);
    ASSERT_TRUE(Make(clock_w_, "sim/clock"));
    ASSERT_TRUE(Make(joint_w_, "ddl/joint_state"));
    ASSERT_TRUE(Make(pose_w_, "dl/pose"));
    ASSERT_TRUE(Make(command_w_, "dl/drive_command"));
    ASSERT_TRUE(Make(motor_status_w_, "ddl/motor_status"));
    ASSERT_TRUE(Make(motor_r_, "ddl/motor_command"));
    ASSERT_TRUE(Make(status_r_, "dl/drive_status"));
    ASSERT_TRUE(testing::WaitFor([&] {
      return clock_w_.MatchedReaders() >= 1 && joint_w_.MatchedReaders() >= 1 &&
             pose_w_.MatchedReaders() >= 1 && command_w_.MatchedReaders() >= 1 &&
             motor_status_w_.MatchedReaders() >= 1 && motor_r_.MatchedWriters() >= 1 &&
             status_r_.MatchedWriters() >= 1;
    }));
  }

  void Stop() {
    if (lifecycle_) (void)lifecycle_->Shutdown();
  }

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
    rover_sim_Clock c{};
    c.sim_time_ns = now_.ns;
    EXPECT_TRUE(clock_w_.Write(c).ok());
    EXPECT_TRUE(testing::WaitFor([&] {
      ctx_->executor().SpinOnce(std::chrono::milliseconds(5));
      return ctx_->Now().ns == now_.ns;
    }));
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
    ASSERT_TRUE(testing::WaitFor([&] {
      ctx_->executor().SpinOnce(std::chrono::milliseconds(5));
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

  FakeRover& rover() { return rover_; }
  Time now() const { return now_; }
  ServiceContext& ctx() { return *ctx_; }
  LocomotionService& service() { return service_; }
  std::vector<rover_ddl_MotorCommand>& motor_commands() { return motor_commands_; }
  std::vector<rover_dl_DriveStatus>& statuses() { return statuses_; }
  int domain() const { return lease_.domain(); }
  void set_publish_joints(bool on) { publish_joints_ = on; }
  void set_publish_pose(bool on) { publish_pose_ = on; }
  dds::Writer<rover_dl_DriveCommand>& command_writer() { return command_w_; }

 private:
  template <class E>
  bool Make(E& out, const std::string& topic) {
    auto e = E::Create(participant_, topic);
    if (!e.ok()) {
      ADD_FAILURE() << e.status().message();
      return false;
    }
    out = std::move(*e);
    return true;
  }

  dds::DomainLease lease_;
  ServiceOptions options_;
  std::unique_ptr<ServiceContext> ctx_;
  LocomotionService service_;
  std::unique_ptr<Lifecycle> lifecycle_;
  dds::Participant participant_;
  dds::Writer<rover_sim_Clock> clock_w_;
  dds::Writer<rover_ddl_JointState> joint_w_;
  dds::Writer<rover_dl_PoseEstimate> pose_w_;
  dds::Writer<rover_dl_DriveCommand> command_w_;
  dds::Writer<rover_ddl_MotorStatus> motor_status_w_;
  dds::Reader<rover_ddl_MotorCommand> motor_r_;
  dds::Reader<rover_dl_DriveStatus> status_r_;
  FakeRover rover_;
  std::int64_t step_ = 0;
  Time now_;
  bool publish_joints_ = true;
  bool publish_pose_ = true;
  std::vector<rover_ddl_MotorCommand> motor_commands_;
  std::vector<rover_dl_DriveStatus> statuses_;
};

}  // namespace rover::dl::testing_support
