#pragma once
// Private to apl/rendezvous: what both executors (rendezvous_executor.cpp, target_approach.cpp)
// build their directed drives and messages from.

#include <Eigen/Core>
#include <cstdint>
#include <cstdio>
#include <string>

#include "rover/apl/rendezvous/rendezvous_executor.hpp"  // the id bases
#include "rover/base/units.hpp"
#include "rover/msg/camera.hpp"
#include "rover/msg/mast.hpp"
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

// The mast LOOK_AT a site point.
inline msg::MastCommand LookAtCommand(const Eigen::Vector3d& site_point, double timeout_s,
                                      Time now, std::uint32_t id) {
  msg::MastCommand c;
  c.stamp = now;
  c.command_id = id;
  c.pointing = msg::MastPointing::kLookAt;
  c.look_at = site_point;
  c.timeout_s = timeout_s;
  return c;
}

// One full-frame NAVCAM pair.
inline msg::StereoRequest NavcamPairRequest(Time now, std::uint32_t id) {
  msg::StereoRequest r;
  r.stamp = now;
  r.request_id = id;
  r.camera = msg::CameraId::kNavcam;
  r.width = 0;  // the full frame
  return r;
}

// A drive as sent: stamped, its id, the default budget when it has none.
inline msg::MobilityCommand StampedDrive(msg::MobilityCommand c, Time now, std::uint32_t id) {
  c.stamp = now;
  c.command_id = id;
  if (c.time_budget_s <= 0.0) c.time_budget_s = kMaxDriveS;
  return c;
}

// STOP of the executor's own drive.
inline msg::MobilityCommand StopDriveCommand(std::uint32_t id) {
  msg::MobilityCommand stop;
  stop.command_id = id;
  stop.mode = msg::MobilityMode::kStop;
  return stop;
}

}  // namespace rover::apl::rendezvous::internal
