#pragma once
/// @file
/// The drive-primitive messages as plain values (idl/rover_dl.idl): dl/drive_command (APL or an
/// operator tool -> DL locomotion, after MER's DRIVE) and dl/drive_status. Enumerator values
/// equal the IDL ordinals; a command read from the wire keeps whatever primitive value it
/// carried, so that locomotion rejects an unknown one (REJECTED_INVALID) naming it.
/// rover/msg/drive_idl.hpp converts them.
///
/// Units: SI and radians; curvature and angles positive counter-clockwise about the rover z axis
/// (up).

#include <cstdint>
#include <string>

#include "rover/base/time.hpp"

namespace rover::msg {

enum class DrivePrimitive : std::int32_t {
  kStop = 0,         ///< stop all motion now
  kArc = 1,          ///< drive `distance` along an arc of `curvature`
  kStraight = 2,     ///< drive `distance` straight
  kTurnInPlace = 3,  ///< turn by `angle` about the rover centre
  kSteer = 4,        ///< point the corner wheels for `curvature`, do not drive
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
  kNone = 0,        ///< still running / never ran
  kNominal = 1,     ///< reached the goal
  kTilt = 2,        ///< tilt over its limit for N cycles
  kSuspension = 3,  ///< rocker or bogie angle out of range
  kMotorStall = 4,
  kMotorCurrent = 5,
  kMotorFault = 6,  ///< any other motor-group fault (overtemp, no telemetry)
  kTimeout = 7,
  kStopCommand = 8,
  kRejectedBusy = 9,      ///< a primitive was already running (MER's BUSY)
  kRejectedInvalid = 10,  ///< NaN, out-of-range or unknown command
  kStaleSensor = 11,      ///< an input needed for the checks stopped updating
};

/// The IDL enumerator names without their prefix ("TURN_IN_PLACE", "STEERING",
/// "REJECTED_BUSY"); "UNKNOWN" for a value no enumerator has.
const char* DrivePrimitiveName(DrivePrimitive p);
const char* DriveStateName(DriveState s);
const char* DriveTerminationName(DriveTermination t);
bool IsKnownPrimitive(DrivePrimitive p);

/// dl/drive_command.
struct DriveCommand {
  Time stamp;
  std::uint32_t command_id = 0;
  DrivePrimitive primitive = DrivePrimitive::kStop;
  double curvature = 0.0;  ///< [1/m] positive turns left
  double distance = 0.0;   ///< [m] along the path; negative drives backwards
  double angle = 0.0;      ///< [rad] turn in place; positive = left (counter-clockwise)
  double speed = 0.0;      ///< [m/s] 0 = default
  double timeout_s = 0.0;  ///< [s] run clock; 0 = derived
};

/// dl/drive_status (latched, keyed by command).
struct DriveStatus {
  Time stamp;
  std::uint32_t command_id = 0;
  DrivePrimitive primitive = DrivePrimitive::kStop;
  DriveState state = DriveState::kIdle;
  DriveTermination termination = DriveTermination::kNone;
  double distance_done = 0.0;   ///< [m] along the path, from wheel odometry
  double heading_change = 0.0;  ///< [rad] from the pose estimate, unwrapped
  std::string message;          ///< <= 127 characters on the wire
};

}  // namespace rover::msg
