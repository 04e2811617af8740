#pragma once
/// @file
/// ArmExecutor: the instrument-arm state machine (no DDS, no threads, no clock reads; the caller
/// passes the run-clock time). The dl-arm service binds it to topics.
///
/// Frames and angles (core/hwconfig arm_description.hpp): rover frame R (x forward, y left,
/// z up, origin on the ground plane); joints q = (azimuth, shoulder, elbow, wrist) [rad] in
/// ddl/joint_state's arm_angle order, driven by motors hw::kArmAzimuth .. hw::kArmWrist;
/// F(q) = ArmDescription::Forward(q).face is the centre of the instrument's face and
/// L(q) = Forward(q).look the direction it looks along. "Face down" means L = -z, the pose
/// ArmDescription::FaceDown(p) solves for a face centre p.
///
/// Commands (dl/arm_command), each becoming one or more legs: a leg is one GROUP_POSITION
/// ddl/motor_command for the four arm motors, every max_rate equal to the leg's rate (ddl-motor
/// synchronises the group, so the joint with the largest travel runs at that rate and the
/// joints move along the straight joint-space line that RoverDescription::CheckArmMove checks):
///   JOINTS  one leg to `joints` at `speed` -> AT_GOAL.
///   PLACE   (target = the face centre wanted, R) leg 1 to the hover pose
///           q_h = FaceDown(target + hover_height z) at `speed`; leg 2, the guarded descent, to
///           q_d = FaceDown(target - overdrive z) at the rate that moves the face at
///           `descent_speed`: with q0 the joints measured when the descent starts,
///             D = |F(q_d) - F(q0)|   (about hover_height + overdrive),   T = D / descent_speed,
///             rate = max_j |q_d,j - q0,j| / T,
///           so the synchronised move takes T and the face covers D in it (the joint-space line
///           bends the face's path slightly: "about" descent_speed). When ddl/joint_state's
///           arm_contact closes during the descent -> GROUP_STOP and PLACED, the message giving
///           the measured face point and how far above (+) or below (-) the target it stopped.
///           The descent arriving without contact -> FAULT "no contact within <overdrive> m
///           below the target". A contact that closes during leg 1 (after the switch was seen
///           open) -> GROUP_STOP and FAULT "unexpected contact ..."; a switch still closed when
///           the descent would start -> FAULT (the hover point touches something, or the switch
///           is stuck).
///   STOW    when the instrument is face down (L_z < -0.9) and lower than the shoulder pivot
///           (F_z < ArmDescription::shoulder z: it may rest on or hang just above a surface),
///           leg 1 lifts it straight up: FaceDown(F(q) + hover_height z), used only when it is
///           reachable; then a leg to ArmDescription::stow at `speed` -> STOWED.
///   AUTOFOCUS (target = the surface point as estimated, e.g. from stereo; FIDO's auto-focus
///           with the microscopic imager, core/hwconfig MicroscopeOptics, working distance s):
///           the face goes face down to heights h_k = s + span/2 - k span/(n - 1) above the
///           target, k = 0..n-1 (n = focus_steps, span = focus_span: the sweep brackets best
///           focus when the estimate is within span/2), the first at `speed`, each next one a
///           guarded step down at descent_speed; at each a ddl/mi_request, and the frame's
///           WaveletFocusMeasure (focus.hpp) is paired with the face height measured when it
///           was requested. After the sweep FindFocusPeak over the frames by height:
///             - the sharpest frame inside the sweep -> best focus at the parabola's vertex;
///             - the sharpest at an end, with best / worst at least sqrt(focus_min_contrast)
///               -> one more step beyond that end (down guarded, up plain), up to
///               focus_max_extra_steps, then FAULT "no focus peak ...";
///             - best / worst measure < focus_min_contrast (once no more steps are due) ->
///               FAULT "no focus signal".
///           The contact switch closing during a step down (the surface is higher than
///           estimated by more than span/2 - about 3 cm with the defaults, FIDO's case):
///           GROUP_STOP, and best focus is predicted from the contact: the face at
///           (face height at contact - ArmDescription::contact_standoff + s), focus_predicted. Then a move to best focus, a
///           final frame, and FOCUSED with focus_height (measured face above the target),
///           focus_images, focus_image_id and focus_measure. A frame not back within
///           focus_image_timeout_s -> FAULT.
///   STOP    GROUP_STOP of the arm motors, FAULT "stopped by command <id>". Never refused (its
///           other fields are ignored); it ends any running command.
/// A leg is done when the motor driver reported its group DONE and every measured joint is
/// within `tolerance` of the leg's goal (DONE alone would trust the driver's own tolerance; the
/// joints alone would count an arm passing through the goal). A new good command supersedes a
/// running one (the arm goes to the newer goal).
///
///   Submit(command)      checks the command; good -> the first leg's motor command, MOVING.
///   OnJoints(sample)     the measured arm angles and contact switch (ddl/joint_state); unhealthy,
///                        non-finite and out-of-order samples are ignored (they do not count as
///                        fresh). Reacts to the contact switch at once (outputs stamped with the
///                        sample's time).
///   OnMotorStatus(s)     the motor driver's report on a group; only the running leg's group
///                        counts. FAULT or REJECTED -> FAULT naming the driver's reason.
///   Step(now)            at check_rate_hz: leg arrival; FAULT (and a GROUP_STOP) on timeout
///                        (timeout_s covers all legs of a command), on stale joints during a
///                        move, and when DONE but the joints stay off the goal for 1 s; a
///                        status every 1 / status_rate_hz while MOVING.
///
/// States (rover_dl.idl ArmState): IDLE (no command yet), MOVING, AT_GOAL, PLACED, STOWED,
/// FAULT, REJECTED. Every status carries the measured joints, the running leg's goal
/// (joint_goals), tool_point = F(measured joints), the contact switch, and `stowed` (every
/// joint within tolerance of ArmDescription::stow).
///
/// Refusals (REJECTED, a message naming the field and value, no motor command; a running move
/// keeps running): an unknown mode; NaN/inf joints, target or timeout_s; timeout_s < 0 or
/// > max_timeout_s; no fresh ddl/joint_state (none yet, or older than joint_stale_s); joints
/// outside the limits (ArmDescription::CheckLimits); a hover or descent point FaceDown cannot
/// reach (out of reach, on the azimuth axis, a joint beyond its limit); and any leg that
/// RoverDescription::CheckArmMove refuses: from the measured joints to the first goal, and
/// between consecutive goals (PLACE: hover -> end of descent; STOW: lift -> stow). Its message
/// names the link and the rover part ("... the arm's instrument would come 0.04 m from the
/// rover's wheel_LF ..."), so a user sees why. A move that starts in a pose the check refuses
/// (e.g. the arm pushed into a keep-out volume) is refused at 0 % of the way.
///
/// Motor command ids are kMotorIdBase + n (n = 0, 1, ...), a range neither dl-locomotion's ids
/// (from 1) nor dl-mast's (0x4D000000 + n) reach, so no client mistakes another's
/// ddl/motor_status for its own.

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "rover/base/status.hpp"
#include "rover/base/time.hpp"
#include "rover/dl/arm/arm_options.hpp"
#include "rover/dl/arm/focus.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/msg/arm.hpp"
#include "rover/msg/camera.hpp"
#include "rover/msg/motor.hpp"
#include "rover/msg/sensors.hpp"

