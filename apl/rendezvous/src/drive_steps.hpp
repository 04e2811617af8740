#pragma once
// Private to apl/rendezvous: what both executors (rendezvous_executor.cpp, target_approach.cpp)
// build their directed drives and messages from.

#include <cstdio>
#include <string>

#include "rover/base/units.hpp"
#include "rover/msg/mobility.hpp"

namespace rover::apl::rendezvous::internal {

inline constexpr double kMaxDriveS = 600.0;  // [s] budget of one drive sent to apl-mobility
inline constexpr int kMaxMobilityRetries = 3;  // legs that ended in a goal error, looked again

inline msg::MobilityPrimitive Turn(double angle) {
  msg::MobilityPrimitive p;
  p.kind = msg::DrivePrimitive::kTurnInPlace;
  p.angle = angle;
  return p;
}

inline msg::MobilityPrimitive Straight(double distance) {
  msg::MobilityPrimitive p;
  p.kind = msg::DrivePrimitive::kStraight;
  p.distance = distance;
  return p;
}

// "+1.2 cm"
inline std::string Cm(double m) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%+.1f cm", 100.0 * m);
  return buf;
}

// "+0.25 deg"
inline std::string Deg(double rad) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%+.2f deg", rad / kDegree);
  return buf;
}

}  // namespace rover::apl::rendezvous::internal
