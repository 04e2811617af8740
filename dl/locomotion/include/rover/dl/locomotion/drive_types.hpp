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
#include "rover/msg/drive.hpp"
#include "rover/msg/motor.hpp"
#include "rover/msg/pose.hpp"
#include "rover/msg/sensors.hpp"

namespace rover::dl {

using msg::kNumSteered;
using msg::kNumWheels;
inline constexpr int kNumMotors = 12;
/// Wheel index of steer actuator j (LF, LR, RF, RR).
inline constexpr std::array<int, kNumSteered> kSteeredWheel = {0, 2, 3, 5};
/// Motor index of steer actuator j.
inline constexpr int SteerMotor(int j) { return 6 + j; }
/// Bit mask of the six drive motors (0..5) and of the four steer motors (6..9).
inline constexpr std::uint16_t kDriveMotorMask = 0x003F;
inline constexpr std::uint16_t kSteerMotorMask = 0x03C0;
inline constexpr std::uint16_t kMobilityMotorMask = kDriveMotorMask | kSteerMotorMask;

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
};

const char* InvalidReasonName(InvalidReason r);

// The inputs are msg::JointState (ddl/joint_state; usable unless FAILED or STALE),
// msg::AttitudeSample (from dl/pose) and msg::MotorStatus (ddl/motor_status); the outputs
// msg::MotorCommand (ddl/motor_command) and DriveStatus.

/// Drive status (dl/drive_status, rover/msg/drive.hpp) plus the typed INVALID reason.
struct DriveStatus : msg::DriveStatus {
  InvalidReason invalid_reason = InvalidReason::kNone;  ///< not on the wire
};

}  // namespace rover::dl
