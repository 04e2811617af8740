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
#include <string_view>
#include <variant>
#include <vector>

#include "rover/apl/sequencer/command_table.hpp"
#include "rover/apl/sequencer/sequence.hpp"
#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/msg/mobility.hpp"
#include "rover/msg/rendezvous.hpp"

namespace rover::apl::sequencer {

// ---- requests ----------------------------------------------------------------------------------

/// A mobility command in core/msg's vocabulary: its mode (seed 000 Table 2's driving modes, the
/// guarded arc of seed 003, STOP and CLEAR_FAULT) and, for the directed, VisOdom and guarded-arc
/// modes, its one primitive.
struct MobilityRequest {
  msg::MobilityMode mode = msg::MobilityMode::kStop;
  /// kArc, kStraight or kTurnInPlace; none for the modes that take a goal or nothing.
  std::optional<msg::DrivePrimitive> primitive;
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
  bool place = false;                   ///< APPROACH_TARGET: the instrument on it at the end
  bool focus = false;                   ///< APPROACH_TARGET: then the imager's auto-focus
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

/// A command's fault, by core/msg's name for it: the typed fault its service reported
/// (msg::MobilityFault: "NOPROGRESS", "WAYPT_TIMEOUT", "BAD_COMMAND"; msg::RendezvousFault:
/// "NOT_FOUND", "TOO_FEW_STRIPES"), OTHER for a failure its service names no fault for, or NONE.
/// The sequence language's `last.fault` compares with these names (FaultNames()). The class of
/// a fault (MER's goal and motion errors, seed 000 Table 1) is msg::FaultClass.
class Fault {
 public:
  Fault() = default;  ///< NONE
  explicit Fault(msg::MobilityFault f);
  explicit Fault(msg::RendezvousFault f);
  static Fault Other();
  /// The fault of a name in FaultNames(); nullopt for any other.
  static std::optional<Fault> Named(std::string_view name);

  const std::string& Name() const;
  int Index() const { return index_; }  ///< in FaultNames()
  bool IsNone() const { return index_ == 0; }
  /// msg::FaultClassOf for a mobility fault; kGoalError for the others (a rendezvous service
  /// fault leaves the rover safe, OTHER makes no claim); kNone for NONE.
  msg::FaultClass DefaultClass() const;
  friend bool operator==(const Fault&, const Fault&) = default;

 private:
  explicit Fault(int index) : index_(index) {}
  int index_ = 0;
};

const char* TerminationName(Termination t);  ///< "NOMINAL"
/// Every name of each enumeration, in value order (index = value): Termination, msg::FaultClass
/// (msg::FaultClassName's) and Fault (NONE, core/msg's mobility faults, its rendezvous faults
/// whose names the mobility ones do not already have, OTHER).
const std::vector<std::string>& TerminationNames();
const std::vector<std::string>& FaultClassNames();
const std::vector<std::string>& FaultNames();

/// How a dispatched command ended, as its service reported it.
struct Outcome {
  Termination termination = Termination::kNone;
  Fault fault;
  /// kNone with a fault: the fault's DefaultClass().
  msg::FaultClass fault_class = msg::FaultClass::kNone;
  std::string message;
  /// When it ended on the run clock (conditions on the pose wait for a pose at least this new);
  /// zero = unknown.
  Time stamp;

  static Outcome Nominal(Time stamp = {}) {
    return {Termination::kNominal, Fault(), msg::FaultClass::kNone, "", stamp};
  }
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
