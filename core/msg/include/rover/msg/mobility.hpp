#pragma once
/// @file
/// The mobility manager's messages as plain values (idl/rover_apl.idl): apl/mobility_command
/// (sequencer, operator or runner -> apl-mobility) and apl/mobility_status, with MER's typed
/// faults and their classes (seed 000 Table 1). rover/msg/mobility_idl.hpp converts them.
///
/// Frames: site frame (x north, y west, z up) for the goal and keep-out zones; primitive
/// curvature is signed in the rover frame (positive = turn left), turn angles positive =
/// counter-clockwise seen from above. Metres, radians, run-clock time.
///
/// Enumerator values equal the IDL ordinals. A command read from the wire keeps whatever mode,
/// think mode or primitive value it carried, so that the mobility manager rejects an unknown one
/// (BAD_COMMAND) naming the field.

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rover/base/time.hpp"
#include "rover/msg/drive.hpp"

namespace rover::msg {

/// Driving modes (seed 000 Table 2, seed 003's guarded arc) and the two control commands.
enum class MobilityMode : std::int32_t {
  kDirected = 0,         ///< primitives, blind
  kVisOdom,              ///< primitives, visual odometry between steps
  kGoToWaypoint,         ///< blind drive to the goal, pose-corrected arcs
  kVisOdomGoToWaypoint,  ///< go-to-waypoint with visual odometry between steps
  kGuarded,              ///< primitives, each vetoed if terrain assessment forbids it
  kGuardedVisOdom,       ///< guarded, visual odometry between steps
  kAutoNav,              ///< drive to the goal with stereo hazard avoidance
  kAutoNavVisOdom,       ///< autonav, visual odometry between steps
  kGuardedArc,           ///< the first primitive blind (a turn), the rest only if seen safe
  kLongTraverse,         ///< global plan, then autonav legs
  kStop,                 ///< stop what runs: goal error STOPPED for it
  kClearFault,           ///< clear a latched motion error
};
inline constexpr int kMobilityModeCount = 12;

enum class ThinkMode : std::int32_t { kDefault = 0, kStopAndGo, kDriveWhileThinking };
inline constexpr int kThinkModeCount = 3;

enum class MobilityState : std::int32_t { kIdle = 0, kRunning, kSucceeded, kFailed, kRejected };
inline constexpr int kMobilityStateCount = 5;

enum class FaultClass : std::int32_t { kNone = 0, kGoalError, kMotionError };
inline constexpr int kFaultClassCount = 3;

/// Typed faults (IDL MobilityFault); FaultClassOf gives each one's class.
enum class MobilityFault : std::int32_t {
  kNone = 0,
  // goal errors
  kArb,
  kAcm,
  kPot,
  kTod,
  kStopped,
  kWaypointTimeout,
  kNoPath,
  kNoProgress,
  kBusy,
  kVisOdom,
  kKeepOut,
  kBadCommand,
  // motion errors
  kImg,
  kSapp,
  kMot,
  kDriveTimeout,
  kTilt,
  kSuspension,
  kNorth,
  // goal error, numbered after the motion errors (the wire keeps earlier values)
  kRestart,  ///< apl-mobility restarted while the command ran: the command is abandoned
};
inline constexpr int kMobilityFaultCount = 21;

/// MER's class of each fault: kGoalError for ARB .. BAD_COMMAND and RESTART, kMotionError for
/// IMG .. NORTH, kNone for NONE and values no enumerator has.
FaultClass FaultClassOf(MobilityFault f);
/// "ARB", "WAYPT_TIMEOUT", ... (the IDL names without MOBFAULT_); "UNKNOWN" otherwise.
std::string_view MobilityFaultName(MobilityFault f);
/// "AUTONAV", "GUARDED_ARC", ... (without MOBILITY_); "mode 17" for a value outside the
/// enumeration.
std::string MobilityModeName(MobilityMode m);
/// "IDLE", "RUNNING", "SUCCEEDED", "FAILED", "REJECTED"; "UNKNOWN" otherwise.
const char* MobilityStateName(MobilityState s);
/// "NONE", "GOAL_ERROR", "MOTION_ERROR"; "UNKNOWN" otherwise.
const char* FaultClassName(FaultClass c);

/// One primitive of a directed, guarded or guarded-arc command (IDL MobilityPrimitive; `kind` is
/// its `primitive` field).
struct MobilityPrimitive {
  DrivePrimitive kind = DrivePrimitive::kStraight;
  double curvature = 0.0;  ///< [1/m] arcs, positive turns left
  double distance = 0.0;   ///< [m] arcs and straights; negative drives backwards
  double angle = 0.0;      ///< [rad] turns in place, positive = left
};

/// A simple polygon in the site frame (3..16 vertices on the wire, either winding).
struct KeepOutZone {
  std::string name;                       ///< <= 31 characters on the wire
  std::vector<Eigen::Vector2d> vertices;  ///< [m] site x, y
};

/// apl/mobility_command. Limits left at 0 take the service's parameter values.
struct MobilityCommand {
  Time stamp;
  std::uint32_t command_id = 0;
  MobilityMode mode = MobilityMode::kDirected;
  Eigen::Vector3d goal = Eigen::Vector3d::Zero();  ///< [m] site frame (z unused)
  double tolerance = 0.0;                          ///< [m] goal radius, >= 0
  double time_budget_s = 0.0;                      ///< [s] run clock; 0 = none
  std::vector<MobilityPrimitive> primitives;       ///< <= 32 on the wire
  std::vector<KeepOutZone> keep_out;               ///< <= 8 on the wire
  ThinkMode think = ThinkMode::kDefault;
  double max_tilt = 0.0;            ///< [rad]; 0 = parameter
  double min_northerly_tilt = 0.0;  ///< [rad] NORTH below it; 0 = no check
  double lmst_end_h = 0.0;          ///< [h] Mars local solar time limit; 0 = none
  int max_steps = 0;                ///< autonav steps (0..65535 on the wire); 0 = parameter
};

/// apl/mobility_status (latched).
struct MobilityStatus {
  Time stamp;
  std::uint32_t command_id = 0;
  MobilityMode mode = MobilityMode::kDirected;
  MobilityState state = MobilityState::kIdle;
  FaultClass fault_class = FaultClass::kNone;
  MobilityFault fault = MobilityFault::kNone;
  std::string message;             ///< <= 127 characters on the wire
  double distance_to_goal = -1.0;  ///< [m] horizontal; -1 for modes without a goal
  double distance_driven = 0.0;    ///< [m] path length driven under this command
  std::uint32_t steps = 0;         ///< drive steps taken
  std::uint32_t images = 0;        ///< range images requested
  bool motion_error_latched = false;
};

}  // namespace rover::msg
