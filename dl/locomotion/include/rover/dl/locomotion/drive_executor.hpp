#pragma once
/// @file
/// Drive-primitive executor: MER's low-level driving (Biesiadecki & Maimone 2006) as a
/// deterministic state machine. It is fed time-stamped inputs (run-clock time) and returns the
/// motor-group commands to send and the drive statuses to publish; it never reads a clock or
/// sleeps.
///
/// Inputs:  OnJointState (ddl/joint_state), OnAttitude (dl/pose: roll, pitch, yaw),
///          OnMotorStatus (ddl/motor_status), Submit (dl/drive_command), Step (timer).
/// Outputs: DriveOutput::motor_commands (ddl/motor_command), DriveOutput::statuses
///          (dl/drive_status, in order).
///
/// Primitives (all "steer first, then drive"):
///   ARC(k, s), STRAIGHT(s): steer the corners to the Ackermann angles of k (0 for STRAIGHT),
///     then one position goal per drive motor: th_i(start) + g_i s / r, at rates g_i v / r
///     (ackermann.hpp). Nominal end: at least half of the wheels (3 of 6) have turned their
///     planned rotation to within wheel_goal_tolerance (as MER).
///   TURN_IN_PLACE(a): steer the corners tangent to the circle about the centre, then velocity
///     goals q_i w / r with w = sign(e) clamp(turn_gain |e|, min_turn_rate, planned yaw rate),
///     where e = a - (heading change so far, unwrapped from the attitude yaw). Nominal end:
///     |e| <= heading_tolerance (closed loop on the estimated heading).
///   STEER(k): steer only; nominal when every corner is within steer_tolerance of its goal.
///   STOP: brakes every mobility motor; ends a running primitive with STOP_COMMAND.
/// The steering phase ends when every measured steer angle is within steer_tolerance of its
/// goal. Every end of a primitive (nominal or not) commands GROUP_STOP on all mobility motors.
///
/// Reactive checks, once per cycle of 1 / check_rate_hz (8 Hz) while a primitive runs, in this
/// order (the first that fires terminates the primitive, state FAILED):
///   1. motor group: a FAULT or REJECTED report for a group of this primitive ->
///      MOTOR_STALL (stall), MOTOR_CURRENT (over-current) or MOTOR_FAULT (anything else);
///   2. staleness: no healthy finite joint state for joint_stale_s, or no attitude for
///      attitude_stale_s -> STALE_SENSOR;
///   3. tilt: acos(cos roll cos pitch) > max_tilt for tilt_cycles consecutive cycles -> TILT;
///   4. suspension: a rocker or bogie angle outside its range for suspension_cycles consecutive
///      cycles -> SUSPENSION;
///   then nominal progress, then 5. run-clock time-out -> TIMEOUT (timeout_s of the command, or
///   timeout_factor * planned duration + timeout_margin_s).
/// Step() may be called more often than the check rate: a cycle runs when at least 0.9 / rate
/// has passed since the previous one, so tilt_cycles keeps its meaning.
///
/// Rejections (state REJECTED; nothing moves; when idle a GROUP_STOP is sent so the rover stays
/// braked): a new primitive while one runs -> REJECTED_BUSY (the running one continues, as MER);
/// unknown primitive, NaN/inf, |k| > 1/min_turn_radius, |s| > max_distance, |a| >
/// max_turn_angle, speed outside [0, max_speed], timeout_s outside [0, max_timeout_s] ->
/// REJECTED_INVALID with an InvalidReason; inputs already stale at submission -> STALE_SENSOR;
/// with require_arm_stowed, an arm joint of the latest joint state more than arm_stow_tolerance
/// off its stowed angle (RoverGeometry::arm_stow) -> REJECTED_INVALID (arm_not_stowed, the
/// message names the joint and how far): the rover does not drive with its arm out. (Checked
/// when a primitive is accepted; dl-arm is not told to keep the arm still during a drive.)
/// A status with state DONE always has termination NOMINAL; FAILED has an off-nominal reason.

#include <cstdint>
#include <optional>
#include <vector>

#include "rover/base/params.hpp"
#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/dl/locomotion/ackermann.hpp"
#include "rover/dl/locomotion/drive_types.hpp"
#include "rover/dl/locomotion/rover_geometry.hpp"

namespace rover::dl::locomotion {

struct DriveOptions {
  double check_rate_hz = 8.0;          ///< [Hz] reactive-check cycle
  double default_speed = 0.05;         ///< [m/s] when DriveCommand.speed == 0 (MER top speed)
  double max_speed = 0.1;              ///< [m/s] largest accepted DriveCommand.speed
  double max_distance = 50.0;          ///< [m] largest accepted |distance|
  double max_turn_angle = 6.2831853;   ///< [rad] largest accepted |angle| (one revolution)
  double max_timeout_s = 3600.0;       ///< [s] largest accepted timeout_s
  double steer_tolerance = 0.035;      ///< [rad] steering reached (2 deg)
  double steer_rate = 0.3;             ///< [rad/s] max rate of the steer motors
  double wheel_goal_tolerance = 0.02;  ///< [rad] a wheel "rotated its planned amount"
  double heading_tolerance = 0.01745;  ///< [rad] turn-in-place goal (1 deg)
  double turn_gain = 1.0;              ///< [1/s] yaw-rate command per rad of heading error
  double min_turn_rate = 0.005;        ///< [rad/s] smallest commanded yaw rate
  double max_tilt = 0.5236;            ///< [rad] (30 deg)
  int tilt_cycles = 3;                 ///< consecutive cycles over max_tilt
  double rocker_min = -0.4363;         ///< [rad] (-25 deg)
  double rocker_max = 0.4363;          ///< [rad]
  double bogie_min = -0.6109;          ///< [rad] (-35 deg)
  double bogie_max = 0.6109;           ///< [rad]
  int suspension_cycles = 1;           ///< consecutive cycles out of range
  double joint_stale_s = 0.5;          ///< [s] joint state older than this is stale
  double attitude_stale_s = 1.0;       ///< [s] attitude older than this is stale
  double timeout_factor = 2.0;         ///< derived time-out = factor * planned duration + margin
  double timeout_margin_s = 10.0;      ///< [s]
  bool require_arm_stowed = true;      ///< refuse to drive while the arm is out
  double arm_stow_tolerance = 0.05;    ///< [rad] an arm joint this close to its stowed angle

