// dl-locomotion: binds DriveExecutor to dl/drive_command, ddl/joint_state, ddl/motor_status and
// dl/pose; publishes ddl/motor_command and dl/drive_status. See locomotion_service.hpp and
// docs/services/dl-locomotion.md.
#include "locomotion_service.hpp"

#include <string>

#include "rover/base/check.hpp"
#include "rover/base/log.hpp"
#include "rover/msg/drive_idl.hpp"
#include "rover/msg/motor_idl.hpp"
#include "rover/msg/pose_idl.hpp"
#include "rover/msg/sensors_idl.hpp"

namespace rover::dl::locomotion {

// ---- service ----------------------------------------------------------------------------------

void LocomotionService::DeclareParameters(ParamSet& params) {
  DeclareRoverGeometryParams(params, "geometry.");
  DeclareDriveParams(params, "drive.");
}

Status LocomotionService::ValidateParameters(const ParamSet& params) const {
  auto geometry = RoverGeometryFromParams(params, "geometry.");
  if (!geometry.ok()) return geometry.status();
  auto options = DriveOptionsFromParams(params, "drive.");
  return options.ok() ? Status::Ok() : options.status();
}

Status LocomotionService::OnConfigure(ServiceContext& ctx, const ParamSet& params) {
  ctx_ = &ctx;
  auto geometry = RoverGeometryFromParams(params, "geometry.");
  if (!geometry.ok()) return geometry.status();
  auto options = DriveOptionsFromParams(params, "drive.");
  if (!options.ok()) return options.status();
  geometry_ = *geometry;
  options_ = *options;
  auto executor = DriveExecutor::Create(geometry_, options_);
  if (!executor.ok()) return executor.status();
  executor_.emplace(std::move(*executor));

  auto mw = ctx.MakeWriter<rover_ddl_MotorCommand>("ddl/motor_command");
  if (!mw.ok()) return mw.status();
  motor_writer_ = std::move(*mw);
  auto sw = ctx.MakeWriter<rover_dl_DriveStatus>("dl/drive_status");
  if (!sw.ok()) return sw.status();
  status_writer_ = std::move(*sw);

  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_JointState>(
      "ddl/joint_state", [this](const dds::Sample<rover_ddl_JointState>& s) {
        const auto j = msg::JointStateFromIdl(s.data());
        if (!j.ok()) return j.status();  // an unknown health value: not usable
        if (!j->AllFinite()) return InvalidArgument("a joint angle or rate is not finite");
        // Ignores unhealthy and out-of-order samples; refuses encoder jumps (rejected input).
        if (Status used = executor_->OnJointState(*j); !used.ok()) return used;
        if (msg::IsUsable(j->health)) last_joint_ = j->stamp;
        return Status::Ok();
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_PoseEstimate>(
      "dl/pose", [this](const dds::Sample<rover_dl_PoseEstimate>& s) {
        const auto a = msg::AttitudeSampleFromIdl(s.data());
        if (!a.ok()) return a.status();  // a degenerate quaternion
        last_attitude_ = a->stamp;
        executor_->OnAttitude(*a);
        return Status::Ok();
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_MotorStatus>(
      "ddl/motor_status", [this](const dds::Sample<rover_ddl_MotorStatus>& s) {
        const auto m = msg::MotorStatusFromIdl(s.data());
        if (!m.ok()) return m.status();
        executor_->OnMotorStatus(*m);
        return Status::Ok();
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_DriveCommand>(
      "dl/drive_command", [this](const dds::Sample<rover_dl_DriveCommand>& s) {
        const DriveCommand c = msg::DriveCommandFromIdl(s.data());
        const DriveOutput out = executor_->Submit(c, ctx_->Now());
        for (const DriveStatus& st : out.statuses) {
          if (st.command_id == c.command_id && st.state == DriveState::kRejected) {
            log::Warn("drive command rejected",
                      {{"command_id", c.command_id},
                       {"termination", DriveTerminationName(st.termination)},
                       {"reason", st.message}});
          }
        }
        Publish(out);
      }));
  ctx.executor().AddTimer(Seconds(1.0 / options_.check_rate_hz), [this] { OnTimer(); });
  ctx.SetHealth(rover_HEALTH_DEGRADED, "waiting for ddl/joint_state and dl/pose");
  return Status::Ok();
}

Status LocomotionService::OnDeactivate(ServiceContext&) {
  StopRunning("service deactivated");
  return Status::Ok();
}

void LocomotionService::Publish(const DriveOutput& out) {
  for (const msg::MotorCommand& c : out.motor_commands) {
    rover_ddl_MotorCommand m{};
    ctx_->Stamp(m.header, "rover");
    msg::MotorCommandToIdl(c, &m);  // stamp = the command's run-clock time
    const Status s = motor_writer_.Write(m);
    if (!s.ok()) log::Error("ddl/motor_command write failed", {{"error", s.message()}});
  }
  for (const DriveStatus& st : out.statuses) {
    rover_dl_DriveStatus m{};
    ctx_->Stamp(m.header, "rover");
    msg::DriveStatusToIdl(st, &m);
    const Status s = status_writer_.Write(m);
    if (!s.ok()) log::Error("dl/drive_status write failed", {{"error", s.message()}});
    if (st.state == DriveState::kFailed) {
      log::Warn("drive primitive failed", {{"command_id", st.command_id},
                                           {"termination", DriveTerminationName(st.termination)},
                                           {"reason", st.message}});
    }
  }
}

void LocomotionService::StopRunning(const char* why) {
  if (!executor_.has_value() || !executor_->busy()) return;
  log::Warn("stopping the running drive primitive", {{"reason", why}});
  DriveCommand stop;
  stop.command_id = 0;
  stop.primitive = DrivePrimitive::kStop;
  Publish(executor_->Submit(stop, ctx_->Now()));
}

void LocomotionService::OnTimer() {
  const Time now = ctx_->Now();
  if (last_timer_.has_value() && now < *last_timer_) {
    // The run clock went back (simulator reset): the stored inputs belong to another run.
    StopRunning("run clock went back");
    auto executor = DriveExecutor::Create(geometry_, options_);
    ROVER_DEMAND(executor.ok());  // the same geometry and options were valid at configuration
    executor_.emplace(std::move(*executor));
    last_joint_.reset();
    last_attitude_.reset();
    log::Info("run clock went back; drive executor restarted");
  }
  last_timer_ = now;
  Publish(executor_->Step(now));
  UpdateHealth(now);
}

void LocomotionService::UpdateHealth(Time now) {
  std::string missing;
  if (!last_joint_.has_value() || ToSeconds(now - *last_joint_) > options_.joint_stale_s) {
    missing = "ddl/joint_state";
  }
  if (!last_attitude_.has_value() || ToSeconds(now - *last_attitude_) > options_.attitude_stale_s) {
    missing += missing.empty() ? "dl/pose" : " and dl/pose";
  }
  if (missing.empty()) {
    ctx_->SetHealth(rover_HEALTH_OK, "");
  } else {
    ctx_->SetHealth(rover_HEALTH_DEGRADED, "no fresh " + missing + ": drive commands are refused");
  }
}

}  // namespace rover::dl::locomotion
