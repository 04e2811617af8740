#pragma once
/// @file
/// The mast messages as plain values (idl/rover_dl.idl): dl/mast_command (APL -> dl-mast) and
/// dl/mast_status (dl-mast -> APL). rover/msg/mast_idl.hpp converts them.
///
/// Angles in radians: pan positive left (counter-clockwise seen from above), tilt positive up,
/// both mast joint angles as ddl/joint_state reports them. `look_at` is in the site frame
/// (x north, y west, z up), metres. Enumerator values equal the IDL ordinals; a command read from
/// the wire keeps whatever pointing value it carried so that dl-mast rejects an unknown one
/// naming it.

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "rover/base/time.hpp"

namespace rover::msg {

enum class MastPointing : std::int32_t {
  kAngles = 0,  ///< go to pan, tilt
  kLookAt = 1,  ///< point the NAVCAM boresight at look_at (needs dl/pose)
};

enum class MastState : std::int32_t { kIdle = 0, kMoving, kAtGoal, kFault, kRejected };

/// "ANGLES", "LOOK_AT"; "UNKNOWN" for a value no enumerator has.
const char* MastPointingName(MastPointing p);
/// "IDLE", "MOVING", "AT_GOAL", "FAULT", "REJECTED"; "UNKNOWN" otherwise.
const char* MastStateName(MastState s);
bool IsKnownPointing(MastPointing p);

/// dl/mast_command.
struct MastCommand {
  Time stamp;
  std::uint32_t command_id = 0;
  MastPointing pointing = MastPointing::kAngles;
  double pan = 0.0;                                   ///< [rad] kAngles
  double tilt = 0.0;                                  ///< [rad] kAngles
  Eigen::Vector3d look_at = Eigen::Vector3d::Zero();  ///< [m] site frame, kLookAt
  double timeout_s = 0.0;                             ///< [s] run clock; 0 = the service's
};

/// dl/mast_status: the latched status of the latest command.
struct MastStatus {
  Time stamp;
  std::uint32_t command_id = 0;
  MastState state = MastState::kIdle;
  double pan = 0.0;        ///< [rad] measured
  double tilt = 0.0;       ///< [rad] measured
  double pan_goal = 0.0;   ///< [rad] the goal being driven to
  double tilt_goal = 0.0;  ///< [rad]
  std::string message;     ///< <= 127 characters on the wire
};

}  // namespace rover::msg
