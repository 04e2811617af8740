#include "rover/msg/arm.hpp"

namespace rover::msg {

const char* ArmModeName(ArmMode m) {
  switch (m) {
    case ArmMode::kJoints:
      return "JOINTS";
    case ArmMode::kPlace:
      return "PLACE";
    case ArmMode::kStow:
      return "STOW";
    case ArmMode::kStop:
      return "STOP";
    case ArmMode::kAutofocus:
      return "AUTOFOCUS";
  }
  return "UNKNOWN";
}

const char* ArmStateName(ArmState s) {
  switch (s) {
    case ArmState::kIdle:
      return "IDLE";
    case ArmState::kMoving:
      return "MOVING";
    case ArmState::kAtGoal:
      return "AT_GOAL";
    case ArmState::kPlaced:
      return "PLACED";
    case ArmState::kStowed:
      return "STOWED";
    case ArmState::kFault:
      return "FAULT";
    case ArmState::kRejected:
      return "REJECTED";
    case ArmState::kFocused:
      return "FOCUSED";
  }
  return "UNKNOWN";
}

bool IsKnownArmMode(ArmMode m) {
  return m == ArmMode::kJoints || m == ArmMode::kPlace || m == ArmMode::kStow || m == ArmMode::kStop ||
         m == ArmMode::kAutofocus;
}

}  // namespace rover::msg
