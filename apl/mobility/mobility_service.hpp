#pragma once
/// @file
/// apl-mobility: the service that binds the MobilityManager (library apl_mobility) to topics,
/// with GESTALT (apl/gestalt's TerrainMap and ArcEvaluator) injected.
///
///   in:  apl/mobility_command -> OnCommand      dl/pose          -> OnPose
///        dl/range_image       -> OnRangeImage   dl/drive_status  -> OnDriveStatus
///        dl/mast_status       -> OnMastStatus   dl/relative_pose -> OnVisOdom (VO samples only)
///   out: dl/drive_command, dl/range_request, dl/mast_command, apl/mobility_status (latched),
///        apl/goodness_map (after each assessment), apl/arc_votes (one per decision)
/// A run-clock timer at 10 Hz calls Step (time-outs, the periodic running status); nothing
/// sleeps. Every input is handed over at the run-clock time of arrival (ctx.Now()).
///
/// Parameters: mobility.* (MobilityOptions), gestalt.* (GestaltOptions) and the input limits
/// inputs.* (dl/pose: 1 s); an invalid one refuses configuration naming its key. A sample the
/// conversion rejects (non-finite, out of range, malformed) goes to OnInputRejected with the
/// conversion's message (dl/pose while running: SAPP; the pending range image: IMG; ...) and to
/// sys/health through the harness's input monitor; nothing a sample carries can crash the
/// service. Deactivation ends a running command STOPPED (a STOP drive is sent).
///
/// Restarts: in a supervised set the running command is checkpointed (command_checkpoint.hpp).
/// Restarted after a crash or kill -9 while a command ran, the service ends that command with
/// the goal error RESTART on apl/mobility_status and reports DEGRADED "restarted: command N
/// (MODE) abandoned" on sys/health until the next command arrives.

#include <optional>

#include "rover/apl/gestalt/options.hpp"
#include "rover/apl/mobility/command_checkpoint.hpp"
#include "rover/base/checkpoint.hpp"
#include "rover/apl/mobility/mobility_manager.hpp"
#include "rover/runtime/service.hpp"

namespace rover::apl::mobility {

class MobilityService final : public Service {
 public:
  MobilityService() : Service("apl-mobility") {}

  /// Staleness limits of the periodic inputs (parameters inputs.*): dl/pose (10 Hz); the manager's
  /// pose_stale_s also stops a drive on it.
  std::vector<runtime::InputSpec> Inputs() const override {
    // A range image is used at once: one captured more than 2 s before it arrives (a delayed
    // or replayed one) is reported on sys/health; a step is assessed on it all the same.
    return {{"dl/pose", {.max_age_s = 1.0}}, {"dl/range_image", {.max_latency_s = 2.0}}};
  }
  void DeclareParameters(ParamSet& params) override;
  Status ValidateParameters(const ParamSet& params) const override;
  Status OnConfigure(ServiceContext& ctx, const ParamSet& params) override;
  Status OnDeactivate(ServiceContext& ctx) override;

  /// The manager (for tests); null before configuration.
  const MobilityManager* manager() const { return manager_ ? &*manager_ : nullptr; }

 private:
  void Publish(const MobilityOutput& out);

  ServiceContext* ctx_ = nullptr;
  std::optional<MobilityManager> manager_;
  dds::Writer<rover_dl_DriveCommand> drive_writer_;
  dds::Writer<rover_dl_RangeRequest> range_writer_;
  dds::Writer<rover_dl_MastCommand> mast_writer_;
  dds::Writer<rover_apl_MobilityStatus> status_writer_;
  dds::Writer<rover_apl_GoodnessMap> map_writer_;
  dds::Writer<rover_apl_ArcVotes> votes_writer_;
  // dl/vo_command: visual-odometry pairs asked for while a VisOdom mode runs (dl-vo images only
  // then, unless its imaging = always).
  dds::Writer<rover_dl_VoCommand> vo_writer_;
  bool vo_requested_ = false;
  void UpdateVoRequest();
  // Ends a command a restart interrupted (from the checkpoint); then checkpoints "idle".
  void EndInterruptedCommand();
  void SaveCommandCheckpoint(const CommandCheckpoint& c);
  CheckpointStore checkpoints_;  // disabled outside a supervised set
  CommandCheckpoint command_checkpoint_;
  bool restart_reported_ = false;
};

}  // namespace rover::apl::mobility
