#pragma once
/// @file
/// The rendezvous messages as plain values (idl/rover_apl.idl): apl/rendezvous_command
/// (sequencer, operator or runner -> apl-rendezvous) and apl/rendezvous_status (latched).
/// rover/msg/rendezvous_idl.hpp converts them. Enumerator values equal the IDL ordinals; a
/// command read from the wire keeps whatever target value it carried so that apl-rendezvous
/// rejects an unknown one naming it.
///
/// Site frame (x north, y west, z up), metres; bearings in the rover frame, radians, + left.

#include <Eigen/Core>
#include <cstdint>
#include <string>

#include "rover/base/time.hpp"

namespace rover::msg {

enum class RendezvousTarget : std::int32_t { kLander = 0, kScience, kStop };
enum class RendezvousPhase : std::int32_t {
  kIdle = 0,
  kLongRange,
  kMidRange,
  kCloseRange,
  kAtRampBase,
  kClimb,
  kDone,
  kFailed,
  kApproachTarget,
  kAtTarget,
  kPlacing,
  kPlaced,
  kFocusing,  ///< kScience: dl-arm's auto-focus sweep over the target
  kFocused    ///< kScience: the microscopic imager at best focus over it
};
enum class RendezvousFault : std::int32_t {
  kNone = 0,
  kBadCommand,
  kBusy,
  kNotFound,
  kTooFewStripes,
  kStalePose,
  kMobility,
  kMast,
  kCamera,
  kStopped,
  kTimeout,
  kPlacement,
  kTargetLost,
  kArm
};
inline constexpr int kRendezvousPhaseCount = 14;
inline constexpr int kRendezvousFaultCount = 14;

/// "LANDER", "SCIENCE", "STOP"; "UNKNOWN" otherwise.
const char* RendezvousTargetName(RendezvousTarget t);
/// "IDLE", "LONG_RANGE", "MID_RANGE", "CLOSE_RANGE", "AT_RAMP_BASE", "CLIMB", "DONE", "FAILED",
/// "APPROACH_TARGET", "AT_TARGET", "PLACING", "PLACED"; "UNKNOWN" otherwise.
const char* RendezvousPhaseName(RendezvousPhase p);
/// "NONE", "BAD_COMMAND", "BUSY", "NOT_FOUND", "TOO_FEW_STRIPES", "STALE_POSE", "MOBILITY",
/// "MAST", "CAMERA", "STOPPED", "TIMEOUT", "PLACEMENT", "TARGET_LOST", "ARM"; "UNKNOWN" otherwise.
const char* RendezvousFaultName(RendezvousFault f);

/// apl/rendezvous_command.
struct RendezvousCommand {
  Time stamp;
  std::uint32_t command_id = 0;
  RendezvousTarget target = RendezvousTarget::kLander;
  Eigen::Vector3d target_estimate = Eigen::Vector3d::Zero();  ///< [m] site frame, deck centre
  double standoff = 0.0;       ///< [m] rover origin before the ramp base; 0 = default
  int ramp = -1;               ///< 0 or 1; -1 = the first one seen (the one facing the rover)
  bool climb = true;           ///< climb onto the deck after the placement
  double time_budget_s = 0.0;  ///< [s] 0 = the service's default
  /// kScience: the target is at left-image pixel (pixel_x, pixel_y) of the NAVCAM pair with
  /// this ddl/stereo_frame request_id.
  std::uint32_t image_id = 0;
  double pixel_x = 0.0;  ///< [px]
  double pixel_y = 0.0;  ///< [px]
  /// kScience: at the standoff, put the arm's instrument on the target (PLACING, PLACED).
  bool place_instrument = false;
  /// kScience: then focus the microscopic imager on the target (dl-arm AUTOFOCUS; after a
  /// placement, about the height the contact measured) (FOCUSING, FOCUSED).
  bool autofocus = false;
};

/// apl/rendezvous_status.
struct RendezvousStatus {
  Time stamp;
  std::uint32_t command_id = 0;
  RendezvousPhase phase = RendezvousPhase::kIdle;
  RendezvousFault fault = RendezvousFault::kNone;
  Eigen::Vector3d target_position = Eigen::Vector3d::Zero();  ///< [m] site frame
  double target_sigma = 0.0;   ///< [m]
  double range = 0.0;          ///< [m] horizontal, rover origin to the deck centre
  double range_sigma = 0.0;    ///< [m]
  double bearing = 0.0;        ///< [rad] rover frame, + left
  double bearing_sigma = 0.0;  ///< [rad]
  int ramp = -1;
  int images = 0;
  std::string features;  ///< <= 63 characters on the wire
  std::string message;   ///< <= 127 characters on the wire
  /// kScience: the target in the rover frame at the last fix [m] (the arm's placement point).
  Eigen::Vector3d target_in_rover = Eigen::Vector3d::Zero();
};

}  // namespace rover::msg
