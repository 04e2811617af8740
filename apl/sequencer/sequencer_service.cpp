#include "sequencer_service.hpp"

#include <string>

#include "rover/apl/sequencer/parser.hpp"
#include "rover/base/log.hpp"
#include "rover/msg/arm_idl.hpp"
#include "rover/msg/mast_idl.hpp"
#include "rover/msg/mobility_idl.hpp"
#include "rover/msg/pose_idl.hpp"
#include "rover/msg/rendezvous_idl.hpp"
#include "rover/msg/sequence_idl.hpp"
#include "service_links.hpp"

namespace rover::apl::sequencer {
namespace {

constexpr double kStepRateHz = 10.0;

// Logs a failed write; a write failure never stops the service.
void Check(const Status& s, const char* topic) {
  if (!s.ok()) log::Error(std::string(topic) + " write failed", {{"error", s.message()}});
}

bool SameStatus(const msg::SequenceStatus& a, const msg::SequenceStatus& b) {
  return a.command_id == b.command_id && a.state == b.state && a.step == b.step &&
         a.message == b.message;
}

}  // namespace

void SequencerService::DeclareParameters(ParamSet& params) {
  DeclareParams<InterpreterOptions>(params, "sequencer.");
}

Status SequencerService::ValidateParameters(const ParamSet& params) const {
  return ReadParams<InterpreterOptions>(params, "sequencer.").status();
}

Status SequencerService::OnConfigure(ServiceContext& ctx, const ParamSet& params) {
  ctx_ = &ctx;
  ROVER_ASSIGN_OR_RETURN(const InterpreterOptions options,
                         ReadParams<InterpreterOptions>(params, "sequencer."));
  ROVER_ASSIGN_OR_RETURN(Interpreter interpreter, Interpreter::Create(options));
  interpreter_.emplace(std::move(interpreter));

  ROVER_ASSIGN_OR_RETURN(mobility_writer_,
                         ctx.MakeWriter<rover_apl_MobilityCommand>("apl/mobility_command"));
  ROVER_ASSIGN_OR_RETURN(mast_writer_, ctx.MakeWriter<rover_dl_MastCommand>("dl/mast_command"));
  ROVER_ASSIGN_OR_RETURN(arm_writer_, ctx.MakeWriter<rover_dl_ArmCommand>("dl/arm_command"));
  ROVER_ASSIGN_OR_RETURN(rendezvous_writer_,
                         ctx.MakeWriter<rover_apl_RendezvousCommand>("apl/rendezvous_command"));
  ROVER_ASSIGN_OR_RETURN(status_writer_,
                         ctx.MakeWriter<rover_apl_SequenceStatus>("apl/sequence_status"));

  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_apl_SequenceCommand>(
      "apl/sequence_command", [this](const dds::Sample<rover_apl_SequenceCommand>& s) {
        OnSequenceCommand(msg::SequenceCommandFromIdl(s.data()));
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_apl_MobilityStatus>(
      "apl/mobility_status", [this](const dds::Sample<rover_apl_MobilityStatus>& s) {
        const Result<msg::MobilityStatus> st = msg::MobilityStatusFromIdl(s.data());
        if (!st.ok()) {  // a value no enumerator has ends nothing
          log::Warn("apl/mobility_status refused", {{"error", st.status().message()}});
          return;
        }
        if (const std::optional<Outcome> o = OutcomeOfMobilityStatus(*st)) {
          OnResult(st->command_id, Family::kMobility, *o);
        }
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_MastStatus>(
      "dl/mast_status", [this](const dds::Sample<rover_dl_MastStatus>& s) {
        const Result<msg::MastStatus> st = msg::MastStatusFromIdl(s.data());
        if (!st.ok()) return;  // a state no enumerator has ends nothing
        if (const std::optional<Outcome> o = OutcomeOfMastStatus(*st)) {
          OnResult(st->command_id, Family::kMast, *o);
        }
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_ArmStatus>(
      "dl/arm_status", [this](const dds::Sample<rover_dl_ArmStatus>& s) {
        const Result<msg::ArmStatus> st = msg::ArmStatusFromIdl(s.data());
        if (!st.ok()) return;
        if (const std::optional<Outcome> o = OutcomeOfArmStatus(*st)) {
          OnResult(st->command_id, Family::kArm, *o);
        }
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_apl_RendezvousStatus>(
      "apl/rendezvous_status", [this](const dds::Sample<rover_apl_RendezvousStatus>& s) {
        const Result<msg::RendezvousStatus> st = msg::RendezvousStatusFromIdl(s.data());
        if (!st.ok()) return;  // a phase or fault no enumerator has ends nothing
        if (const std::optional<Outcome> o = OutcomeOfRendezvousStatus(*st)) {
          OnResult(st->command_id, Family::kRendezvous, *o);
        }
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_PoseEstimate>(
      "dl/pose", [this](const dds::Sample<rover_dl_PoseEstimate>& s) {
        const Result<msg::PoseEstimate> p = msg::PoseEstimateFromIdl(s.data());
        if (!p.ok()) return;
        Eigen::Isometry3d x = Eigen::Isometry3d::Identity();
        x.linear() = p->orientation.toRotationMatrix();
        x.translation() = p->position;
        site_from_rover_ = x;
        interpreter_->OnPose(PoseOfEstimate(*p));
        if (interpreter_->busy()) Handle(interpreter_->Step(ctx_->Now()));
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_RelativePose>(
      "dl/relative_pose", [this](const dds::Sample<rover_dl_RelativePose>& s) {
        const Result<msg::RelativePose> r = msg::RelativePoseFromIdl(s.data());
        if (!r.ok() || !interpreter_->busy() || !IsVisOdomFailure(*r)) return;
        interpreter_->OnVisOdomFailures(++visodom_failures_);
        Handle(interpreter_->Step(ctx_->Now()));
      }));
  ctx.executor().AddTimer(Seconds(1.0 / kStepRateHz), [this] {
    if (interpreter_->busy()) Handle(interpreter_->Step(ctx_->Now()));
  });
  ctx.SetHealth(rover_HEALTH_OK, "");
  return Status::Ok();
}

Status SequencerService::OnDeactivate(ServiceContext& ctx) {
  if (interpreter_ && interpreter_->busy()) {
    // The outstanding command is cancelled; the ON_ABORT block cannot run without the service,
    // so its first command is not sent and a second Stop ends the block.
    StepOutput out = interpreter_->Stop(ctx.Now(), "apl-sequencer deactivated");
    if (out.cancel) Cancel(*out.cancel);
    if (interpreter_->busy()) out = interpreter_->Stop(ctx.Now(), "apl-sequencer deactivated");
    PublishIfChanged(out.status);
  }
  return Status::Ok();
}

void SequencerService::Refuse(std::uint32_t command_id, const std::string& why) {
  log::Warn("sequence refused", {{"command_id", command_id}, {"reason", why}});
  msg::SequenceStatus s;
  s.stamp = ctx_->Now();
  s.command_id = command_id;
  s.state = msg::SequenceState::kFailed;
  s.message = why;
  PublishStatus(s);
}

void SequencerService::OnSequenceCommand(const msg::SequenceCommand& c) {
  const Time now = ctx_->Now();
  if (interpreter_->busy()) {
    // The refusal stays the latched sample until the running sequence's status changes.
    Refuse(c.command_id, "sequence " + std::to_string(sequence_id_) + " is running (step " +
                             std::to_string(interpreter_->status().step) + ")");
    return;
  }
  ParseOptions options;
  options.source = "apl/sequence_command " + std::to_string(c.command_id);
  Result<std::map<std::string, std::string>> overrides = msg::ParseSequenceOverrides(c.overrides);
  if (!overrides.ok()) return Refuse(c.command_id, options.source + ": " + overrides.status().message());
  options.overrides = std::move(*overrides);
  Result<Sequence> sequence = ParseSequence(c.text, options);
  if (!sequence.ok()) return Refuse(c.command_id, sequence.status().message());
  if (Status s = CheckDispatchable(*sequence); !s.ok()) {
    return Refuse(c.command_id, options.source + ": " + s.message());
  }
  if (Status s = interpreter_->Start(std::move(*sequence), now); !s.ok()) {
    return Refuse(c.command_id, s.message());
  }
  log::Info("sequence started", {{"command_id", c.command_id}});
  sequence_id_ = c.command_id;
  visodom_failures_ = 0;
  outstanding_family_.reset();
  Handle(interpreter_->Step(now));
}

void SequencerService::OnResult(std::uint32_t command_id, Family family,
                                const Outcome& outcome) {
  if (!outstanding_family_ || *outstanding_family_ != family ||
      interpreter_->outstanding() != command_id) {
    return;  // another client's command, or one the sequencer no longer waits for
  }
  outstanding_family_.reset();
  const Status s = interpreter_->OnCommandResult(command_id, outcome);
  if (!s.ok()) log::Warn("command result refused", {{"command_id", command_id},
                                                    {"error", s.message()}});
  Handle(interpreter_->Step(ctx_->Now()));
}

std::optional<Outcome> SequencerService::Send(const Command& c) {
  const Time now = ctx_->Now();
  switch (c.family) {
    case Family::kMobility: {
      Result<msg::MobilityCommand> m = MobilityCommandOf(c, now);
      if (!m.ok()) return Outcome::Rejected(Fault(msg::MobilityFault::kBadCommand), m.status().message(), now);
      msg::MobilityCommandMessage out;
      msg::MobilityCommandToIdl(*m, &out);
      ctx_->Stamp(out.msg.header, "site");
      Check(mobility_writer_.Write(out.msg), "apl/mobility_command");
      break;
    }
    case Family::kMast: {
      rover_dl_MastCommand out{};
      msg::MastCommandToIdl(MastCommandOf(c, now), &out);
      ctx_->Stamp(out.header, "site");
      Check(mast_writer_.Write(out), "dl/mast_command");
      break;
    }
    case Family::kRendezvous: {
      rover_apl_RendezvousCommand out{};
      msg::RendezvousCommandToIdl(RendezvousCommandOf(c, now), &out);
      ctx_->Stamp(out.header, "site");
      Check(rendezvous_writer_.Write(out), "apl/rendezvous_command");
      break;
    }
    case Family::kArm: {
      Result<msg::ArmCommand> m = ArmCommandOf(c, site_from_rover_, now);
      if (!m.ok()) return Outcome::Rejected(Fault(msg::MobilityFault::kBadCommand), m.status().message(), now);
      rover_dl_ArmCommand out{};
      msg::ArmCommandToIdl(*m, &out);
      ctx_->Stamp(out.header, "rover");
      Check(arm_writer_.Write(out), "dl/arm_command");
      break;
    }
    default:  // CheckDispatchable refused these before the start
      return Outcome::Rejected(Fault(msg::MobilityFault::kBadCommand), "apl-sequencer does not dispatch " +
                                                    std::string(FamilyName(c.family)) +
                                                    " commands yet", now);
  }
  outstanding_family_ = c.family;
  log::Info("sequence command", {{"sequence", sequence_id_}, {"command_id", c.id},
                                 {"step", c.step}, {"text", c.text}});
  return std::nullopt;
}

void SequencerService::Cancel(const Command& c) {
  outstanding_family_.reset();
  if (c.family == Family::kRendezvous) {
    rover_apl_RendezvousCommand stop{};
    msg::RendezvousCommandToIdl(RendezvousStopCommand(c.id, ctx_->Now()), &stop);
    ctx_->Stamp(stop.header, "site");
    Check(rendezvous_writer_.Write(stop), "apl/rendezvous_command");
    return;
  }
  if (c.family == Family::kArm) {
    rover_dl_ArmCommand stop{};
    msg::ArmCommandToIdl(ArmStopCommand(c.id, ctx_->Now()), &stop);
    ctx_->Stamp(stop.header, "rover");
    Check(arm_writer_.Write(stop), "dl/arm_command");
    return;
  }
  if (c.family != Family::kMobility) return;  // a mast move ends by itself
  msg::MobilityCommandMessage stop;
  msg::MobilityCommandToIdl(MobilityStopCommand(c.id, ctx_->Now()), &stop);
  ctx_->Stamp(stop.msg.header, "site");
  Check(mobility_writer_.Write(stop.msg), "apl/mobility_command");
}

void SequencerService::Handle(StepOutput out) {
  for (int guard = 0; guard < 1000; ++guard) {
    if (out.cancel) Cancel(*out.cancel);
    if (!out.command) break;
    const std::optional<Outcome> refused = Send(*out.command);
    if (!refused) break;
    const Status s = interpreter_->OnCommandResult(out.command->id, *refused);
    if (!s.ok()) log::Warn("command result refused", {{"error", s.message()}});
    out = interpreter_->Step(ctx_->Now());
  }
  PublishIfChanged(out.status);
}

void SequencerService::PublishIfChanged(const SequenceStatus& status) {
  const msg::SequenceStatus s = SequenceStatusOf(status, sequence_id_, ctx_->Now());
  if (!last_status_ || !SameStatus(*last_status_, s) || status.dispatched != last_dispatched_) {
    last_dispatched_ = status.dispatched;
    last_status_ = s;
    PublishStatus(s);
  }
}

void SequencerService::PublishStatus(const msg::SequenceStatus& s) {
  rover_apl_SequenceStatus m{};
  msg::SequenceStatusToIdl(s, &m);
  ctx_->Stamp(m.header, "site");
  Check(status_writer_.Write(m), "apl/sequence_status");
  if (s.state == msg::SequenceState::kFailed) {
    log::Warn("sequence failed", {{"command_id", s.command_id}, {"message", s.message}});
  }
}

}  // namespace rover::apl::sequencer
