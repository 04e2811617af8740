#include "rover/msg/sequence.hpp"

namespace rover::msg {

const char* SequenceStateName(SequenceState s) {
  switch (s) {
    case SequenceState::kIdle:
      return "IDLE";
    case SequenceState::kRunning:
      return "RUNNING";
    case SequenceState::kDone:
      return "DONE";
    case SequenceState::kFailed:
      return "FAILED";
  }
  return "UNKNOWN";
}

}  // namespace rover::msg
