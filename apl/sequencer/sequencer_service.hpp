#pragma once
/// @file
/// apl-sequencer: the service that runs sequences (library apl_sequencer's parser and
/// Interpreter) by sending its neighbours' commands and waiting on their statuses.
///
///   in:  apl/sequence_command -> parse, check, Start      apl/mobility_status -> result
///        dl/mast_status       -> result                   dl/pose             -> OnPose
///        apl/rendezvous_status, dl/arm_status -> result
///        dl/relative_pose     -> VisOdom failures (visual-odometry samples not CONVERGED)
///   out: apl/mobility_command (mobility commands, and a STOP to cancel one), dl/mast_command,
///        apl/rendezvous_command, dl/arm_command (ARM MOVE, PLACE, STOW; a STOP to cancel),
///        apl/sequence_status (latched: on every change of state, step or message)
///
/// A run-clock timer at 10 Hz and every input call Interpreter::Step; nothing sleeps. Inputs
/// are handed over at the run-clock time of arrival (ctx.Now()); results keep their status's
/// stamp, so a condition after a drive waits for a pose from after it ended.
///
/// Bad input: a text that does not parse, names a command the service does not dispatch
/// (ARM UNSTOW), or arrives while a sequence runs is
/// answered by a FAILED status for its command_id whose message gives the reason (the first
/// parse error with line and column); nothing of it runs. A running sequence's status is
/// published again at its next change. A mobility command the manager's message cannot carry (a speed) ends its
/// step REJECTED BAD_COMMAND without being sent. Parameters: sequencer.* (InterpreterOptions).
/// Deactivation stops a running sequence (its outstanding mobility command gets a STOP).

#include <cstdint>
#include <optional>
#include <string>

#include <Eigen/Geometry>

#include "rover/apl/sequencer/interpreter.hpp"
#include "rover/msg/sequence.hpp"
#include "rover/runtime/service.hpp"

namespace rover::apl::sequencer {

class SequencerService final : public Service {
 public:
  SequencerService() : Service("apl-sequencer") {}

  void DeclareParameters(ParamSet& params) override;
  Status ValidateParameters(const ParamSet& params) const override;
  Status OnConfigure(ServiceContext& ctx, const ParamSet& params) override;
  Status OnDeactivate(ServiceContext& ctx) override;

  /// The interpreter (for tests); null before configuration.
  const Interpreter* interpreter() const { return interpreter_ ? &*interpreter_ : nullptr; }

 private:
  void OnSequenceCommand(const msg::SequenceCommand& c);
  void OnResult(std::uint32_t command_id, Family family, const Outcome& outcome);
  /// Sends what `out` asks for; a command refused before sending gets its result at once and
  /// the interpreter steps again. Then publishes the status if it changed.
  void Handle(StepOutput out);
  /// The outcome of a command that cannot be sent, else nullopt once it is written.
  std::optional<Outcome> Send(const Command& c);
  /// Stops an outstanding command: a mobility STOP for a mobility command.
  void Cancel(const Command& c);
  /// Publishes the current sequence's status when state, step, message or the commands
  /// dispatched changed since the last one.
  void PublishIfChanged(const SequenceStatus& status);
  void PublishStatus(const msg::SequenceStatus& s);
  void Refuse(std::uint32_t command_id, const std::string& why);

  ServiceContext* ctx_ = nullptr;
  std::optional<Interpreter> interpreter_;
  std::uint32_t sequence_id_ = 0;             // the apl/sequence_command running or last run
  std::optional<Family> outstanding_family_;  // of the command waiting for its result
  int visodom_failures_ = 0;                  // since the running sequence started
  std::optional<msg::SequenceStatus> last_status_;  // of the current sequence, as published
  std::uint32_t last_dispatched_ = 0;
  dds::Writer<rover_apl_MobilityCommand> mobility_writer_;
  dds::Writer<rover_dl_MastCommand> mast_writer_;
  dds::Writer<rover_apl_RendezvousCommand> rendezvous_writer_;
  dds::Writer<rover_dl_ArmCommand> arm_writer_;
  std::optional<Eigen::Isometry3d> site_from_rover_;  // the latest dl/pose (ARM PLACE)
  dds::Writer<rover_apl_SequenceStatus> status_writer_;
};

}  // namespace rover::apl::sequencer
