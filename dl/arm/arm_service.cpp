// dl-arm: binds ArmExecutor to dl/arm_command, ddl/joint_state, ddl/motor_status and
// ddl/mi_frame; publishes ddl/motor_command, ddl/mi_request and dl/arm_status. See arm_service.hpp and docs/services/dl-arm.md.
#include "arm_service.hpp"

#include <string>

#include "rover/base/check.hpp"
#include "rover/base/log.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/msg/arm_idl.hpp"
#include "rover/msg/camera_idl.hpp"
#include "rover/msg/motor_idl.hpp"
#include "rover/msg/sensors_idl.hpp"

namespace rover::dl::arm {

// ---- service ----------------------------------------------------------------------------------

void ArmService::DeclareParameters(ParamSet& params) {
  DeclareParams<hwconfig::RoverDescription>(params, "geometry.");
  DeclareParams<ArmOptions>(params, "arm.");
}

Status ArmService::ValidateParameters(const ParamSet& params) const {
  ROVER_ASSIGN_OR_RETURN(const hwconfig::RoverDescription rover,
                         ReadParams<hwconfig::RoverDescription>(params, "geometry."));
  ROVER_ASSIGN_OR_RETURN(const ArmOptions options, ReadParams<ArmOptions>(params, "arm."));
  return ArmExecutor::Create(rover, options).status();
}

Status ArmService::OnConfigure(ServiceContext& ctx, const ParamSet& params) {
  ctx_ = &ctx;
  ROVER_ASSIGN_OR_RETURN(rover_, ReadParams<hwconfig::RoverDescription>(params, "geometry."));
  ROVER_ASSIGN_OR_RETURN(options_, ReadParams<ArmOptions>(params, "arm."));
  ROVER_ASSIGN_OR_RETURN(ArmExecutor executor, ArmExecutor::Create(rover_, options_));
  executor_.emplace(std::move(executor));

  ROVER_ASSIGN_OR_RETURN(motor_writer_,
                         ctx.MakeWriter<rover_ddl_MotorCommand>("ddl/motor_command"));
  ROVER_ASSIGN_OR_RETURN(status_writer_, ctx.MakeWriter<rover_dl_ArmStatus>("dl/arm_status"));
  ROVER_ASSIGN_OR_RETURN(mi_writer_, ctx.MakeWriter<rover_ddl_MiRequest>("ddl/mi_request"));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_MiFrame>(
      "ddl/mi_frame", [this](const dds::Sample<rover_ddl_MiFrame>& s) {
        const auto frame = msg::MiFrameFromIdl(s.data());
        if (!frame.ok()) return frame.status();  // on sys/health through the input monitor
        Publish(executor_->OnMiFrame(*frame, ctx_->Now()));
        return Status::Ok();
      }));

  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_JointState>(
      "ddl/joint_state", [this](const dds::Sample<rover_ddl_JointState>& s) {
        const auto joints = msg::JointStateFromIdl(s.data());
        if (!joints.ok()) return joints.status();  // an unreadable one is not fresh
        Publish(executor_->OnJoints(*joints));
        return Status::Ok();
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_MotorStatus>(
      "ddl/motor_status", [this](const dds::Sample<rover_ddl_MotorStatus>& s) {
        const auto status = msg::MotorStatusFromIdl(s.data());
        if (!status.ok()) return status.status();  // on sys/health through the input monitor
        Publish(executor_->OnMotorStatus(*status, ctx_->Now()));
        return Status::Ok();
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_ArmCommand>(
      "dl/arm_command", [this](const dds::Sample<rover_dl_ArmCommand>& s) {
        const ArmCommand c = msg::ArmCommandFromIdl(s.data());
        const ArmOutput out = executor_->Submit(c, ctx_->Now());
        for (const ArmStatus& st : out.statuses) {
          if (st.state == ArmState::kRejected) {
            log::Warn("arm command rejected",
                      {{"command_id", c.command_id}, {"reason", st.message}});
          }
        }
        Publish(out);
      }));
  ctx.executor().AddTimer(Seconds(1.0 / options_.check_rate_hz), [this] { OnTimer(); });
  ctx.SetHealth(rover_HEALTH_DEGRADED, "waiting for ddl/joint_state");
  return Status::Ok();
}

Status ArmService::OnActivate(ServiceContext&) {
  ArmOutput out;
  out.statuses.push_back(executor_->status());  // IDLE (or the latest state after a restart)
  out.statuses.back().stamp = ctx_->Now();
  Publish(out);
  return Status::Ok();
}

Status ArmService::OnDeactivate(ServiceContext&) {
  Publish(executor_->Stop("service deactivated", ctx_->Now()));
  return Status::Ok();
}

void ArmService::Publish(const ArmOutput& out) {
  for (const msg::MotorCommand& c : out.motor_commands) {
    rover_ddl_MotorCommand m{};
    msg::MotorCommandToIdl(c, &m);
    ctx_->Stamp(m.header, "rover");
    m.header.stamp_ns = c.stamp.ns;
    const Status s = motor_writer_.Write(m);
    if (!s.ok()) log::Error("ddl/motor_command write failed", {{"error", s.message()}});
  }
  for (const msg::MiRequest& r : out.mi_requests) {
    rover_ddl_MiRequest m{};
    msg::MiRequestToIdl(r, &m);
    ctx_->Stamp(m.header, "rover");
    m.header.stamp_ns = r.stamp.ns;
    const Status s = mi_writer_.Write(m);
    if (!s.ok()) log::Error("ddl/mi_request write failed", {{"error", s.message()}});
  }
  for (const ArmStatus& st : out.statuses) {
    rover_dl_ArmStatus m{};
    msg::ArmStatusToIdl(st, &m);
    ctx_->Stamp(m.header, "rover");
    m.header.stamp_ns = st.stamp.ns;
    const Status s = status_writer_.Write(m);
    if (!s.ok()) log::Error("dl/arm_status write failed", {{"error", s.message()}});
    if (st.state == ArmState::kFault) {
      log::Warn("arm command failed", {{"command_id", st.command_id}, {"reason", st.message}});
    }
  }
}

void ArmService::OnTimer() {
  const Time now = ctx_->Now();
  if (last_timer_.has_value() && now < *last_timer_) {
    // The run clock went back (simulator reset): the stored inputs belong to another run.
    Publish(executor_->Stop("run clock went back", now));
    auto executor = ArmExecutor::Create(rover_, options_);
    ROVER_DEMAND(executor.ok());  // the same description and options were valid at configuration
    executor_.emplace(std::move(*executor));
    log::Info("run clock went back; arm executor restarted");
  }
  last_timer_ = now;
  Publish(executor_->Step(now));
  if (executor_->JointsFresh(now)) {
    ctx_->SetHealth(rover_HEALTH_OK, "");
  } else {
    ctx_->SetHealth(rover_HEALTH_DEGRADED, "no fresh ddl/joint_state: arm commands are refused");
  }
}

}  // namespace rover::dl::arm
