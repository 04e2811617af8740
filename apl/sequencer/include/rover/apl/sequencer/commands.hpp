#pragma once
/// @file
/// What the interpreter hands out and takes in, free of DDS: the typed command requests of each
/// family (the sequencer service maps them to apl/mobility_command, dl/mast_command,
/// apl/rendezvous_command and the arm service's command), the outcome of a command (its
/// termination, MER fault type and class, message) and the pose input.
///
/// Units: SI and radians. Frames: site frame (x north, y west, z up), rover heading `yaw`
/// counter-clockwise from site x; turn angles + = left (counter-clockwise).

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "rover/apl/sequencer/command_table.hpp"
#include "rover/apl/sequencer/sequence.hpp"
#include "rover/base/status.hpp"
#include "rover/base/time.hpp"

namespace rover::apl::sequencer {

// ---- requests ----------------------------------------------------------------------------------

/// Seed 000 Table 2's driving modes, the guarded arc of seed 003 and the manager's own commands.
enum class MobilityMode {
  kDirected,             ///< blind drive primitive
  kVisodom,              ///< drive primitive with visual-odometry updates
  kGoToWaypoint,         ///< blind go-to-waypoint
  kVisodomGoToWaypoint,  ///< go-to-waypoint with visual odometry
  kGuarded,              ///< terrain assessment, no path selection
  kGuardedVisodom,
  kGuardedArc,           ///< arc driven only if the hazard cameras show it safe
  kAutonav,              ///< terrain assessment and path selection
  kAutonavVisodom,
  kLongTraverse,         ///< ROAMAN plan, then autonav legs
  kStop,
  kClearFault,
};

enum class Primitive { kNone, kArc, kStraight, kTurnInPlace };

struct MobilityRequest {
  MobilityMode mode = MobilityMode::kStop;
  Primitive primitive = Primitive::kNone;  ///< directed, visodom and guarded-arc modes
  double curvature = 0.0;       ///< [1/m] + turns left
  double distance = 0.0;        ///< [m] along the path
  double angle = 0.0;           ///< [rad] turn in place, + = left (TURN TO: resolved at dispatch)
  double goal_x = 0.0;          ///< [m] site frame, waypoint modes
  double goal_y = 0.0;          ///< [m]
  double tolerance = 0.0;       ///< [m] goal radius, waypoint modes
  double speed = 0.0;           ///< [m/s] 0 = the service's default
  double time_budget_s = 0.0;   ///< [s] 0 = the service's default
};

struct MastRequest {
  enum class Kind { kAngles, kLookAt };
  Kind kind = Kind::kAngles;
  double pan = 0.0;   ///< [rad] + looks left
  double tilt = 0.0;  ///< [rad] + looks up
  Vec3 point;         ///< kLookAt, site frame [m]
};

struct RendezvousRequest {
  enum class Kind { kReturnToLander, kApproachTarget };
  Kind kind = Kind::kReturnToLander;
  std::optional<Vec3> point;            ///< lander estimate or designated site-frame point [m]
  std::optional<std::uint32_t> image;   ///< APPROACH_TARGET by pixel: the image id
  double u = 0.0;                       ///< [px] with `image`
  double v = 0.0;                       ///< [px]
  double standoff = 0.0;                ///< [m]
  double time_budget_s = 0.0;           ///< [s] 0 = the service's default
};

struct ArmRequest {
  enum class Kind { kMove, kPlace, kStow, kUnstow, kAutofocus };
  Kind kind = Kind::kStow;
  std::array<double, 4> joints{};  ///< kMove [rad]
  Vec3 point;                      ///< kPlace, site frame [m]
  double hover = 0.0;              ///< kPlace [m]
  int focus_steps = 0;             ///< kAutofocus
  double focus_step = 0.0;         ///< kAutofocus [m]
};

using Request = std::variant<MobilityRequest, MastRequest, RendezvousRequest, ArmRequest>;

/// A command to dispatch.
struct Command {
  std::uint32_t id = 0;  ///< unique per interpreter, increasing; results name it
  int step = 0;          ///< step number in the sequence (1-based)
  int line = 0;          ///< source line
  CommandKind kind = CommandKind::kStop;
  Family family = Family::kMobility;
  Request request;
  std::string text;      ///< as written
};

// ---- outcomes ----------------------------------------------------------------------------------

/// How a command ended.
enum class Termination {
  kNone,      ///< no command has ended yet (the value of `last.termination` before one has)
  kNominal,   ///< reached its goal
  kFault,     ///< ended by a fault (see Fault and FaultClass)
  kRejected,  ///< refused without moving (invalid or busy)
};

/// MER's two classes (seed 000 Table 1): a goal error leaves the rover safe and ready for the
/// next goal; a motion error refuses all motion until CLEAR_FAULT.
enum class FaultClass { kNone, kGoalError, kMotionError };

/// Seed 000 Table 1's fault types (names as MER's, '-' written '_'), then those of the
/// rendezvous and arm services.
enum class Fault {
  kNone,
  // goal errors
  kArb,             ///< ARB: resource rescinded
  kAcm,             ///< ACM: not OK to drive
  kPot,             ///< POT: steering calibration with a bad potentiometer
  kTod,             ///< TOD: time-of-day limit
  kStopped,         ///< STOPPED: stop command
  kWaypointTimeout, ///< WAYPT_TIMEOUT
  kNoPath,          ///< NOPATH: no safe path
  kNoProgress,      ///< NOPROGRESS: limit cycle or stuck
  kBusy,            ///< BUSY: mobility already running
  kVisodom,         ///< VISODOM: too many visual-odometry failures
  kKeepOut,         ///< KEEPOUT: the next step would enter a keep-out zone
  // motion errors
  kImg,             ///< IMG: image acquisition failed
  kSapp,            ///< SAPP: attitude (IMU) problem
  kMot,             ///< MOT: motor error
  kIdd,             ///< IDD: arm unstowed during a drive
  kDriveTimeout,    ///< DRIVE_TIMEOUT: one step timed out
  kCsw,             ///< CSW: contact switch
  kTilt,            ///< TILT: excessive or unknown tilt
  kSuspension,      ///< SUSPENSION: excessive or unknown articulation
  kBadTables,       ///< BAD_TABLES: drive tables corrupted
  kNorth,           ///< NORTH: insufficient northerly tilt
  // rendezvous and arm (goal errors unless the service says otherwise)
  kTrackingLost,    ///< TRACKING_LOST: the target left the view
  kNoRange,         ///< NO_RANGE: the designated pixel has no range
  kArmCollision,    ///< ARM_COLLISION: the move would hit the rover
  kNoFocus,         ///< NO_FOCUS: auto-focus found no best focus
  kInvalid,         ///< INVALID: the service found the command invalid
  kOther,           ///< OTHER: any other reason (see the message)
};

const char* TerminationName(Termination t);  ///< "NOMINAL"
const char* FaultClassName(FaultClass c);    ///< "GOAL_ERROR"
const char* FaultName(Fault f);              ///< "NOPROGRESS"
/// Table 1's class of a fault (kNone for kNone).
FaultClass DefaultFaultClass(Fault f);
/// Every name of each enumeration, in value order (index = value).
const std::vector<std::string>& TerminationNames();
const std::vector<std::string>& FaultClassNames();
const std::vector<std::string>& FaultNames();

/// How a dispatched command ended, as its service reported it.
struct Outcome {
  Termination termination = Termination::kNone;
  Fault fault = Fault::kNone;
  /// kNone with a fault: the fault's DefaultFaultClass.
  FaultClass fault_class = FaultClass::kNone;
  std::string message;
  /// When it ended on the run clock (conditions on the pose wait for a pose at least this new);
  /// zero = unknown.
  Time stamp;

