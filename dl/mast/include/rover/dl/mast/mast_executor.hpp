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

namespace rover::dl::mast {

/// rover_dl.idl MastPointing ordinals.
enum class MastPointing : std::int32_t { kAngles = 0, kLookAt = 1 };
/// rover_dl.idl MastState ordinals.
enum class MastState : std::int32_t { kIdle = 0, kMoving, kAtGoal, kFault, kRejected };
/// rover_ddl.idl GroupMode and GroupState ordinals (the subset the mast uses).
enum class MotorMode : std::int32_t { kPosition = 0, kVelocity = 1, kStop = 2 };
enum class MotorGroupState : std::int32_t { kIdle = 0, kRunning, kDone, kFault, kRejected };

/// "IDLE", "MOVING", "AT_GOAL", "FAULT", "REJECTED"; "?" otherwise.
const char* MastStateName(MastState s);

/// First motor command id of the mast (see the file comment).
inline constexpr std::uint32_t kMotorIdBase = 0x4D000000u;
/// Mask of the two mast motors.
inline constexpr std::uint16_t kMastMotorMask =
    static_cast<std::uint16_t>((1u << hw::kMastPan) | (1u << hw::kMastTilt));

/// dl/mast_command.
struct MastCommand {
  std::uint32_t command_id = 0;
  MastPointing pointing = MastPointing::kAngles;
  double pan = 0.0;                                   ///< [rad] kAngles
  double tilt = 0.0;                                  ///< [rad] kAngles
  Eigen::Vector3d look_at = Eigen::Vector3d::Zero();  ///< [m] site frame, kLookAt
  double timeout_s = 0.0;                             ///< [s] 0 = options.timeout_s
};

/// The mast angles of one ddl/joint_state sample.
struct MastJoints {
  Time stamp;
  double pan = 0.0;   ///< [rad]
  double tilt = 0.0;  ///< [rad]
  bool healthy = true;
};

/// One dl/pose sample: the rover in the site frame.
struct RoverPose {
  Time stamp;
  Eigen::Isometry3d site_from_rover = Eigen::Isometry3d::Identity();
};

/// ddl/motor_status, as far as the mast needs it.
struct MotorReport {
  std::uint32_t command_id = 0;
  MotorGroupState state = MotorGroupState::kIdle;
  int fault_motor = -1;
  std::string fault;    ///< the fault's name (motor driver's enum), "" if none
  std::string message;
};

/// ddl/motor_command for the mast motors.
struct MastMotorCommand {
  Time stamp;
  std::uint32_t command_id = 0;
  MotorMode mode = MotorMode::kStop;
  std::uint16_t motor_mask = kMastMotorMask;
  double pan_goal = 0.0;   ///< [rad] goal[hw::kMastPan] (kPosition)
  double tilt_goal = 0.0;  ///< [rad] goal[hw::kMastTilt]
  double max_rate = 0.0;   ///< [rad/s] for both motors
};

/// dl/mast_status.
struct MastStatus {
  Time stamp;
  std::uint32_t command_id = 0;
  MastState state = MastState::kIdle;
  double pan = 0.0;        ///< [rad] measured
  double tilt = 0.0;       ///< [rad] measured
  double pan_goal = 0.0;   ///< [rad]
  double tilt_goal = 0.0;  ///< [rad]
  std::string message;
};

/// What to publish after a call, in order.
struct MastOutput {
  std::vector<MastMotorCommand> motor_commands;
  std::vector<MastStatus> statuses;
};

class MastExecutor {
 public:
  /// Errors: rover.Validate() or options.Validate() failures.
  static Result<MastExecutor> Create(const hwconfig::RoverDescription& rover,
                                     const MastOptions& options);

  MastOutput Submit(const MastCommand& command, Time now);
  void OnJoints(const MastJoints& joints);
  void OnPose(const RoverPose& pose);
  MastOutput OnMotorStatus(const MotorReport& report, Time now);
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
  Result<PanTilt> GoalOf(const MastCommand& command, Time now) const;
  bool WithinTolerance() const;
  std::uint32_t NextMotorId();

  hwconfig::RoverDescription rover_;
  MastOptions options_;
  MastStatus status_;
  std::optional<MastJoints> joints_;
  std::optional<RoverPose> pose_;
  std::uint32_t next_motor_id_ = kMotorIdBase;
  std::uint32_t motor_id_ = 0;  // motor command of the running move
  bool motors_done_ = false;
  Time done_at_;  // when the motor driver reported the move DONE
  Time move_start_;
  double move_timeout_s_ = 0.0;
  Time last_status_;
};

}  // namespace rover::dl::mast
