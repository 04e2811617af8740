#pragma once
/// @file
/// Fake instrument arm (header only; target rover_test_fakes, whose rover_msg_idl brings
/// rover_hwconfig for the arm description): the four arm motors (12..15) as ddl-motor and
/// ddl-joints would report them, kinematic only. It follows ddl/motor_command for the arm
/// motors: a position goal moves the four joints along the straight joint-space line to the
/// goal in (largest travel) / max_rate seconds (the synchronised move of ddl-motor without its
/// acceleration ramps; 0.25 rad/s when the command gives no rate); STOP brakes. Step integrates,
/// Joints reports ddl/joint_state with arm_angle and arm_contact, which closes when the
/// instrument face's centre (ArmDescription::Forward) is at or below `surface` (none: never).
/// A position group that arrives is reported DONE on ddl/motor_status (TakeStatus), as the
/// motor driver does; `jammed` makes the joints stop moving (a stall the test reports itself).
/// Commands for other motors are ignored. Deterministic: no randomness; it moves only in Step.
/// The test wires it to DDS.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <optional>

#include <Eigen/Core>

#include "rover/base/clock.hpp"
#include "rover/hwconfig/arm_description.hpp"
#include "rover/runtime/dds.hpp"

namespace rover::testing {

class FakeArm {
 public:
  static constexpr int kFirstMotor = 12;  ///< azimuth; shoulder, elbow, wrist follow
  static constexpr unsigned kMask = 0xF000u;

  /// Starts in the arm description's stowed pose.
  explicit FakeArm(const hwconfig::ArmDescription& arm = {}) : arm_(arm), q_(arm.stow) {}

  /// Takes a motor command if it selects an arm motor (or is a STOP of all motors).
  void Apply(const rover_ddl_MotorCommand& c) {
    const unsigned mask = c.motor_mask;
    const bool all = c.mode == rover_ddl_GROUP_STOP && mask == 0;
    if (!all && (mask & kMask) == 0) return;
    ++commands_;
    if (c.mode != rover_ddl_GROUP_POSITION) {
      moving_ = false;  // STOP (or velocity, which the arm never uses): brake
      return;
    }
    start_ = q_;
    double travel = 0.0;
    for (std::size_t k = 0; k < q_.size(); ++k) {
      goal_[k] = c.goal[kFirstMotor + k];
      travel = std::max(travel, std::abs(goal_[k] - start_[k]));
    }
    const double rate = c.max_rate[kFirstMotor] > 0.0 ? c.max_rate[kFirstMotor] : 0.25;
    last_rate_ = rate;
    duration_ = travel / rate;
    elapsed_ = 0.0;
    group_ = c.command_id;
    moving_ = true;
  }

  /// Moves the joints for `dt` [s].
  void Step(double dt) {
    if (!moving_ || jammed) return;
    elapsed_ += dt;
    const double s = duration_ > 0.0 ? std::min(1.0, elapsed_ / duration_) : 1.0;
    for (std::size_t k = 0; k < q_.size(); ++k) q_[k] = start_[k] + s * (goal_[k] - start_[k]);
    if (s >= 1.0) {
      moving_ = false;
      done_ = group_;
    }
  }

  /// ddl/joint_state now: the arm angles and contact switch (other joints at 0), health OK.
  rover_ddl_JointState Joints(Time t) const {
    rover_ddl_JointState j{};
    j.header.stamp_ns = t.ns;
    for (std::size_t k = 0; k < q_.size(); ++k) j.arm_angle[k] = q_[k];
    j.arm_contact = contact();
    j.health = rover_HEALTH_OK;
    return j;
  }

  /// The DONE ddl/motor_status of a group that arrived since the last call, if any.
  std::optional<rover_ddl_MotorStatus> TakeStatus(Time t) {
    if (!done_.has_value()) return std::nullopt;
    rover_ddl_MotorStatus s{};
    s.header.stamp_ns = t.ns;
    s.command_id = *done_;
    s.state = rover_ddl_GROUP_DONE;
    s.fault = rover_ddl_MOTOR_FAULT_NONE;
    s.fault_motor = -1;
    for (std::size_t k = 0; k < q_.size(); ++k) s.position[kFirstMotor + k] = q_[k];
    done_.reset();
    return s;
  }

  /// Centre of the instrument's face, rover frame [m].
  Eigen::Vector3d face() const { return arm_.Forward(q_).face; }
  bool contact() const { return surface.has_value() && face().z() <= *surface; }
  const hwconfig::ArmAngles& q() const { return q_; }  ///< [rad]
  double last_rate() const { return last_rate_; }      ///< max_rate of the latest goal [rad/s]
  int commands() const { return commands_; }           ///< arm motor commands taken
  bool moving() const { return moving_; }

  std::optional<double> surface;  ///< [m] height of a horizontal surface below the face
  bool jammed = false;

 private:
  hwconfig::ArmDescription arm_;
  hwconfig::ArmAngles q_{}, start_{}, goal_{};
  double duration_ = 0.0, elapsed_ = 0.0, last_rate_ = 0.0;
  bool moving_ = false;
  std::uint32_t group_ = 0;
  std::optional<std::uint32_t> done_;
  int commands_ = 0;
};

}  // namespace rover::testing
