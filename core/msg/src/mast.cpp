#include "rover/msg/mast.hpp"

namespace rover::msg {

const char* MastPointingName(MastPointing p) {
  switch (p) {
    case MastPointing::kAngles:
      return "ANGLES";
    case MastPointing::kLookAt:
      return "LOOK_AT";
  }
  return "UNKNOWN";
}

const char* MastStateName(MastState s) {
  switch (s) {
    case MastState::kIdle:
      return "IDLE";
    case MastState::kMoving:
      return "MOVING";
    case MastState::kAtGoal:
      return "AT_GOAL";
    case MastState::kFault:
      return "FAULT";
    case MastState::kRejected:
      return "REJECTED";
  }
  return "UNKNOWN";
}

bool IsKnownPointing(MastPointing p) {
  return p == MastPointing::kAngles || p == MastPointing::kLookAt;
}

}  // namespace rover::msg