namespace rover::dl::arm {

// The messages are core/msg's (rover/msg/arm.hpp, motor.hpp, sensors.hpp).
using hwconfig::ArmAngles;
using msg::ArmCommand;
using msg::ArmMode;
using msg::ArmState;
using msg::ArmStateName;
using msg::ArmStatus;

/// First motor command id of the arm (see the file comment).
inline constexpr std::uint32_t kMotorIdBase = 0x41000000u;
/// Mask of the four arm motors.
inline constexpr std::uint16_t kArmMotorMask =
    static_cast<std::uint16_t>((1u << hw::kArmAzimuth) | (1u << hw::kArmShoulder) |
                               (1u << hw::kArmElbow) | (1u << hw::kArmWrist));

/// What to publish after a call, in order. Motor commands are for kArmMotorMask only: a
/// position goal (goal and max_rate set at the four arm motors) or a group stop; timeout_s 0
/// (the motor driver derives it from the planned move).
struct ArmOutput {
  std::vector<msg::MotorCommand> motor_commands;
  std::vector<ArmStatus> statuses;
  std::vector<msg::MiRequest> mi_requests;  ///< microscopic-imager frames to take (AUTOFOCUS)
};

/// First ddl/mi_request id of the arm's auto-focus.
inline constexpr std::uint32_t kMiRequestIdBase = 0x41A00000u;

class ArmExecutor {
 public:
  /// Errors: rover.Validate() (the arm description included) or options.Validate() failures.
  static Result<ArmExecutor> Create(const hwconfig::RoverDescription& rover,
                                    const ArmOptions& options);

  ArmOutput Submit(const ArmCommand& command, Time now);
  /// Uses arm_angle, arm_contact, health and stamp of ddl/joint_state.
  ArmOutput OnJoints(const msg::JointState& joints);
  ArmOutput OnMotorStatus(const msg::MotorStatus& report, Time now);
  /// A ddl/mi_frame; only the frame the running AUTOFOCUS waits for counts (others ignored). A
  /// frame that is not healthy, or whose focus measure cannot be computed, is a FAULT.
  ArmOutput OnMiFrame(const msg::MiFrame& frame, Time now);
  ArmOutput Step(Time now);
  /// Stops a running command (GROUP_STOP of the arm motors, FAULT naming `why`); nothing if idle.
  ArmOutput Stop(const std::string& why, Time now);

