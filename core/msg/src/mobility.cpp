#include "rover/msg/mobility.hpp"

#include <array>

namespace rover::msg {
namespace {

constexpr std::array<std::string_view, kMobilityFaultCount> kFaultNames = {
    "NONE",    "ARB",           "ACM",         "POT",        "TOD",
    "STOPPED", "WAYPT_TIMEOUT", "NOPATH",      "NOPROGRESS", "BUSY",
    "VISODOM", "KEEPOUT",       "BAD_COMMAND", "IMG",        "SAPP",
    "MOT",     "DRIVE_TIMEOUT", "TILT",        "SUSPENSION", "NORTH",
    "RESTART"};

constexpr std::array<std::string_view, kMobilityModeCount> kModeNames = {
    "DIRECTED",    "VISODOM",         "GO_TO_WAYPOINT", "VISODOM_GO_TO_WAYPOINT",
    "GUARDED",     "GUARDED_VISODOM", "AUTONAV",        "AUTONAV_VISODOM",
    "GUARDED_ARC", "LONG_TRAVERSE",   "STOP",           "CLEAR_FAULT"};

constexpr std::array<const char*, kMobilityStateCount> kStateNames = {
    "IDLE", "RUNNING", "SUCCEEDED", "FAILED", "REJECTED"};

constexpr std::array<const char*, kFaultClassCount> kClassNames = {"NONE", "GOAL_ERROR",
                                                                   "MOTION_ERROR"};

}  // namespace

FaultClass FaultClassOf(MobilityFault f) {
  const int v = static_cast<int>(f);
  if (v <= 0 || v >= kMobilityFaultCount) return FaultClass::kNone;
  if (f == MobilityFault::kRestart) return FaultClass::kGoalError;
  return v >= static_cast<int>(MobilityFault::kImg) ? FaultClass::kMotionError
                                                    : FaultClass::kGoalError;
}

std::string_view MobilityFaultName(MobilityFault f) {
  const int v = static_cast<int>(f);
  return v >= 0 && v < kMobilityFaultCount ? kFaultNames[static_cast<std::size_t>(v)] : "UNKNOWN";
}

std::string MobilityModeName(MobilityMode m) {
  const int v = static_cast<int>(m);
  if (v >= 0 && v < kMobilityModeCount) return std::string(kModeNames[static_cast<std::size_t>(v)]);
  return "mode " + std::to_string(v);
}

const char* MobilityStateName(MobilityState s) {
  const int v = static_cast<int>(s);
  return v >= 0 && v < kMobilityStateCount ? kStateNames[static_cast<std::size_t>(v)] : "UNKNOWN";
}

const char* FaultClassName(FaultClass c) {
  const int v = static_cast<int>(c);
  return v >= 0 && v < kFaultClassCount ? kClassNames[static_cast<std::size_t>(v)] : "UNKNOWN";
}

}  // namespace rover::msg
