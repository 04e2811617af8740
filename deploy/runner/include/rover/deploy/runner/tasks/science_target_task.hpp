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
///   4. At AT_TARGET records, against the truth at that moment: the placement error (the
///      reported target_in_rover, where the arm would be sent, against the target point in
///      the true rover frame; horizontal and 3-D), the same for wheel odometry alone (the
///      designated point carried by dl/pose_odometry), the standoff error and the heading to
///      the target.
///
///   task:
///     type: science_target
///     target: 0                # index into the scenario's science_targets
///     standoff: 0              # [m] 0 = the service's (1.05)
///     pixel_offset: {x: 0, y: 0}  # [px] added to the true pixel
///     look_offset: {x: 0, y: 0}   # [m] the mast aims this far off the target (site frame)
///     time_budget_s: 2400      # [s] the command's budget; 0 = the service's
///     expect: at_target        # | a fault: TARGET_LOST, BAD_COMMAND, ...
///
/// `at_target` passes on DONE after AT_TARGET; a fault name on FAILED with that fault.

#include <optional>
#include <string>

#include "rover/deploy/runner/task.hpp"

namespace rover::deploy::runner {

struct ScienceTargetSpec {
  int target = 0;
  double standoff = 0.0;
  Eigen::Vector2d pixel_offset = Eigen::Vector2d::Zero();
  Eigen::Vector2d look_offset = Eigen::Vector2d::Zero();
  double time_budget_s = 0.0;
  std::string expect = "at_target";
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

  ScienceTargetTask(ScienceTargetSpec spec, double start_x, double start_y)
      : spec_(std::move(spec)), start_x_(start_x), start_y_(start_y) {}
  Status Open(TaskContext& ctx) override;
  bool Ready() const override;
  TaskOutcome Run(TaskContext& ctx) override;
  std::vector<Eigen::Vector2d> PlannedPath() const override;

 private:
  ScienceTargetSpec spec_;
  double start_x_, start_y_;
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
