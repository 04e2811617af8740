#include "rover/dl/locomotion/drive_types.hpp"

#include <cmath>

namespace rover::dl {

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

const char* InvalidReasonName(InvalidReason r) {
  switch (r) {
    case InvalidReason::kNone:
      return "none";
    case InvalidReason::kUnknownPrimitive:
      return "unknown_primitive";
    case InvalidReason::kNonFinite:
      return "non_finite";
    case InvalidReason::kCurvatureOutOfRange:
      return "curvature_out_of_range";
    case InvalidReason::kDistanceOutOfRange:
      return "distance_out_of_range";
    case InvalidReason::kAngleOutOfRange:
      return "angle_out_of_range";
    case InvalidReason::kSpeedOutOfRange:
      return "speed_out_of_range";
    case InvalidReason::kTimeoutOutOfRange:
      return "timeout_out_of_range";
  }
  return "unknown";
}

const char* MotorFaultName(MotorFault f) {
  switch (f) {
    case MotorFault::kNone:
      return "NONE";
    case MotorFault::kStall:
      return "STALL";
    case MotorFault::kOverCurrent:
      return "OVERCURRENT";
    case MotorFault::kOverTemp:
      return "OVERTEMP";
    case MotorFault::kTimeout:
      return "TIMEOUT";
    case MotorFault::kNoTelemetry:
      return "NO_TELEMETRY";
    case MotorFault::kBadCommand:
      return "BAD_COMMAND";
    case MotorFault::kStopped:
      return "STOPPED";
  }
  return "UNKNOWN";
}

bool IsKnownPrimitive(DrivePrimitive p) {
  const auto v = static_cast<std::int32_t>(p);
  return v >= static_cast<std::int32_t>(DrivePrimitive::kStop) &&
         v <= static_cast<std::int32_t>(DrivePrimitive::kSteer);
}

bool JointSample::AllFinite() const {
  auto finite = [](const auto& a) {
    for (double v : a) {
      if (!std::isfinite(v)) return false;
    }
    return true;
  };
  return finite(wheel_angle) && finite(wheel_rate) && finite(steer_angle) && finite(rocker_angle) &&
         finite(bogie_angle);
}

}  // namespace rover::dl
