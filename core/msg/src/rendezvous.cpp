#include "rover/msg/rendezvous.hpp"

#include <array>

namespace rover::msg {

const char* RendezvousTargetName(RendezvousTarget t) {
  switch (t) {
    case RendezvousTarget::kLander:
      return "LANDER";
    case RendezvousTarget::kScience:
      return "SCIENCE";
    case RendezvousTarget::kStop:
      return "STOP";
  }
  return "UNKNOWN";
}

const char* RendezvousPhaseName(RendezvousPhase p) {
  static constexpr std::array<const char*, kRendezvousPhaseCount> kNames = {
      "IDLE", "LONG_RANGE", "MID_RANGE", "CLOSE_RANGE", "AT_RAMP_BASE", "CLIMB", "DONE", "FAILED",
      "APPROACH_TARGET", "AT_TARGET", "PLACING", "PLACED", "FOCUSING", "FOCUSED"};
  const auto i = static_cast<std::size_t>(p);
  return i < kNames.size() ? kNames[i] : "UNKNOWN";
}

const char* RendezvousFaultName(RendezvousFault f) {
  static constexpr std::array<const char*, kRendezvousFaultCount> kNames = {
      "NONE",       "BAD_COMMAND", "BUSY",   "NOT_FOUND", "TOO_FEW_STRIPES", "STALE_POSE",
      "MOBILITY",   "MAST",        "CAMERA", "STOPPED",   "TIMEOUT",         "PLACEMENT",
      "TARGET_LOST", "ARM"};
  const auto i = static_cast<std::size_t>(f);
  return i < kNames.size() ? kNames[i] : "UNKNOWN";
}

}  // namespace rover::msg
