#pragma once
/// @file
/// The science-target task: the operator's part of FIDO's single-command approach (seed 004,
/// section 5) and the judge's measurement of it.
///
///   1. Points the mast at the target point (dl/mast_command LOOK_AT, as an operator would aim
///      the NAVCAM at the rock of interest) and takes a full NAVCAM pair (ddl/camera_request,
///      ids kCameraPrefix << 24 | n).
///   2. Picks the target's pixel in that pair's left image: the target point -- on the rock's
///      surface, on its face towards the rover's start 0.4 radius from its centre, where a
///      person clicks on the rock (its top sits on the silhouette from afar) -- projected with
///      the frame's camera model and the true rover pose (sim/truth), plus the scenario's
///      `pixel_offset`. Only the runner reads truth.
///   3. Sends one apl/rendezvous_command TARGET_SCIENCE naming the pair (image_id) and pixel,
///      then waits for its terminal apl/rendezvous_status (DONE or FAILED).
///   4. At AT_TARGET records, against the truth at that moment: the aim error (the reported
///      target_in_rover, where the arm is sent, against the target point in the true rover
///      frame; horizontal and 3-D; called placement_error when `place` is off), the same for
///      wheel odometry alone (the designated point carried by dl/pose_odometry), the standoff
///      error and the heading to the target.
///   5. With `place: true` the command asks for the instrument on the target; at PLACED records
///      placement_error: the instrument's face centre (sim/truth tool_point, the arm's reach
///      point) against the target point, and whether it touches (instrument_contact).
///
///   task:
///     type: science_target
///     target: 0                # index into the scenario's science_targets
///     standoff: 0              # [m] 0 = the service's (1.05)
///     pixel_offset: {x: 0, y: 0}  # [px] added to the true pixel
///     look_offset: {x: 0, y: 0}   # [m] the mast aims this far off the target (site frame)
///     time_budget_s: 2400      # [s] the command's budget; 0 = the service's
///     expect: at_target        # | a fault: TARGET_LOST, BAD_COMMAND, ...
///     place: false             # put the arm's instrument on the target at the end
///     template:                # optional: MER's conditional-sequence approach first
///       file: ../sequences/approach_template.seq   # relative to the scenario file
///       time_budget_s: 1500
///
/// `at_target` passes on DONE after AT_TARGET (and PLACED with `place`); a fault name on FAILED
/// with that fault.
///
/// With `template`, each run first approaches the same target as MER did (seed 003): the
/// target's site point is ranged on the ground from the designation pair (the picked pixel by
/// correlation along its ray, ray_stereo.hpp, with the dl/pose of the pair), written into the
/// sequence's TARGET `target` (apl/sequencer ApplyOverrides) and sent on apl/sequence_command to
/// apl-sequencer; at its end the runner measures where the rover believes the target is
/// (dl/pose) against the truth (`template_aim_error`; `template_placement_error` at the
/// instrument when the template's ARM PLACE touched, else the aim; `template_instrument_contact`;
/// measured also when only the ARM PLACE failed), stows the arm, drives the rover back to the
/// start (a DIRECTED turn, straight, turn from dl/pose) and takes a fresh designation pair for
/// the tracked approach. The template's outcome is measured, not judged; the run's pass is the
/// tracked approach's.

#include <optional>
#include <string>

#include "rover/deploy/runner/task.hpp"
#include "rover/msg/arm.hpp"

