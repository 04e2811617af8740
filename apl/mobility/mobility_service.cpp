#include "mobility_service.hpp"

#include <memory>
#include <string>

#include "rover/apl/mobility/command_checkpoint.hpp"
#include "rover/apl/mobility/navigation.hpp"
#include "rover/base/format.hpp"
#include "rover/base/log.hpp"
#include "rover/hwconfig/rover_description.hpp"
#include "rover/msg/drive_idl.hpp"
#include "rover/msg/mast_idl.hpp"
#include "rover/msg/mobility_idl.hpp"
#include "rover/msg/navigation_idl.hpp"
#include "rover/msg/pose_idl.hpp"
#include "rover/msg/range_idl.hpp"

namespace rover::apl::mobility {
namespace {

constexpr double kStepRateHz = 10.0;

// Logs a failed write; a write failure never stops the service.
void Check(const Status& s, const char* topic) {
  if (!s.ok()) log::Error(std::string(topic) + " write failed", {{"error", s.message()}});
}


}  // namespace

void MobilityService::DeclareParameters(ParamSet& params) {
  DeclareNavigationParams(params);
}

Status MobilityService::ValidateParameters(const ParamSet& params) const {
  return ValidateNavigationParams(params);
}

Status MobilityService::OnConfigure(ServiceContext& ctx, const ParamSet& params) {
  ctx_ = &ctx;
  log::Info("local planner", {{"planner", PlannerName(params)}});
  ROVER_ASSIGN_OR_RETURN(MobilityManager manager, MakeMobilityManager(params));
  manager_.emplace(std::move(manager));

  ROVER_ASSIGN_OR_RETURN(drive_writer_, ctx.MakeWriter<rover_dl_DriveCommand>("dl/drive_command"));
  ROVER_ASSIGN_OR_RETURN(range_writer_, ctx.MakeWriter<rover_dl_RangeRequest>("dl/range_request"));
  ROVER_ASSIGN_OR_RETURN(mast_writer_, ctx.MakeWriter<rover_dl_MastCommand>("dl/mast_command"));
  ROVER_ASSIGN_OR_RETURN(status_writer_,
                         ctx.MakeWriter<rover_apl_MobilityStatus>("apl/mobility_status"));
  ROVER_ASSIGN_OR_RETURN(map_writer_, ctx.MakeWriter<rover_apl_GoodnessMap>("apl/goodness_map"));
  ROVER_ASSIGN_OR_RETURN(votes_writer_, ctx.MakeWriter<rover_apl_ArcVotes>("apl/arc_votes"));
  ROVER_ASSIGN_OR_RETURN(vo_writer_, ctx.MakeWriter<rover_dl_VoCommand>("dl/vo_command"));

  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_apl_MobilityCommand>(
      "apl/mobility_command", [this](const dds::Sample<rover_apl_MobilityCommand>& s) {
        const MobilityCommand c = msg::MobilityCommandFromIdl(s.data());
        log::Info("mobility command",
                  {{"command_id", c.command_id}, {"mode", msg::MobilityModeName(c.mode)}});
        if (restart_reported_) {  // the commander has moved on from the interrupted command
          restart_reported_ = false;
          ctx_->SetHealth(rover_HEALTH_OK, "");
        }
        Publish(manager_->OnCommand(c, ctx_->Now()));
      }));
  // A rejected sample goes to the manager (its typed fault) and, returned, to sys/health.
  const auto rejected = [this](MobilityInput input, const Status& s, std::uint32_t id = 0) {
    Publish(manager_->OnInputRejected(input, s.message(), ctx_->Now(), id));
    return s;
  };
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_PoseEstimate>(
      "dl/pose", [this, rejected](const dds::Sample<rover_dl_PoseEstimate>& s) {
        const Result<PoseSample> pose = msg::PoseSampleFromIdl(s.data());
        if (!pose.ok()) return rejected(MobilityInput::kPose, pose.status());
        Publish(manager_->OnPose(*pose, ctx_->Now()));
        return Status::Ok();
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_RangeImage>(
      "dl/range_image", [this, rejected](const dds::Sample<rover_dl_RangeImage>& s) {
        const rover_dl_RangeImage& m = s.data();
        const Result<msg::RangeImage> image = msg::RangeImageFromIdl(m);
        if (!image.ok()) return rejected(MobilityInput::kRangeImage, image.status(), m.request_id);
        MobilityOutput out;
        {
          runtime::ScopedActivity planning(ctx_->activities(), "planning");
          out = manager_->OnRangeImage(nav_core::RangeScanFromImage(*image), image->camera,
                                       m.request_id, ctx_->Now());
        }
        Publish(out);
        return Status::Ok();
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_DriveStatus>(
      "dl/drive_status", [this, rejected](const dds::Sample<rover_dl_DriveStatus>& s) {
        const Result<DriveStatus> status = msg::DriveStatusFromIdl(s.data());
        if (!status.ok()) return rejected(MobilityInput::kDriveStatus, status.status());
        Publish(manager_->OnDriveStatus(*status, ctx_->Now()));
        return Status::Ok();
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_MastStatus>(
      "dl/mast_status", [this, rejected](const dds::Sample<rover_dl_MastStatus>& s) {
        const Result<MastStatus> status = msg::MastStatusFromIdl(s.data());
        if (!status.ok()) return rejected(MobilityInput::kMastStatus, status.status());
        Publish(manager_->OnMastStatus(*status, ctx_->Now()));
        return Status::Ok();
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_RelativePose>(
      "dl/relative_pose", [this, rejected](const dds::Sample<rover_dl_RelativePose>& s) {
        const Result<RelativePose> vo = msg::RelativePoseFromIdl(s.data());
        if (!vo.ok()) return rejected(MobilityInput::kVisOdom, vo.status());
        Publish(manager_->OnVisOdom(*vo, ctx_->Now()));
        return Status::Ok();
      }));
  ctx.executor().AddTimer(Seconds(1.0 / kStepRateHz), [this] {
    MobilityOutput out;
    {
      runtime::ScopedActivity planning(ctx_->activities(), "planning");
      out = manager_->Step(ctx_->Now());
    }
    Publish(out);
  });
  ctx.SetHealth(rover_HEALTH_OK, "");
  checkpoints_ = CheckpointStore::FromEnvironment(ctx.name());
  EndInterruptedCommand();
  return Status::Ok();
}

void MobilityService::EndInterruptedCommand() {
  if (!checkpoints_.enabled()) return;
  const auto loaded = checkpoints_.Load();
  if (!loaded.ok()) {
    log::Warn("checkpoint unreadable: a command interrupted by a restart cannot be named",
              {{"error", loaded.status().message()}});
  } else if (loaded->has_value()) {
    const auto c = CommandCheckpointFromFields(**loaded);
    if (!c.ok()) {
      log::Warn("checkpoint unreadable: a command interrupted by a restart cannot be named",
                {{"path", checkpoints_.path()}, {"error", c.status().message()}});
    } else if (c->running) {
      const MobilityStatus ended = InterruptedCommandStatus(*c, ctx_->Now());
      log::Warn("restarted: the running command is abandoned",
                {{"command_id", c->command_id}, {"mode", msg::MobilityModeName(c->mode)}});
      ctx_->SetHealth(rover_HEALTH_DEGRADED, "restarted: command " +
                                                 std::to_string(c->command_id) + " (" +
                                                 msg::MobilityModeName(c->mode) + ") abandoned");
      restart_reported_ = true;
      command_checkpoint_ = *c;
      MobilityOutput out;
      out.statuses.push_back(ended);
      Publish(out);
      return;
    }
  }
  SaveCommandCheckpoint(CommandCheckpoint{});
}

void MobilityService::SaveCommandCheckpoint(const CommandCheckpoint& c) {
  command_checkpoint_ = c;
  if (!checkpoints_.enabled()) return;
  const Status s = checkpoints_.Save(CommandCheckpointFields(c));
  if (!s.ok()) log::Warn("checkpoint not written", {{"error", s.message()}});
}

Status MobilityService::OnDeactivate(ServiceContext& ctx) {
  if (manager_ && manager_->busy()) {
    MobilityCommand stop;
    stop.mode = Mode::kStop;
    Publish(manager_->OnCommand(stop, ctx.Now()));
  }
  checkpoints_.Remove();  // a clean stop: nothing was interrupted
  return Status::Ok();
}

void MobilityService::Publish(const MobilityOutput& out) {
  for (const std::string& note : out.notes) log::Warn(note);
  for (const DriveCommand& d : out.drives) {
    rover_dl_DriveCommand m{};
    msg::DriveCommandToIdl(d, &m);
    ctx_->Stamp(m.header, "rover");
    Check(drive_writer_.Write(m), "dl/drive_command");
  }
  for (const RangeRequest& r : out.range_requests) {
    rover_dl_RangeRequest m{};
    msg::RangeRequestToIdl(r, &m);
    ctx_->Stamp(m.header, "rover");
    Check(range_writer_.Write(m), "dl/range_request");
  }
  for (const MastCommand& r : out.mast_requests) {
    rover_dl_MastCommand m{};
    msg::MastCommandToIdl(r, &m);
    ctx_->Stamp(m.header, "site");
    Check(mast_writer_.Write(m), "dl/mast_command");
  }
  if (out.goodness_map) {
    const msg::GoodnessMap map = nav_core::GoodnessMapToMessage(*out.goodness_map);
    rover_apl_GoodnessMap m{};
    const Status filled = msg::GoodnessMapToIdl(map, &m);
    if (filled.ok()) {
      ctx_->Stamp(m.header, "site");
      m.header.stamp_ns = map.stamp.ns;  // capture time of the newest data
      Check(map_writer_.Write(m), "apl/goodness_map");
    } else {
      Check(filled, "apl/goodness_map");
    }
  }
  for (const ArcVotesSnapshot& v : out.arc_votes) {
    msg::ArcVotesMessage m;
    msg::ArcVotesToIdl(ArcVotesOf(v), &m);
    ctx_->Stamp(m.msg.header, "site");
    Check(votes_writer_.Write(m.msg), "apl/arc_votes");
  }
  for (const MobilityStatus& st : out.statuses) {
    rover_apl_MobilityStatus m{};
    msg::MobilityStatusToIdl(st, &m);
    ctx_->Stamp(m.header, "site");
    Check(status_writer_.Write(m), "apl/mobility_status");
    const CommandCheckpoint next = NextCommandCheckpoint(command_checkpoint_, st);
    if (next != command_checkpoint_) SaveCommandCheckpoint(next);
    if (st.state == State::kFailed || st.state == State::kRejected) {
      log::Warn("mobility command ended", {{"command_id", st.command_id},
                                           {"fault", std::string(msg::MobilityFaultName(st.fault))},
                                           {"message", st.message}});
    }
  }
  UpdateVoRequest();
}

void MobilityService::UpdateVoRequest() {
  const MobilityStatus& st = manager_->status();
  const bool want = st.state == State::kRunning && ModeUsesVisOdom(st.mode);
  if (want == vo_requested_) return;
  rover_dl_VoCommand m{};
  msg::VoCommandToIdl(msg::VoCommand{ctx_->Now(), ctx_->name(), want}, &m);
  ctx_->Stamp(m.header, "");
  const Status written = vo_writer_.Write(m);
  Check(written, "dl/vo_command");
  if (written.ok()) vo_requested_ = want;
}

}  // namespace rover::apl::mobility
