#include "rover/msg/motor.hpp"

namespace rover::msg {

const char* GroupModeName(GroupMode m) {
  switch (m) {
    case GroupMode::kPosition:
      return "POSITION";
    case GroupMode::kVelocity:
      return "VELOCITY";
    case GroupMode::kStop:
      return "STOP";
  }
  return "UNKNOWN";
}

const char* GroupStateName(GroupState s) {
  switch (s) {
    case GroupState::kIdle:
      return "IDLE";
    case GroupState::kRunning:
      return "RUNNING";
    case GroupState::kDone:
      return "DONE";
    case GroupState::kFault:
      return "FAULT";
    case GroupState::kRejected:
      return "REJECTED";
  }
  return "UNKNOWN";
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

bool IsKnownGroupMode(GroupMode m) {
  const auto v = static_cast<std::int32_t>(m);
  return v >= static_cast<std::int32_t>(GroupMode::kPosition) &&
         v <= static_cast<std::int32_t>(GroupMode::kStop);
}

}  // namespace rover::msg
