#pragma once
/// @file
/// Fake rover below dl-locomotion (header only; target rover_fake_rover): the mobility motors as
/// the DDL would drive them, without dynamics beyond rate limits. It follows ddl/motor_command
/// (steer and drive motors move toward position goals at their rate limits, velocity goals
/// integrate, STOP brakes) and reports ddl/joint_state and the dl/pose heading of a turn in
/// place (integrated from the left-front wheel's rate). Deterministic: no randomness; it moves
/// only in Step. The test wires it to DDS (see dl/locomotion/test/locomotion_rig.hpp).

#include <algorithm>
#include <array>
#include <cstddef>

#include "rover/base/clock.hpp"
#include "rover/dl/locomotion/ackermann.hpp"
#include "rover/geometry/transforms.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/testing/fakes/fake_pose.hpp"

namespace rover::testing {

class FakeRover {
 public:
  FakeRover() { mode_.fill(rover_ddl_GROUP_STOP); }

  /// Takes a motor command: the motors of its mask (all motors for a STOP with an empty mask)
  /// get its mode, goal and rate limit (0.5 rad/s when the command gives none).
  void Apply(const rover_ddl_MotorCommand& c) {
    const bool all = c.mode == rover_ddl_GROUP_STOP && c.motor_mask == 0;
    for (std::size_t m = 0; m < hw::kNumMotors; ++m) {
      if (!all && ((c.motor_mask >> m) & 1u) == 0) continue;
      mode_[m] = c.mode;
      goal_[m] = c.goal[m];
      rate_[m] = c.max_rate[m] > 0.0 ? c.max_rate[m] : 0.5;
    }
  }

  /// Moves every motor for `dt` [s]; a velocity-mode LF wheel turns the rover in place.
  void Step(double dt) {
    const dl::locomotion::RoverGeometry g;
    for (std::size_t m = 0; m < hw::kNumMotors; ++m) {
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
      yaw_ += goal_[0] * g.wheel_radius / dl::locomotion::TurnInPlaceRadius(g, 0) * dt;
    }
  }

  /// ddl/joint_state now: wheel and steer angles, health OK.
  rover_ddl_JointState Joints(Time t) const {
    rover_ddl_JointState j{};
    j.header.stamp_ns = t.ns;
    for (std::size_t i = 0; i < 6; ++i) j.wheel_angle[i] = wheel_[i];
    for (std::size_t i = 0; i < 4; ++i) j.steer_angle[i] = steer_[i];
    const hwconfig::ArmAngles stow = hwconfig::RoverDescription{}.arm.stow;  // the arm stays stowed
    for (std::size_t i = 0; i < stow.size(); ++i) j.arm_angle[i] = stow[i];
    j.health = rover_HEALTH_OK;
    return j;
  }

  /// dl/pose now: at the site origin, heading yaw(), 1e-4 variances.
  rover_dl_PoseEstimate Pose(Time t) const {
    FakePoseState s;
    s.orientation = geometry::QuaternionFromRpy(0.0, 0.0, yaw_);
    s.variance = 1e-4;
    return PoseEstimateMessage(t, s);
  }

  const std::array<double, 6>& wheels() const { return wheel_; }  ///< [rad]
  const std::array<double, 4>& steers() const { return steer_; }  ///< [rad]
  double yaw() const { return yaw_; }                             ///< [rad]

 private:
  std::array<double, 6> wheel_{};
  std::array<double, 4> steer_{};
  std::array<double, 2> spare_{};
  std::array<rover_ddl_GroupMode, hw::kNumMotors> mode_{};
  std::array<double, hw::kNumMotors> goal_{};
  std::array<double, hw::kNumMotors> rate_{};
  double yaw_ = 0.0;
};

}  // namespace rover::testing
