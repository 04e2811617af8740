#pragma once
/// @file
/// MastExecutor: the mast pointing state machine (no DDS, no threads, no clock reads; the caller
/// passes the run-clock time). The dl-mast service binds it to topics.
///
///   Submit(command)      checks the command; a good one becomes the goal: one position command
///                        for the two mast motors (hw::kMastPan, hw::kMastTilt) at `speed`, and
///                        MOVING. A new command supersedes a running one (the mast simply goes
///                        to the newer goal). Bad commands -> REJECTED with a message naming the
///                        field and value, no motor command; a running move keeps running.
///   OnJoints(sample)     the measured pan/tilt (ddl/joint_state); unhealthy, non-finite and
///                        out-of-order samples are ignored (they do not count as fresh).
///   OnPose(sample)       the rover pose in the site frame (dl/pose), for look-at commands.
///   OnMotorStatus(s)     the motor driver's report on a group; only groups this executor
///                        commanded count. FAULT or REJECTED -> FAULT naming the motor driver's
///                        reason; DONE with both joints within tolerance -> AT_GOAL.
///   Step(now)            at check_rate_hz: AT_GOAL once the motors are DONE and the joints
///                        within tolerance; FAULT on timeout or stale joints during a move (and
///                        a GROUP_STOP of the mast motors); FAULT when the motors are DONE
///                        but the joints stay outside the tolerance for 1 s; a status every 1 / status_rate_hz
///                        while MOVING.
///
/// States (rover_dl.idl MastState): IDLE (no command yet), MOVING, AT_GOAL, FAULT, REJECTED.
/// Refusals: unknown pointing value; NaN/inf pan, tilt, look_at or timeout_s; pan/tilt outside
/// [pan_min, pan_max] / [tilt_min, tilt_max]; timeout_s < 0 or > max_timeout_s; no fresh
/// ddl/joint_state (older than joint_stale_s, or none yet); for MAST_POINT_LOOK_AT no fresh
/// dl/pose (pose_stale_s) and every LookAtAngles refusal (look_at.hpp).
///
/// Motor command ids are kMotorIdBase + n (n = 0, 1, ...), a range dl-locomotion's ids (from 1)
/// never reach, so neither client mistakes the other's ddl/motor_status for its own.

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/dl/mast/look_at.hpp"
#include "rover/dl/mast/mast_options.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/msg/mast.hpp"
#include "rover/msg/motor.hpp"
#include "rover/msg/pose.hpp"
#include "rover/msg/sensors.hpp"

namespace rover::dl::mast {

// The messages are core/msg's (rover/msg/mast.hpp, motor.hpp, sensors.hpp, pose.hpp).
using msg::MastCommand;
using msg::MastPointing;
using msg::MastState;
using msg::MastStateName;
using msg::MastStatus;

/// First motor command id of the mast (see the file comment).
inline constexpr std::uint32_t kMotorIdBase = 0x4D000000u;
/// Mask of the two mast motors.
inline constexpr std::uint16_t kMastMotorMask =
    static_cast<std::uint16_t>((1u << hw::kMastPan) | (1u << hw::kMastTilt));

/// What to publish after a call, in order. Motor commands are for kMastMotorMask only: a
/// position goal (goal and max_rate set at hw::kMastPan and hw::kMastTilt) or a group stop;
/// timeout_s 0 (the motor driver derives it from the planned move).
struct MastOutput {
  std::vector<msg::MotorCommand> motor_commands;
  std::vector<MastStatus> statuses;
};

class MastExecutor {
 public:
  /// Errors: rover.Validate() or options.Validate() failures.
  static Result<MastExecutor> Create(const hwconfig::RoverDescription& rover,
                                     const MastOptions& options);

  MastOutput Submit(const MastCommand& command, Time now);
  /// Uses mast_pan, mast_tilt and health of ddl/joint_state.
  void OnJoints(const msg::JointState& joints);
  void OnPose(const msg::PoseSample& pose);
  MastOutput OnMotorStatus(const msg::MotorStatus& report, Time now);
  MastOutput Step(Time now);
  /// Stops a running move (GROUP_STOP of the mast motors, FAULT naming `why`); nothing if idle.
  MastOutput Stop(const std::string& why, Time now);

  /// The latest status (IDLE before the first command).
  const MastStatus& status() const { return status_; }
  bool moving() const { return status_.state == MastState::kMoving; }
  const MastOptions& options() const { return options_; }
  /// True when the latest usable ddl/joint_state is at most joint_stale_s old at `now`.
  bool JointsFresh(Time now) const;

 private:
  MastExecutor(const hwconfig::RoverDescription& rover, const MastOptions& options)
      : rover_(rover), options_(options) {}

  void SetStatus(MastState state, std::string message, Time now, MastOutput* out);
  void Reject(const MastCommand& command, const Status& why, Time now, MastOutput* out);
  void Fault(std::string message, Time now, MastOutput* out);
  msg::MotorCommand MotorCommand(msg::GroupMode mode, Time now);
  Result<PanTilt> GoalOf(const MastCommand& command, Time now) const;
  bool WithinTolerance() const;
  std::uint32_t NextMotorId();

  hwconfig::RoverDescription rover_;
  MastOptions options_;
  MastStatus status_;
  struct Joints {
    Time stamp;
    double pan = 0.0;   // [rad]
    double tilt = 0.0;  // [rad]
  };
  std::optional<Joints> joints_;
  std::optional<msg::PoseSample> pose_;
  std::uint32_t next_motor_id_ = kMotorIdBase;
  std::uint32_t motor_id_ = 0;  // motor command of the running move
  bool motors_done_ = false;
  Time done_at_;  // when the motor driver reported the move DONE
  Time move_start_;
  double move_timeout_s_ = 0.0;
  Time last_status_;
};

}  // namespace rover::dl::mast