namespace rover::deploy::runner {

struct TemplateSpec {
  std::string file;  ///< resolved against the scenario's folder
  double time_budget_s = 1500.0;
};

struct ScienceTargetSpec {
  int target = 0;
  double standoff = 0.0;
  Eigen::Vector2d pixel_offset = Eigen::Vector2d::Zero();
  Eigen::Vector2d look_offset = Eigen::Vector2d::Zero();
  double time_budget_s = 0.0;
  std::string expect = "at_target";
  /// place the arm's instrument on the target at the end (command place_instrument); the
  /// placement error is then measured at the instrument (sim/truth tool_point)
  bool place = false;
  /// then focus the microscopic imager on it (command autofocus; FIDO's single command ends
  /// so); judged from truth at FOCUSED
  bool autofocus = false;
  std::optional<TemplateSpec> template_approach;
};

/// Parses and checks the section (names file, line and key on error; a target index the
/// scenario's science_targets do not have is named with their count).
Result<ScienceTargetSpec> ParseScienceTargetTask(const TaskSource& source);

class ScienceTargetTask : public Task {
 public:
  static constexpr std::uint32_t kCommandId = 1;
  static constexpr std::uint32_t kStopId = 2;
  static constexpr std::uint32_t kCameraPrefix = 200;
  static constexpr std::uint32_t kMastId = 0xC8000001u;
  static constexpr double kGraceS = 60.0;
  static constexpr std::uint32_t kSequenceId = 100;
  static constexpr std::uint32_t kReturnDriveId = 0xC8000101u;
  static constexpr std::uint32_t kStowId = 0xC8000201u;

  ScienceTargetTask(ScienceTargetSpec spec, double start_x, double start_y, double start_yaw)
      : spec_(std::move(spec)), start_x_(start_x), start_y_(start_y), start_yaw_(start_yaw) {}
  Status Open(TaskContext& ctx) override;
  bool Ready() const override;
  TaskOutcome Run(TaskContext& ctx) override;
  std::vector<Eigen::Vector2d> PlannedPath() const override;

 private:
  struct Designation {
    Eigen::Vector2d pixel = Eigen::Vector2d::Zero();
    std::uint32_t image_id = 0;
    Eigen::Isometry3d truth = Eigen::Isometry3d::Identity();  // sim/truth at the pair
    std::optional<Eigen::Isometry3d> estimate, odometry;      // dl/pose, dl/pose_odometry
    std::optional<Eigen::Vector3d> ground_point;  // the pixel ranged on the ground, site frame
  };
  // Looks at the target, takes pair `n`, picks the pixel; "" or the failure.
  std::string Designate(TaskContext& ctx, std::uint32_t n, StepResult* step, Designation* d);
  // MER's template approach to the ground-ranged point, then back to the start.
  void RunTemplate(TaskContext& ctx, const Designation& d, TaskOutcome* out);
  void Pump();
  // Stows the arm (dl/arm_command STOW) when dl-arm said it is out; "" or the failure.
  std::string StowArm(TaskContext& ctx);

  std::optional<Eigen::Isometry3d> truth_now_, estimate_now_, odometry_now_;
  Eigen::Vector3d tool_now_ = Eigen::Vector3d::Zero();  // sim/truth: the instrument's face
  bool tool_contact_now_ = false;
  std::optional<msg::ArmStatus> arm_now_;
  dds::Writer<rover_dl_ArmCommand> arm_;
  dds::Reader<rover_dl_ArmStatus> arm_status_;
  dds::Writer<rover_apl_SequenceCommand> sequence_;
  dds::Reader<rover_apl_SequenceStatus> sequence_status_;
  dds::Writer<rover_apl_MobilityCommand> mobility_;
  dds::Reader<rover_apl_MobilityStatus> mobility_status_;
  dds::Reader<rover_dl_PoseEstimate> estimate_;
  ScienceTargetSpec spec_;
  double start_x_, start_y_, start_yaw_;
  std::optional<Eigen::Vector3d> top_;  // the target point (site frame), from the world
  dds::Writer<rover_apl_RendezvousCommand> command_;
  dds::Writer<rover_dl_MastCommand> mast_;
  dds::Writer<rover_ddl_StereoRequest> camera_;
  dds::Reader<rover_apl_RendezvousStatus> status_;
  dds::Reader<rover_dl_MastStatus> mast_status_;
  dds::Reader<rover_ddl_StereoFrame> frames_;
  dds::Reader<rover_sim_Truth> truth_;
  dds::Reader<rover_dl_PoseEstimate> odometry_;
};

/// Registers science_target.
void RegisterScienceTargetTask(TaskRegistry& registry);

}  // namespace rover::deploy::runner