  /// The latest status (IDLE before the first command).
  const ArmStatus& status() const { return status_; }
  bool moving() const { return status_.state == ArmState::kMoving; }
  const ArmOptions& options() const { return options_; }
  /// The frames of the running or latest AUTOFOCUS: face height above its target [m] and the
  /// focus measure, in the order taken (the final frame included).
  const std::vector<FocusSample>& focus_samples() const { return focus_samples_; }
  /// True when the latest usable ddl/joint_state is at most joint_stale_s old at `now`.
  bool JointsFresh(Time now) const;

 private:
  enum class Stage { kJoints, kHover, kDescent, kLift, kStow, kFocusMove, kFocusStep };
  // What follows a leg's arrival in AUTOFOCUS: a sweep frame or the final frame.
  enum class Frame { kNone, kSweep, kFinal };
  struct Leg {
    Stage stage = Stage::kJoints;
    ArmAngles goal{};
    Frame frame = Frame::kNone;
  };
  struct Plan {
    std::vector<Leg> legs;
    Eigen::Vector3d target = Eigen::Vector3d::Zero();  // PLACE only
  };
  struct Joints {
    Time stamp;
    ArmAngles q{};
    bool contact = false;
    int fastest_wheel = 0;      // of ddl/joint_state's wheel_rate
    double wheel_rate = 0.0;    // [rad/s] its |rate|
  };

  ArmExecutor(const hwconfig::RoverDescription& rover, const ArmOptions& options)
      : rover_(rover), options_(options) {}

  Result<Plan> PlanOf(const ArmCommand& command, Time now) const;
  Result<Plan> PlacePlan(const Eigen::Vector3d& target) const;
  Result<Plan> StowPlan() const;
  Result<Plan> AutofocusPlan(const ArmCommand& command) const;
  // AUTOFOCUS: appends a leg putting the face `height` above the target and starts it.
  void FocusLegTo(double height, Frame frame, Time now, std::string message, ArmOutput* out);
  void RequestFrame(Time now, ArmOutput* out);
  void DecideFocus(Time now, ArmOutput* out);
  void FocusOnContact(Time now, ArmOutput* out);
  double FaceHeight() const;  // measured face above plan_.target [m]
  void StartLeg(std::size_t leg, Time now, std::string message, ArmOutput* out);
  void CheckArrival(Time now, ArmOutput* out);
  void OnContact(Time now, ArmOutput* out);
  void SetStatus(ArmState state, std::string message, Time now, ArmOutput* out);
  void Reject(const ArmCommand& command, const Status& why, Time now, ArmOutput* out);
  void Fault(std::string message, Time now, ArmOutput* out);
  void Fill(ArmStatus* s) const;
  msg::MotorCommand MotorCommand(msg::GroupMode mode, Time now);
  bool WithinTolerance(const ArmAngles& goal) const;
  // "" while the wheels stand still (|rate| <= max_wheel_rate), else which turns how fast.
  std::string Driving() const;
  // A move that is not a stow (stows may run while the rover drives).
  bool MovingOut() const;
  double DescentRate(const ArmAngles& from, const ArmAngles& to) const;
  const Leg& leg() const { return plan_.legs[leg_]; }
  std::uint32_t NextMotorId();

  hwconfig::RoverDescription rover_;
  ArmOptions options_;
  ArmStatus status_;
  std::optional<Joints> joints_;
  Plan plan_;                       // the running command's legs
  std::size_t leg_ = 0;             // the running leg
  bool contact_seen_open_ = false;  // the switch read open since the command began
  std::uint32_t next_motor_id_ = kMotorIdBase;
  std::uint32_t motor_id_ = 0;  // motor command of the running leg
  bool motors_done_ = false;
  Time done_at_;  // when the motor driver reported the leg DONE
  Time move_start_;
  double move_timeout_s_ = 0.0;
  Time last_status_;
  // AUTOFOCUS state.
  std::vector<FocusSample> focus_samples_;
  double focus_step_ = 0.0;          // [m] sweep step
  int focus_extra_steps_ = 0;        // steps added beyond the sweep so far
  bool focus_predicted_ = false;
  std::uint32_t next_mi_id_ = kMiRequestIdBase;
  std::uint32_t awaiting_frame_ = 0;  // ddl/mi_request id being waited for; 0 = none
  Time frame_requested_;
  double frame_height_ = 0.0;        // face height when that frame was requested
};

}  // namespace rover::dl::arm
