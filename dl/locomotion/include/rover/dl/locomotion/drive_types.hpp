#pragma once
/// @file
/// The drive-related types of the locomotion library. The messages themselves (dl/drive_command,
/// dl/drive_status, ddl/motor_command, ddl/motor_status, ddl/joint_state, the dl/pose attitude)
/// are core/msg's (rover/msg/*.hpp); out-of-range values coming from the wire are detected by
/// the library (IsKnown*), never assumed away.
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
#include "rover/msg/drive.hpp"
#include "rover/msg/motor.hpp"
#include "rover/msg/pose.hpp"
#include "rover/msg/sensors.hpp"

namespace rover::dl::locomotion {

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

// ---- messages (rover/msg/drive.hpp, motor.hpp, sensors.hpp, pose.hpp) ----------------------

using msg::DriveCommand;
using msg::DrivePrimitive;
using msg::DrivePrimitiveName;
using msg::DriveState;
using msg::DriveStateName;
using msg::DriveTermination;
using msg::DriveTerminationName;
using msg::GroupMode;
using msg::GroupState;
using msg::IsKnownPrimitive;
using msg::MotorFault;
using msg::MotorFaultName;

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
  kArmNotStowed,         ///< ddl/joint_state puts an arm joint off its stowed angle
};

const char* InvalidReasonName(InvalidReason r);

// The inputs are msg::JointState (ddl/joint_state; usable unless FAILED or STALE),
// msg::AttitudeSample (from dl/pose) and msg::MotorStatus (ddl/motor_status); the outputs
// msg::MotorCommand (ddl/motor_command) and DriveStatus.

/// Drive status (dl/drive_status, rover/msg/drive.hpp) plus the typed INVALID reason.
struct DriveStatus : msg::DriveStatus {
  InvalidReason invalid_reason = InvalidReason::kNone;  ///< not on the wire
};

}  // namespace rover::dl::locomotion
