#pragma once
/// @file
/// Plain types of the mobility manager (MER's Mobility Manager, seed 000), free of DDS: the
/// command and status of apl/mobility_command / apl/mobility_status, the typed faults with their
/// class (seed 000 Table 1), and the requests the manager hands to the device layer (drive
/// primitives for dl/drive_command, range requests for dl/range_request, mast pointing for
/// dl/mast_command) and the reports it reads back.
///
/// Frames: site frame (x north, y west, z up) for goals, poses and keep-out zones; primitive
/// curvature is signed in the rover frame (positive = turn left), turn angles positive =
/// counter-clockwise seen from above. Metres, radians, run-clock time.
///
/// The enumerations keep the IDL's order (idl/rover_apl.idl, idl/rover_dl.idl) so that the
/// conversions are plain casts; a value outside an enumeration (e.g. an unknown mode from the
/// wire) is representable and is rejected by ValidateCommand.

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"

namespace rover::apl::mobility {

/// Driving modes (seed 000 Table 2, seed 003's guarded arc) and the two control commands.
enum class Mode : int {
  kDirected = 0,         ///< primitives, blind
  kVisOdom,              ///< primitives, visual odometry between steps
  kGoToWaypoint,         ///< blind drive to the goal, pose-corrected arcs
  kVisOdomGoToWaypoint,  ///< go-to-waypoint with visual odometry between steps
  kGuarded,              ///< primitives, each vetoed if terrain assessment forbids it
  kGuardedVisOdom,       ///< guarded, visual odometry between steps
  kAutoNav,              ///< drive to the goal with stereo hazard avoidance
  kAutoNavVisOdom,       ///< autonav, visual odometry between steps
  kGuardedArc,           ///< the first primitive blind (a turn), the rest only if seen safe
  kLongTraverse,         ///< global plan, then autonav legs (needs a GlobalPlanner)
  kStop,                 ///< stop what runs: goal error STOPPED for it
  kClearFault,           ///< clear a latched motion error
};
inline constexpr int kModeCount = 12;

enum class ThinkMode : int { kDefault = 0, kStopAndGo, kDriveWhileThinking };

enum class State : int { kIdle = 0, kRunning, kSucceeded, kFailed, kRejected };

enum class FaultClass : int { kNone = 0, kGoalError, kMotionError };

/// Typed faults (idl MobilityFault); FaultClassOf gives each one's class.
enum class Fault : int {
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
};
inline constexpr int kFaultCount = 20;

/// MER's class of each fault: kGoalError for ARB .. BAD_COMMAND, kMotionError for IMG .. NORTH.
FaultClass FaultClassOf(Fault f);
/// "ARB", "WAYPT_TIMEOUT", ... (MER's names, as in the IDL without MOBFAULT_).
std::string_view FaultName(Fault f);
/// "AUTONAV", "GUARDED_ARC", ... ("mode 17" for a value outside the enumeration).
std::string ModeName(Mode m);

/// Modes that drive to `goal` (and so need a finite goal and tolerance).
bool ModeHasGoal(Mode m);
/// Modes that execute `primitives`.
bool ModeHasPrimitives(Mode m);
/// Modes with visual odometry between steps.
bool ModeUsesVisOdom(Mode m);

/// Drive primitives, in dl/drive_command's order.
enum class PrimitiveKind : int { kStop = 0, kArc, kStraight, kTurnInPlace, kSteer };

/// One primitive of a directed, guarded or guarded-arc command.
struct Primitive {
  PrimitiveKind kind = PrimitiveKind::kStraight;
  double curvature = 0.0;  ///< [1/m] arcs, positive turns left
  double distance = 0.0;   ///< [m] arcs and straights; negative drives backwards
  double angle = 0.0;      ///< [rad] turns in place, positive = left
};

/// A simple polygon in the site frame (3..16 vertices, either winding).
struct KeepOutZone {
  std::string name;
  std::vector<Eigen::Vector2d> vertices;  ///< [m] site x, y
};

/// apl/mobility_command. Limits left at 0 take the options' values.
struct MobilityCommand {
  std::uint32_t command_id = 0;
  Mode mode = Mode::kDirected;
  Eigen::Vector3d goal = Eigen::Vector3d::Zero();  ///< [m] site frame (z unused)
  double tolerance = 0.0;                          ///< [m] goal radius, >= 0
  double time_budget_s = 0.0;                      ///< [s] run clock; 0 = none
  std::vector<Primitive> primitives;
  std::vector<KeepOutZone> keep_out;
  ThinkMode think = ThinkMode::kDefault;
  double max_tilt = 0.0;            ///< [rad]; 0 = options
  double min_northerly_tilt = 0.0;  ///< [rad] NORTH below it; 0 = no check
  double lmst_end_h = 0.0;          ///< [h] Mars local solar time limit; 0 = none
  int max_steps = 0;                ///< autonav steps; 0 = options
};

/// apl/mobility_status.
struct MobilityStatus {
  Time stamp;
  std::uint32_t command_id = 0;
  Mode mode = Mode::kDirected;
  State state = State::kIdle;
  FaultClass fault_class = FaultClass::kNone;
  Fault fault = Fault::kNone;
  std::string message;
  double distance_to_goal = -1.0;  ///< [m] horizontal; -1 for modes without a goal
  double distance_driven = 0.0;    ///< [m] path length driven under this command
  std::uint32_t steps = 0;         ///< drive steps taken
  std::uint32_t images = 0;        ///< range images requested
  bool motion_error_latched = false;
};

/// A drive primitive for dl/drive_command (speed and time-out 0 = locomotion's defaults).
struct DriveRequest {
  std::uint32_t command_id = 0;
  PrimitiveKind kind = PrimitiveKind::kStop;
  double curvature = 0.0;  ///< [1/m]
  double distance = 0.0;   ///< [m]
  double angle = 0.0;      ///< [rad]
  double speed = 0.0;      ///< [m/s]
  double timeout_s = 0.0;  ///< [s]
  Time stamp;
};

/// dl/drive_status states and terminations (the IDL's order).
enum class DriveState : int { kIdle = 0, kSteering, kDriving, kTurning, kDone, kFailed, kRejected };
enum class DriveTermination : int {
  kNone = 0,
  kNominal,
  kTilt,
  kSuspension,
  kMotorStall,
  kMotorCurrent,
  kMotorFault,
  kTimeout,
  kStopCommand,
  kRejectedBusy,
  kRejectedInvalid,
  kStaleSensor,
};

/// What the manager reads from dl/drive_status.
struct DriveReport {
  std::uint32_t command_id = 0;
  DriveState state = DriveState::kIdle;
  DriveTermination termination = DriveTermination::kNone;
  double distance_done = 0.0;  ///< [m]
  std::string message;
};

/// Camera pairs (rover_common CameraId order).
enum class Camera : int { kNavcam = 0, kFrontHazcam, kRearHazcam };
std::string_view CameraName(Camera c);

/// A request for one range image (dl/range_request).
struct RangeRequest {
  std::uint32_t request_id = 0;
  Camera camera = Camera::kFrontHazcam;
  int width = 0;  ///< [px] 0 = stereo's default
  Time stamp;
};

/// A mast pointing request (dl/mast_command), by angles or a site-frame look-at point.
struct MastRequest {
  std::uint32_t command_id = 0;
  bool look_at = false;
  double pan = 0.0;                                  ///< [rad]
  double tilt = 0.0;                                 ///< [rad]
  Eigen::Vector3d target = Eigen::Vector3d::Zero();  ///< [m] site frame (look_at)
  Time stamp;
};

enum class MastState : int { kIdle = 0, kMoving, kAtGoal, kFault, kRejected };
/// What the manager reads from dl/mast_status.
struct MastReport {
  std::uint32_t command_id = 0;
  MastState state = MastState::kIdle;
};

/// dl/pose: the rover's pose estimate at `stamp`.
struct PoseSample {
  Time stamp;
  Eigen::Isometry3d site_from_rover = Eigen::Isometry3d::Identity();
};

/// A visual-odometry result (dl/relative_pose from the VO service): converged or not.
struct VisOdomResult {
  Time t_to;  ///< end of the motion it measured
  bool converged = false;
};

}  // namespace rover::apl::mobility