  static Outcome Nominal(Time stamp = {}) { return {Termination::kNominal, Fault::kNone,
                                                    FaultClass::kNone, "", stamp}; }
  static Outcome Failed(Fault fault, std::string message, Time stamp = {});
  static Outcome Rejected(Fault fault, std::string message, Time stamp = {});

  /// Ok when the fields agree: NOMINAL has no fault; FAULT and REJECTED have one; NONE is not
  /// an outcome.
  Status Validate() const;
  /// "NOPROGRESS (goal error): <message>" or "NOMINAL".
  std::string Describe() const;
};

// ---- pose ------------------------------------------------------------------------------------

/// The rover's pose estimate (dl/pose): position of the rover centre in the site frame and ZYX
/// attitude.
struct PoseSample {
  Time stamp;
  Vec3 position;      ///< [m]
  double roll = 0.0;  ///< [rad]
  double pitch = 0.0; ///< [rad]
  double yaw = 0.0;   ///< [rad]
  bool valid = true;  ///< false: the estimator marked it unusable
};

/// Tilt of the rover's z axis from vertical: acos(cos roll * cos pitch) [rad].
double TiltOf(const PoseSample& pose);
/// Horizontal distance from the rover centre to `point` [m].
double DistanceTo(const PoseSample& pose, const Vec3& point);

// ---- building ----------------------------------------------------------------------------------

/// True when building the command needs the pose (TURN TO faces a point or heading).
bool NeedsPose(const CommandCall& call);
/// The typed command for a parsed call. `pose` is required when NeedsPose(call); TURN TO's angle
/// is then wrap(atan2(ty - y, tx - x) - yaw) for a point, wrap(heading - yaw) for a heading, in
/// (-pi, pi]. Errors: FailedPrecondition when the pose is needed and absent.
Result<Command> BuildCommand(const CommandCall& call, const PoseSample* pose, std::uint32_t id,
                             int step);

}  // namespace rover::apl::sequencer
