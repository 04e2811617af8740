#pragma once
/// @file
/// APPROACH_TARGET (TARGET_SCIENCE) as a DDS-free state machine: FIDO's single-command
/// science-target approach (seed 004, section 5). The operator picks the target at a pixel of a
/// NAVCAM left image the rover took; the rover then drives towards it in legs of at most
/// `target_leg`, and after each leg points the mast at the target, takes a pair and tracks the
/// target in it (TargetVision::Track: the features about it, the rover's motion relative to
/// them, the target re-ranged), so the next leg starts from where the target really is, not
/// where wheel odometry puts it. It stops `standoff` from the target (horizontal, rover origin
/// to the target point) facing it, where the arm reaches it.
///
/// Steps: designate (in the named pair) -> [leg -> look at the target -> pair -> track]* ->
/// AT_TARGET -> (with place_instrument: PLACING -> PLACED) -> (with autofocus: FOCUSING ->
/// FOCUSED) -> stands `hold_at_base_s` -> DONE.
/// Placement: one dl/arm_command PLACE at target_in_rover (the target measured in the last pair,
/// in the rover frame where the rover now stands); dl-arm goes above it and descends until its
/// contact switch closes (dl/arm/README.md). The arm is never out while the rover drives: when
/// dl-arm has said the arm is not stowed, the first leg waits for a STOW (an approach that
/// never hears from dl-arm drives as before). Auto-focus: one dl/arm_command AUTOFOCUS (FIDO's
/// ten-frame sweep, dl/arm/README.md) about the face's contact point when the instrument was
/// placed (the contact measured the surface), else about target_in_rover. Legs: farther than standoff +
/// `target_final_approach`, a `target_leg_mode` drive (autonav by default) of at most
/// `target_leg` towards the point `standoff` before the target; nearer, a directed turn to face
/// it and a straight (backwards when too close). Done when within `target_along_tolerance` of
/// the standoff and `target_heading_tolerance_deg` of facing it, measured in the last pair.
///
/// Phases: APPROACH_TARGET, AT_TARGET, DONE, FAILED. Goal errors (msg::RendezvousFault):
/// BAD_COMMAND (standoff, time budget, image id, pixel, target too far: the field and value
/// named), BUSY, STALE_POSE, TARGET_LOST (out of view, too few features: the tracker's reason),
/// MOBILITY, MAST, CAMERA, STOPPED, TIMEOUT, PLACEMENT (not at the standoff after
/// `target_max_steps` pairs), ARM (dl-arm refused, faulted or did not answer within
/// `arm_timeout_s`; its message included). Every one stops what the executor started (a
/// running arm move gets an ARM STOP).
///
/// Frames: site S (dl/pose), rover R. The status carries the target in S (target_position, for
/// the legs and the mast) and in R at the last fix (target_in_rover, for the arm: measured
/// in that pair, not carried by odometry).

#include <Eigen/Geometry>
#include <memory>
#include <optional>
#include <string>

#include "rover/apl/rendezvous/rendezvous_executor.hpp"
#include "rover/apl/rendezvous/rendezvous_options.hpp"
#include "rover/apl/rendezvous/sightings.hpp"

namespace rover::apl::rendezvous {

class TargetApproach {
 public:
  /// Preconditions: options.Validate() is ok, vision is not null.
  TargetApproach(const RendezvousOptions& options, std::shared_ptr<TargetVision> vision);

  /// A TARGET_SCIENCE command. `pair` is the NAVCAM pair named by command.image_id with the
  /// dl/pose at its capture, or null when the caller holds no such pair (BAD_COMMAND). With
  /// image_id 0 the target is the site point command.target_estimate instead: the mast looks
  /// at it, a pair is taken, and the target is designated where the point projects in it.
  ExecutorOutput OnCommand(const msg::RendezvousCommand& command, const NavcamPair* pair,
                           const Eigen::Isometry3d& site_from_rover_at_pair, Time now);
  /// TARGET_STOP: stops a running approach (STOPPED); false when none runs.
  bool Stop(std::uint32_t command_id, ExecutorOutput* out);
  ExecutorOutput OnPose(const msg::PoseSample& pose, Time now);
  ExecutorOutput OnMobilityStatus(const msg::MobilityStatus& status, Time now);
  ExecutorOutput OnMastStatus(const msg::MastStatus& status, Time now);
  /// dl/arm_status: remembered (is the arm stowed?) and, for this executor's arm commands,
  /// the end of a stow or a placement.
  ExecutorOutput OnArmStatus(const msg::ArmStatus& status, Time now);
  /// A NAVCAM pair; pairs that do not answer the outstanding request are ignored.
  ExecutorOutput OnStereoPair(const NavcamPair& pair, Time now);
  ExecutorOutput Step(Time now);

  const msg::RendezvousStatus& status() const { return status_; }
  bool busy() const { return wait_ != Wait::kNone; }

 private:
  enum class Wait { kNone, kMast, kSettle, kFrame, kDrive, kHold, kStow, kPlace, kFocus };

  void Reply(ExecutorOutput* out);
  void Fail(msg::RendezvousFault fault, const std::string& message, ExecutorOutput* out);
  bool PoseFresh(Time now) const;
  void Look(Time now, ExecutorOutput* out);
  void RequestPair(Time now, ExecutorOutput* out);
  void Drive(msg::MobilityCommand c, Time now, ExecutorOutput* out);
  void Arm(msg::ArmCommand c, Wait wait, Time now, ExecutorOutput* out);
  // dl-arm AUTOFOCUS on `target` (rover frame); `from` says where the point comes from.
  void Focus(const Eigen::Vector3d& target, const std::string& from, Time now,
             ExecutorOutput* out);
  // From the target estimate and the pose: done, or the next move.
  void Decide(Time now, ExecutorOutput* out);
  void Accept(const TargetFix& fix, const Eigen::Isometry3d& site_from_rover);

  RendezvousOptions options_;
  std::shared_ptr<TargetVision> vision_;
  msg::RendezvousCommand command_;
  msg::RendezvousStatus status_;
  std::optional<msg::PoseSample> pose_;
  Wait wait_ = Wait::kNone;
  Time wait_since_;
  Time deadline_;
  CommandIds ids_{kScienceIdHalf};
  std::uint32_t outstanding_ = 0;
  double standoff_ = 1.05;
  Eigen::Vector3d target_site_ = Eigen::Vector3d::Zero();
  int steps_ = 0;
  int mobility_retries_ = 0;
  bool designating_ = false;  // by a site point: the pair awaited designates
  std::optional<msg::ArmStatus> arm_;          // the latest dl/arm_status, anyone's
  std::optional<msg::MobilityCommand> after_stow_;  // the leg that waits for the stow
  std::optional<Eigen::Vector3d> focus_at_;  // placed: the contact point the sweep follows
};


}  // namespace rover::apl::rendezvous
