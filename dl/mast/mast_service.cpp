// dl-mast: binds MastExecutor to dl/mast_command, ddl/joint_state, ddl/motor_status and dl/pose;
// publishes ddl/motor_command and dl/mast_status. See mast_service.hpp and
// docs/services/dl-mast.md.
#include "mast_service.hpp"

#include <cmath>
#include <cstring>
#include <string>

#include "rover/base/check.hpp"
#include "rover/base/log.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/dl/locomotion/drive_types.hpp"

namespace rover::dl::mast {

// ---- conversions ------------------------------------------------------------------------------

MastCommand MastCommandFromIdl(const rover_dl_MastCommand& m) {
  MastCommand c;
  c.command_id = m.command_id;
  c.pointing = static_cast<MastPointing>(static_cast<std::int32_t>(m.pointing));
  c.pan = m.pan;
  c.tilt = m.tilt;
  c.look_at = Eigen::Vector3d(m.look_at.x, m.look_at.y, m.look_at.z);
  c.timeout_s = m.timeout_s;
  return c;
}

MastJoints MastJointsFromIdl(const rover_ddl_JointState& m) {
  MastJoints j;
  j.stamp = Time{m.header.stamp_ns};
  j.pan = m.mast_pan;
  j.tilt = m.mast_tilt;
  j.healthy = m.health == rover_HEALTH_OK || m.health == rover_HEALTH_DEGRADED;
  return j;
}

std::optional<RoverPose> RoverPoseFromIdl(const rover_dl_PoseEstimate& m) {
  const rover_Quaternion& q = m.pose.orientation;
  const Eigen::Quaterniond quat(q.w, q.x, q.y, q.z);
  const Eigen::Vector3d t(m.pose.position.x, m.pose.position.y, m.pose.position.z);
  if (!quat.coeffs().allFinite() || !t.allFinite()) return std::nullopt;
  const double n = quat.norm();
  if (!(n >= 0.5 && n <= 2.0)) return std::nullopt;
  RoverPose p;
  p.stamp = Time{m.header.stamp_ns};
  p.site_from_rover = Eigen::Isometry3d::Identity();
  p.site_from_rover.linear() = quat.normalized().toRotationMatrix();
  p.site_from_rover.translation() = t;
  return p;
}

MotorReport MotorReportFromIdl(const rover_ddl_MotorStatus& m) {
  MotorReport r;
  r.command_id = m.command_id;
  r.state = static_cast<MotorGroupState>(static_cast<std::int32_t>(m.state));
  r.fault_motor = m.fault_motor;
  if (m.fault != rover_ddl_MOTOR_FAULT_NONE) {
    r.fault = dl::MotorFaultName(static_cast<dl::MotorFault>(static_cast<std::int32_t>(m.fault)));
  }
  r.message.assign(m.message, strnlen(m.message, sizeof(m.message)));
  return r;
}

rover_ddl_MotorCommand MotorCommandToIdl(const MastMotorCommand& c) {
  rover_ddl_MotorCommand m{};
  m.header.stamp_ns = c.stamp.ns;
  m.command_id = c.command_id;
  m.motor_mask = c.motor_mask;
  m.mode = static_cast<rover_ddl_GroupMode>(static_cast<std::int32_t>(c.mode));
  m.goal[hw::kMastPan] = c.pan_goal;
  m.goal[hw::kMastTilt] = c.tilt_goal;
  m.max_rate[hw::kMastPan] = c.max_rate;
  m.max_rate[hw::kMastTilt] = c.max_rate;
  m.timeout_s = 0.0;  // the motor driver derives it from the planned move
  return m;
}

rover_dl_MastStatus MastStatusToIdl(const MastStatus& s) {
  rover_dl_MastStatus m{};
  m.header.stamp_ns = s.stamp.ns;
  m.command_id = s.command_id;
  m.state = static_cast<rover_dl_MastState>(static_cast<std::int32_t>(s.state));
  m.pan = s.pan;
  m.tilt = s.tilt;
  m.pan_goal = s.pan_goal;
  m.tilt_goal = s.tilt_goal;
  dds::CopyString(m.message, s.message);
  return m;
}

// ---- service ----------------------------------------------------------------------------------

void MastService::DeclareParameters(ParamSet& params) {
  DeclareParams<hwconfig::RoverDescription>(params, "geometry.");
  DeclareParams<MastOptions>(params, "mast.");
}

Status MastService::ValidateParameters(const ParamSet& params) const {
  ROVER_ASSIGN_OR_RETURN(const hwconfig::RoverDescription rover,
                         ReadParams<hwconfig::RoverDescription>(params, "geometry."));
  ROVER_ASSIGN_OR_RETURN(const MastOptions options, ReadParams<MastOptions>(params, "mast."));
  return MastExecutor::Create(rover, options).status();
}

Status MastService::OnConfigure(ServiceContext& ctx, const ParamSet& params) {
  ctx_ = &ctx;
  ROVER_ASSIGN_OR_RETURN(rover_, ReadParams<hwconfig::RoverDescription>(params, "geometry."));
  ROVER_ASSIGN_OR_RETURN(options_, ReadParams<MastOptions>(params, "mast."));
  ROVER_ASSIGN_OR_RETURN(MastExecutor executor, MastExecutor::Create(rover_, options_));
  executor_.emplace(std::move(executor));

  ROVER_ASSIGN_OR_RETURN(motor_writer_,
                         ctx.MakeWriter<rover_ddl_MotorCommand>("ddl/motor_command"));
  ROVER_ASSIGN_OR_RETURN(status_writer_, ctx.MakeWriter<rover_dl_MastStatus>("dl/mast_status"));

  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_JointState>(
      "ddl/joint_state", [this](const dds::Sample<rover_ddl_JointState>& s) {
        executor_->OnJoints(MastJointsFromIdl(s.data()));
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_PoseEstimate>(
      "dl/pose", [this](const dds::Sample<rover_dl_PoseEstimate>& s) {
        const std::optional<RoverPose> p = RoverPoseFromIdl(s.data());
        if (p.has_value()) executor_->OnPose(*p);
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_MotorStatus>(
      "ddl/motor_status", [this](const dds::Sample<rover_ddl_MotorStatus>& s) {
        Publish(executor_->OnMotorStatus(MotorReportFromIdl(s.data()), ctx_->Now()));
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_MastCommand>(
      "dl/mast_command", [this](const dds::Sample<rover_dl_MastCommand>& s) {
        const MastCommand c = MastCommandFromIdl(s.data());
        const MastOutput out = executor_->Submit(c, ctx_->Now());
        for (const MastStatus& st : out.statuses) {
          if (st.state == MastState::kRejected) {
            log::Warn("mast command rejected",
                      {{"command_id", c.command_id}, {"reason", st.message}});
          }
        }
        Publish(out);
      }));
  ctx.executor().AddTimer(Seconds(1.0 / options_.check_rate_hz), [this] { OnTimer(); });
  ctx.SetHealth(rover_HEALTH_DEGRADED, "waiting for ddl/joint_state");
  return Status::Ok();
}

Status MastService::OnActivate(ServiceContext&) {
  MastOutput out;
  out.statuses.push_back(executor_->status());  // IDLE (or the latest state after a restart)
  out.statuses.back().stamp = ctx_->Now();
  Publish(out);
  return Status::Ok();
}

Status MastService::OnDeactivate(ServiceContext&) {
  Publish(executor_->Stop("service deactivated", ctx_->Now()));
  return Status::Ok();
}

void MastService::Publish(const MastOutput& out) {
  for (const MastMotorCommand& c : out.motor_commands) {
    rover_ddl_MotorCommand m = MotorCommandToIdl(c);
    ctx_->Stamp(m.header, "rover");
    m.header.stamp_ns = c.stamp.ns;
    const Status s = motor_writer_.Write(m);
    if (!s.ok()) log::Error("ddl/motor_command write failed", {{"error", s.message()}});
  }
  for (const MastStatus& st : out.statuses) {
    rover_dl_MastStatus m = MastStatusToIdl(st);
    ctx_->Stamp(m.header, "rover");
    m.header.stamp_ns = st.stamp.ns;
    const Status s = status_writer_.Write(m);
    if (!s.ok()) log::Error("dl/mast_status write failed", {{"error", s.message()}});
    if (st.state == MastState::kFault) {
      log::Warn("mast move failed", {{"command_id", st.command_id}, {"reason", st.message}});
    }
  }
}

void MastService::OnTimer() {
  const Time now = ctx_->Now();
  if (last_timer_.has_value() && now < *last_timer_) {
    // The run clock went back (simulator reset): the stored inputs belong to another run.
    Publish(executor_->Stop("run clock went back", now));
    auto executor = MastExecutor::Create(rover_, options_);
    ROVER_DEMAND(executor.ok());  // the same description and options were valid at configuration
    executor_.emplace(std::move(*executor));
    log::Info("run clock went back; mast executor restarted");
  }
  last_timer_ = now;
  Publish(executor_->Step(now));
  if (executor_->JointsFresh(now)) {
    ctx_->SetHealth(rover_HEALTH_OK, "");
  } else {
    ctx_->SetHealth(rover_HEALTH_DEGRADED, "no fresh ddl/joint_state: mast commands are refused");
  }
}

}  // namespace rover::dl::mast
