// dl-locomotion: binds DriveExecutor to dl/drive_command, ddl/joint_state, ddl/motor_status and
// dl/pose; publishes ddl/motor_command and dl/drive_status. See locomotion_service.hpp and
// docs/services/dl-locomotion.md.
#include "locomotion_service.hpp"

#include <cmath>
#include <cstring>
#include <string>

#include "rover/base/check.hpp"
#include "rover/base/log.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::dl {
namespace {

template <class A, std::size_t N>
void CopyArray(const double (&src)[N], A& dst) {
  for (std::size_t i = 0; i < N && i < dst.size(); ++i) dst[i] = src[i];
}

bool UsableHealth(rover_SensorHealth h) {
  return h == rover_HEALTH_OK || h == rover_HEALTH_DEGRADED;
}

}  // namespace

// ---- conversions ------------------------------------------------------------------------------

DriveCommand DriveCommandFromIdl(const rover_dl_DriveCommand& m) {
  DriveCommand c;
  c.stamp = Time{m.header.stamp_ns};
  c.command_id = m.command_id;
  c.primitive = static_cast<DrivePrimitive>(static_cast<std::int32_t>(m.primitive));
  c.curvature = m.curvature;
  c.distance = m.distance;
  c.angle = m.angle;
  c.speed = m.speed;
  c.timeout_s = m.timeout_s;
  return c;
}

JointSample JointSampleFromIdl(const rover_ddl_JointState& m) {
  JointSample j;
  j.stamp = Time{m.header.stamp_ns};
  CopyArray(m.wheel_angle, j.wheel_angle);
  CopyArray(m.wheel_rate, j.wheel_rate);
  CopyArray(m.steer_angle, j.steer_angle);
  CopyArray(m.rocker_angle, j.rocker_angle);
  CopyArray(m.bogie_angle, j.bogie_angle);
  j.healthy = UsableHealth(m.health);
  return j;
}

MotorGroupStatus MotorGroupStatusFromIdl(const rover_ddl_MotorStatus& m) {
  MotorGroupStatus s;
  s.stamp = Time{m.header.stamp_ns};
  s.command_id = m.command_id;
  s.state = static_cast<GroupState>(static_cast<std::int32_t>(m.state));
  s.fault = static_cast<MotorFault>(static_cast<std::int32_t>(m.fault));
  s.fault_motor = m.fault_motor;
  s.message.assign(m.message, strnlen(m.message, sizeof(m.message)));
  return s;
}

std::optional<AttitudeSample> AttitudeFromPose(const rover_dl_PoseEstimate& m) {
  const rover_Quaternion& q = m.pose.orientation;
  const Eigen::Quaterniond quat(q.w, q.x, q.y, q.z);
  if (!quat.coeffs().allFinite()) return std::nullopt;
  const double n = quat.norm();
  if (!(n >= 0.5 && n <= 2.0)) return std::nullopt;
  const geometry::Rpy rpy = geometry::RpyFromQuaternion(quat.normalized());
  AttitudeSample a;
  a.stamp = Time{m.header.stamp_ns};
  a.roll = rpy.x();
  a.pitch = rpy.y();
  a.yaw = rpy.z();
  a.healthy = true;
  return a;
}

rover_ddl_MotorCommand MotorCommandToIdl(const MotorGroupCommand& c) {
  rover_ddl_MotorCommand m{};
  m.header.stamp_ns = c.stamp.ns;
  m.command_id = c.command_id;
  m.motor_mask = c.motor_mask;
  m.mode = static_cast<rover_ddl_GroupMode>(static_cast<std::int32_t>(c.mode));
  for (std::size_t i = 0; i < kNumMotors; ++i) {
    m.goal[i] = c.goal[i];
    m.max_rate[i] = c.max_rate[i];
  }
  m.timeout_s = c.timeout_s;
  return m;
}

rover_dl_DriveStatus DriveStatusToIdl(const DriveStatus& s) {
  rover_dl_DriveStatus m{};
  m.header.stamp_ns = s.stamp.ns;
  m.command_id = s.command_id;
  m.primitive = IsKnownPrimitive(s.primitive)
                    ? static_cast<rover_dl_DrivePrimitive>(static_cast<std::int32_t>(s.primitive))
                    : rover_dl_PRIMITIVE_STOP;
  m.state = static_cast<rover_dl_DriveState>(static_cast<std::int32_t>(s.state));
  m.termination = static_cast<rover_dl_DriveTermination>(static_cast<std::int32_t>(s.termination));
  m.distance_done = s.distance_done;
  m.heading_change = s.heading_change;
  dds::CopyString(m.message, s.message);
  return m;
}

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
        const JointSample j = JointSampleFromIdl(s.data());
        if (j.healthy && j.AllFinite()) last_joint_ = j.stamp;
        executor_->OnJointState(j);  // ignores unhealthy, non-finite and out-of-order samples
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_PoseEstimate>(
      "dl/pose", [this](const dds::Sample<rover_dl_PoseEstimate>& s) {
        const std::optional<AttitudeSample> a = AttitudeFromPose(s.data());
        if (!a.has_value()) return;
        last_attitude_ = a->stamp;
        executor_->OnAttitude(*a);
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_MotorStatus>(
      "ddl/motor_status", [this](const dds::Sample<rover_ddl_MotorStatus>& s) {
        executor_->OnMotorStatus(MotorGroupStatusFromIdl(s.data()));
      }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_dl_DriveCommand>(
      "dl/drive_command", [this](const dds::Sample<rover_dl_DriveCommand>& s) {
        const DriveCommand c = DriveCommandFromIdl(s.data());
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
  for (const MotorGroupCommand& c : out.motor_commands) {
    rover_ddl_MotorCommand m = MotorCommandToIdl(c);
    ctx_->Stamp(m.header, "rover");
    m.header.stamp_ns = c.stamp.ns;
    const Status s = motor_writer_.Write(m);
    if (!s.ok()) log::Error("ddl/motor_command write failed", {{"error", s.message()}});
  }
  for (const DriveStatus& st : out.statuses) {
    rover_dl_DriveStatus m = DriveStatusToIdl(st);
    ctx_->Stamp(m.header, "rover");
    m.header.stamp_ns = st.stamp.ns;
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

}  // namespace rover::dl
