#pragma once
/// @file
/// Plain C++ mirrors of the drive-related IDL types (idl/rover_ddl.idl, idl/rover_dl.idl) used by
/// the locomotion library. Enumerator values equal the IDL ordinals, so a service converts with
/// static_cast in both directions; out-of-range values coming from the wire are detected by the
/// library (IsKnown*), never assumed away.
///
/// Index conventions (fixed, as in rover_hw.idl / rover_ddl.idl):
///   wheels      0 LF, 1 LM, 2 LR, 3 RF, 4 RM, 5 RR           (drive motor i = wheel i)
///   steer       0 LF, 1 LR, 2 RF, 3 RR                       (steer motor 6 + j)
///   suspension  0 left, 1 right                              (rocker and bogie)
/// Units: SI and radians; angles positive counter-clockwise about the rover z axis (up) for
/// steering and heading, positive "front up" for rocker and bogie.

#include <array>
#include <cstdint>
#include <string>

#include "rover/base/time.hpp"
#include "rover/hwconfig/rover_description.hpp"

namespace rover::dl {

// Counts, the steered wheels (kSteeredWheel, SteerMotor) and the motor masks are the rover
// description's (core/hwconfig rover_description.hpp).
using hw::kNumMotors;
using hwconfig::kDriveMotorMask;
using hwconfig::kMobilityMotorMask;
using hwconfig::kNumSteered;
using hwconfig::kNumWheels;
using hwconfig::kSteeredWheel;
using hwconfig::kSteerMotorMask;
using hwconfig::SteerMotor;

// ---- rover::dl (rover_dl.idl) -----------------------------------------------------------------

enum class DrivePrimitive : std::int32_t {
  kStop = 0,
  kArc = 1,
  kStraight = 2,
  kTurnInPlace = 3,
  kSteer = 4,
};

enum class DriveState : std::int32_t {
  kIdle = 0,
  kSteering = 1,
  kDriving = 2,
  kTurning = 3,
  kDone = 4,
  kFailed = 5,
  kRejected = 6,
};

enum class DriveTermination : std::int32_t {
  kNone = 0,
  kNominal = 1,
  kTilt = 2,
  kSuspension = 3,
  kMotorStall = 4,
  kMotorCurrent = 5,
  kMotorFault = 6,
  kTimeout = 7,
  kStopCommand = 8,
  kRejectedBusy = 9,
  kRejectedInvalid = 10,
  kStaleSensor = 11,
};

/// Why a command was rejected INVALID (not on the wire; the message carries the details).
enum class InvalidReason : std::int32_t {
  kNone = 0,
  kUnknownPrimitive,
  kNonFinite,            ///< a field the primitive uses is NaN or infinite
  kCurvatureOutOfRange,  ///< |curvature| > 1 / min_turn_radius
  kDistanceOutOfRange,   ///< |distance| > max_distance
  kAngleOutOfRange,      ///< |angle| > max_turn_angle
  kSpeedOutOfRange,      ///< speed < 0 or > max_speed
  kTimeoutOutOfRange,    ///< timeout_s < 0 or > max_timeout_s
};

// ---- rover::ddl (rover_ddl.idl) ---------------------------------------------------------------

enum class GroupMode : std::int32_t { kPosition = 0, kVelocity = 1, kStop = 2 };
enum class GroupState : std::int32_t {
  kIdle = 0,
  kRunning = 1,
  kDone = 2,
  kFault = 3,
  kRejected = 4
};
enum class MotorFault : std::int32_t {
  kNone = 0,
  kStall,
  kOverCurrent,
  kOverTemp,
  kTimeout,
  kNoTelemetry,
  kBadCommand,
  kStopped,
};

const char* DrivePrimitiveName(DrivePrimitive p);
const char* DriveStateName(DriveState s);
const char* DriveTerminationName(DriveTermination t);
const char* InvalidReasonName(InvalidReason r);
const char* MotorFaultName(MotorFault f);
bool IsKnownPrimitive(DrivePrimitive p);

// ---- inputs -----------------------------------------------------------------------------------

/// One encoder/potentiometer sample (ddl/joint_state). `healthy` is false when the driver marked
/// the sample FAILED or STALE; such samples do not count as fresh.
struct JointSample {
  Time stamp;
  std::array<double, kNumWheels> wheel_angle{};   ///< [rad] cumulative drive rotation
  std::array<double, kNumWheels> wheel_rate{};    ///< [rad/s]
  std::array<double, kNumSteered> steer_angle{};  ///< [rad] positive = wheel front to the left
  std::array<double, 2> rocker_angle{};           ///< [rad] left, right; positive front up
  std::array<double, 2> bogie_angle{};            ///< [rad] left, right, relative to the rocker
  bool healthy = true;

  /// True when every angle and rate is finite.
  bool AllFinite() const;
};

/// Rover attitude from the pose estimate (dl/pose) or the IMU: ZYX roll, pitch, yaw of the rover
/// frame in the site frame (see rover/geometry/transforms.hpp).
struct AttitudeSample {
  Time stamp;
  double roll = 0.0;   ///< [rad]
  double pitch = 0.0;  ///< [rad]
  double yaw = 0.0;    ///< [rad] heading, counter-clockwise from site x (north)
  bool healthy = true;
};

/// The motor driver's report on a motor group (ddl/motor_status, without the per-motor arrays).
struct MotorGroupStatus {
  Time stamp;
  std::uint32_t command_id = 0;
  GroupState state = GroupState::kIdle;
  MotorFault fault = MotorFault::kNone;
  int fault_motor = -1;
  std::string message;
};

/// A drive primitive request (dl/drive_command).
struct DriveCommand {
  Time stamp;
  std::uint32_t command_id = 0;
  DrivePrimitive primitive = DrivePrimitive::kStop;
  double curvature = 0.0;  ///< [1/m] positive turns left
  double distance = 0.0;   ///< [m] along the path; negative drives backwards
  double angle = 0.0;      ///< [rad] turn in place; positive = left (counter-clockwise)
  double speed = 0.0;      ///< [m/s] 0 = default
  double timeout_s = 0.0;  ///< [s] 0 = derived
};

// ---- outputs ----------------------------------------------------------------------------------

/// One motor-group command (ddl/motor_command).
struct MotorGroupCommand {
  Time stamp;
  std::uint32_t command_id = 0;
  std::uint16_t motor_mask = 0;
  GroupMode mode = GroupMode::kStop;
  std::array<double, kNumMotors> goal{};      ///< [rad] or [rad/s]
  std::array<double, kNumMotors> max_rate{};  ///< [rad/s] for position goals; 0 = default
  double timeout_s = 0.0;
};

/// Drive status (dl/drive_status) plus the typed INVALID reason.
struct DriveStatus {
  Time stamp;
  std::uint32_t command_id = 0;
  DrivePrimitive primitive = DrivePrimitive::kStop;
  DriveState state = DriveState::kIdle;
  DriveTermination termination = DriveTermination::kNone;
  InvalidReason invalid_reason = InvalidReason::kNone;
  double distance_done = 0.0;   ///< [m] along the path, from the wheel rotations
  double heading_change = 0.0;  ///< [rad] from the attitude input, unwrapped
  std::string message;
};

}  // namespace rover::dl