  Status Validate() const;
};

/// What to send and publish after an input.
struct DriveOutput {
  std::vector<msg::MotorCommand> motor_commands;
  std::vector<DriveStatus> statuses;
  bool empty() const { return motor_commands.empty() && statuses.empty(); }
};

class DriveExecutor {
 public:
  /// Errors: invalid geometry or options.
  static Result<DriveExecutor> Create(const RoverGeometry& geometry, const DriveOptions& options);

  /// Stores the latest sample. Non-finite or unhealthy samples are ignored (they do not refresh
  /// the staleness timer). Samples older than the stored one are ignored. A sample whose wheel
  /// angles jumped implausibly from the stored one (CheckWheelJump: an encoder fault) is not
  /// stored and its OutOfRange returned, so no motor goal is ever computed from it.
  Status OnJointState(const msg::JointState& sample);
  /// Stores the latest attitude and, while a primitive runs, accumulates the unwrapped heading
  /// change. Non-finite or unhealthy samples are ignored.
  void OnAttitude(const msg::AttitudeSample& sample);
  /// Stores the latest motor-group report (checked at the next cycle).
  void OnMotorStatus(const msg::MotorStatus& status);

  /// Handles a drive command received at run-clock time `now` (see the file comment).
  DriveOutput Submit(const DriveCommand& command, Time now);
  /// Runs the reactive checks and the state machine if a cycle is due at `now`. While a primitive
  /// runs, each cycle reports one status.
  DriveOutput Step(Time now);

  bool busy() const { return phase_ != Phase::kIdle; }
  /// The latest status (of the running or the last primitive).
  const DriveStatus& status() const { return status_; }
  /// The plan of the running (or last) primitive.
  const DrivePlan& plan() const { return plan_; }
  const RoverGeometry& geometry() const { return geometry_; }
  const DriveOptions& options() const { return options_; }

  /// Checks a command against the limits without executing it: kNone if valid; otherwise the
  /// reason and a message naming the field and value.
  InvalidReason CheckCommand(const DriveCommand& command, std::string* message) const;

 private:
  enum class Phase { kIdle, kSteering, kDriving, kTurning };

  DriveExecutor(const RoverGeometry& g, const DriveOptions& o) : geometry_(g), options_(o) {}

  msg::MotorCommand NewCommand(Time now, std::uint16_t mask, GroupMode mode);
  msg::MotorCommand StopCommand(Time now);
  msg::MotorCommand SteerCommand(Time now);
  msg::MotorCommand DrivePositionCommand(Time now);
  msg::MotorCommand TurnVelocityCommand(Time now, double yaw_rate);
  DriveStatus MakeStatus(Time now, std::uint32_t command_id, DrivePrimitive primitive,
                         DriveState state, DriveTermination termination, std::string message) const;
  void Reject(const DriveCommand& command, Time now, DriveTermination termination,
              InvalidReason reason, std::string message, DriveOutput* out);
  void Terminate(Time now, DriveTermination termination, std::string message, DriveOutput* out);
  bool SensorsFresh(Time now, std::string* why) const;
  bool SteeringReached() const;
  double DistanceDone() const;
  double RemainingTimeout(Time now) const;
  void RunCycle(Time now, DriveOutput* out);

  RoverGeometry geometry_;
  DriveOptions options_;

  // Latest inputs.
  std::optional<msg::JointState> joint_;
  std::optional<msg::AttitudeSample> attitude_;
  std::optional<msg::MotorStatus> motor_status_;

  // Running primitive.
  Phase phase_ = Phase::kIdle;
  DriveCommand command_;
  DrivePlan plan_;
  DriveStatus status_;
  Time start_time_;
  double timeout_s_ = 0.0;
  std::uint32_t first_motor_id_ = 0;  // first motor command id of this primitive
  std::uint32_t last_motor_id_ = 0;   // latest motor command id issued
  std::uint32_t next_motor_id_ = 1;
  std::array<double, kNumWheels> wheel_start_{};
  std::array<double, kNumWheels> path_ratio_{};
  double heading_change_ = 0.0;
  double last_yaw_ = 0.0;
  double commanded_yaw_rate_ = 0.0;
  int tilt_count_ = 0;
  int suspension_count_ = 0;
  std::optional<Time> last_cycle_;
};

/// Declares the drive parameters under `prefix` ("drive." by default); angles in degrees with a
/// `_deg` suffix.
void DeclareDriveParams(ParamSet& params, const std::string& prefix = "drive.");
Result<DriveOptions> DriveOptionsFromParams(const ParamSet& params,
                                            const std::string& prefix = "drive.");

}  // namespace rover::dl::locomotion
