#pragma once
/// @file
/// Fake mast motors (header only; target rover_test_fakes): the pan and tilt motors (10, 11) as
/// ddl-motor and ddl-joints would report them, without dynamics beyond a rate limit. It follows
/// ddl/motor_command for the mast motors (position goals at the command's max_rate, 0.6 rad/s
/// when it gives none; STOP brakes), integrates the angles in Step and reports them as
/// ddl/joint_state (Joints). A position group that arrives is reported DONE on ddl/motor_status
/// (TakeStatus), as the motor driver does; `jammed` makes the motors stop moving (a stall the
/// test reports itself). Commands for other motors are ignored. Deterministic: no randomness;
/// it moves only in Step. The test wires it to DDS.

#include <cmath>
#include <cstdint>
#include <optional>

#include "rover/base/clock.hpp"
#include "rover/runtime/dds.hpp"

namespace rover::testing {

class FakeMast {
 public:
  static constexpr int kPan = 10;
  static constexpr int kTilt = 11;

  /// Takes a motor command if it selects a mast motor (or is a STOP of all motors).
  void Apply(const rover_ddl_MotorCommand& c) {
    const unsigned mask = c.motor_mask;
    const bool all = c.mode == rover_ddl_GROUP_STOP && mask == 0;
    if (!all && (mask & ((1u << kPan) | (1u << kTilt))) == 0) return;
    ++commands_;
    if (c.mode == rover_ddl_GROUP_POSITION) {
      goal_pan_ = c.goal[kPan];
      goal_tilt_ = c.goal[kTilt];
      rate_ = c.max_rate[kPan] > 0.0 ? c.max_rate[kPan] : 0.6;
      group_ = c.command_id;
      moving_ = true;
    } else {
      moving_ = false;  // STOP (or velocity, which the mast never uses): brake
    }
  }

  /// Moves the motors for `dt` [s].
  void Step(double dt) {
    if (!moving_ || jammed) return;
    const auto toward = [&](double& q, double goal) {
      if (std::abs(goal - q) <= rate_ * dt) {
        q = goal;
      } else {
        q += goal > q ? rate_ * dt : -rate_ * dt;
      }
    };
    toward(pan_, goal_pan_);
    toward(tilt_, goal_tilt_);
    if (pan_ == goal_pan_ && tilt_ == goal_tilt_) {
      moving_ = false;
      done_ = group_;
    }
  }

  /// ddl/joint_state now: the mast angles (wheels at 0), health OK.
  rover_ddl_JointState Joints(Time t) const {
    rover_ddl_JointState j{};
    j.header.stamp_ns = t.ns;
    j.mast_pan = pan_;
    j.mast_tilt = tilt_;
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
    s.position[kPan] = pan_;
    s.position[kTilt] = tilt_;
    done_.reset();
    return s;
  }

  double pan() const { return pan_; }    ///< [rad]
  double tilt() const { return tilt_; }  ///< [rad]
  int commands() const { return commands_; }  ///< mast motor commands taken
  bool jammed = false;

 private:
  double pan_ = 0.0, tilt_ = 0.0;
  double goal_pan_ = 0.0, goal_tilt_ = 0.0;
  double rate_ = 0.6;
  bool moving_ = false;
  std::uint32_t group_ = 0;
  std::optional<std::uint32_t> done_;
  int commands_ = 0;
};

}  // namespace rover::testing
