#include "rover/msg/drive.hpp"

namespace rover::msg {

const char* DrivePrimitiveName(DrivePrimitive p) {
  switch (p) {
    case DrivePrimitive::kStop:
      return "STOP";
    case DrivePrimitive::kArc:
      return "ARC";
    case DrivePrimitive::kStraight:
      return "STRAIGHT";
    case DrivePrimitive::kTurnInPlace:
      return "TURN_IN_PLACE";
    case DrivePrimitive::kSteer:
      return "STEER";
  }
  return "UNKNOWN";
}

const char* DriveStateName(DriveState s) {
  switch (s) {
    case DriveState::kIdle:
      return "IDLE";
    case DriveState::kSteering:
      return "STEERING";
    case DriveState::kDriving:
      return "DRIVING";
    case DriveState::kTurning:
      return "TURNING";
    case DriveState::kDone:
      return "DONE";
    case DriveState::kFailed:
      return "FAILED";
    case DriveState::kRejected:
      return "REJECTED";
  }
  return "UNKNOWN";
}

const char* DriveTerminationName(DriveTermination t) {
  switch (t) {
    case DriveTermination::kNone:
      return "NONE";
    case DriveTermination::kNominal:
      return "NOMINAL";
    case DriveTermination::kTilt:
      return "TILT";
    case DriveTermination::kSuspension:
      return "SUSPENSION";
    case DriveTermination::kMotorStall:
      return "MOTOR_STALL";
    case DriveTermination::kMotorCurrent:
      return "MOTOR_CURRENT";
    case DriveTermination::kMotorFault:
      return "MOTOR_FAULT";
    case DriveTermination::kTimeout:
      return "TIMEOUT";
    case DriveTermination::kStopCommand:
      return "STOP_COMMAND";
    case DriveTermination::kRejectedBusy:
      return "REJECTED_BUSY";
    case DriveTermination::kRejectedInvalid:
      return "REJECTED_INVALID";
    case DriveTermination::kStaleSensor:
      return "STALE_SENSOR";
  }
  return "UNKNOWN";
}

bool IsKnownPrimitive(DrivePrimitive p) {
  const auto v = static_cast<std::int32_t>(p);
  return v >= static_cast<std::int32_t>(DrivePrimitive::kStop) &&
         v <= static_cast<std::int32_t>(DrivePrimitive::kSteer);
}

}  // namespace rover::msg
