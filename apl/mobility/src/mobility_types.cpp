#include "rover/apl/mobility/mobility_types.hpp"

#include <array>

namespace rover::apl::mobility {
namespace {

constexpr std::array<std::string_view, kFaultCount> kFaultNames = {
    "NONE",    "ARB",           "ACM",         "POT",        "TOD",
    "STOPPED", "WAYPT_TIMEOUT", "NOPATH",      "NOPROGRESS", "BUSY",
    "VISODOM", "KEEPOUT",       "BAD_COMMAND", "IMG",        "SAPP",
    "MOT",     "DRIVE_TIMEOUT", "TILT",        "SUSPENSION", "NORTH"};

constexpr std::array<std::string_view, kModeCount> kModeNames = {
    "DIRECTED",    "VISODOM",         "GO_TO_WAYPOINT", "VISODOM_GO_TO_WAYPOINT",
    "GUARDED",     "GUARDED_VISODOM", "AUTONAV",        "AUTONAV_VISODOM",
    "GUARDED_ARC", "LONG_TRAVERSE",   "STOP",           "CLEAR_FAULT"};

}  // namespace

FaultClass FaultClassOf(Fault f) {
  const int v = static_cast<int>(f);
  if (v <= 0 || v >= kFaultCount) return FaultClass::kNone;
  return v >= static_cast<int>(Fault::kImg) ? FaultClass::kMotionError : FaultClass::kGoalError;
}

std::string_view FaultName(Fault f) {
  const int v = static_cast<int>(f);
  return v >= 0 && v < kFaultCount ? kFaultNames[static_cast<std::size_t>(v)] : "UNKNOWN";
}

std::string ModeName(Mode m) {
  const int v = static_cast<int>(m);
  if (v >= 0 && v < kModeCount) return std::string(kModeNames[static_cast<std::size_t>(v)]);
  return "mode " + std::to_string(v);
}

bool ModeHasGoal(Mode m) {
  switch (m) {
    case Mode::kGoToWaypoint:
    case Mode::kVisOdomGoToWaypoint:
    case Mode::kAutoNav:
    case Mode::kAutoNavVisOdom:
    case Mode::kLongTraverse:
      return true;
    default:
      return false;
  }
}

bool ModeHasPrimitives(Mode m) {
  switch (m) {
    case Mode::kDirected:
    case Mode::kVisOdom:
    case Mode::kGuarded:
    case Mode::kGuardedVisOdom:
    case Mode::kGuardedArc:
      return true;
    default:
      return false;
  }
}

bool ModeUsesVisOdom(Mode m) {
  return m == Mode::kVisOdom || m == Mode::kVisOdomGoToWaypoint || m == Mode::kGuardedVisOdom ||
         m == Mode::kAutoNavVisOdom;
}

std::string_view CameraName(Camera c) {
  switch (c) {
    case Camera::kNavcam:
      return "navcam";
    case Camera::kFrontHazcam:
      return "front_hazcam";
    case Camera::kRearHazcam:
      return "rear_hazcam";
  }
  return "unknown_camera";
}

}  // namespace rover::apl::mobility
