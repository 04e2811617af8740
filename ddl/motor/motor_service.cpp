#include "motor_service.hpp"

#include "rover/base/log.hpp"
#include "rover/ddl/driver_support/driver_params.hpp"
#include "rover/msg/health_idl.hpp"
#include "rover/msg/hw_idl.hpp"
#include "rover/msg/motor_idl.hpp"

namespace rover::ddl::motor {

using driver_support::DeclareDriverHardwareParams;
using driver_support::DriverHardwareConfig;
using driver_support::HealthSummary;
using driver_support::IsLogWorthy;

void MotorService::DeclareParameters(ParamSet& p) {
  DeclareDriverHardwareParams(p);
  DeclareMotorManagerParams(p, "motor_manager");
  p.Declare("status_rate_hz", 8.0,
            "[Hz] monitor tick and ddl/motor_status publication rate (run clock)")
      .Range(1.0, 100.0);
  p.Declare("max_future_s", 1.0,
            "[s] hw/motor_telemetry stamped further ahead of the run clock is dropped as corrupt")
      .Range(0.001, 60.0);
}

Status MotorService::ValidateParameters(const ParamSet& p) const {
  auto hw = DriverHardwareConfig(p);
  if (!hw.ok()) return hw.status();
  auto options = MotorManagerOptionsFromParams(p, "motor_manager");
  if (!options.ok()) return options.status();
  return MotorGroupManager::Create(*hw, *options).status();
}

Status MotorService::OnConfigure(ServiceContext& ctx, const ParamSet& p) {
  ctx_ = &ctx;
  auto hw = DriverHardwareConfig(p);
  if (!hw.ok()) return hw.status();
  auto options = MotorManagerOptionsFromParams(p, "motor_manager");
  if (!options.ok()) return options.status();
  auto manager = MotorGroupManager::Create(*hw, *options);
  if (!manager.ok()) return manager.status();
  manager_.emplace(std::move(*manager));
  telemetry_.emplace("hw/motor_telemetry", options->telemetry_timeout_s,
                     p.GetDouble("max_future_s"));

  auto gw = ctx.MakeWriter<rover_hw_MotorGoals>("hw/motor_goals");
  if (!gw.ok()) return gw.status();
  goals_writer_ = std::move(*gw);
  auto sw = ctx.MakeWriter<rover_ddl_MotorStatus>("ddl/motor_status");
  if (!sw.ok()) return sw.status();
  status_writer_ = std::move(*sw);

  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_ddl_MotorCommand>(
      "ddl/motor_command",
      [this](const dds::Sample<rover_ddl_MotorCommand>& s) { OnCommand(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_hw_MotorTelemetry>(
      "hw/motor_telemetry",
      [this](const dds::Sample<rover_hw_MotorTelemetry>& s) { OnTelemetry(s.data()); }));
  ctx.executor().AddTimer(Seconds(1.0 / p.GetDouble("status_rate_hz")), [this] { OnTick(); });
  ctx.SetHealth(rover_HEALTH_STALE, telemetry_->StaleReason(ctx.Now()));
  return Status::Ok();
}

Status MotorService::OnDeactivate(ServiceContext& ctx) {
  if (manager_) Publish(manager_->StopAll(ctx.Now(), "ddl-motor deactivated"));
  return Status::Ok();
}

Time MotorService::Now() {
  const Time now = ctx_->Now();
  if (clock_jump_.WentBack(now, ctx_->clock().valid())) {
    log::Warn("run clock went back (simulator reset): stopping every motor group",
              {{"now_s", now.seconds()}});
    Publish(manager_->StopAll(now, "run clock went back (simulator reset)"));
    manager_->ForgetTelemetry();
    telemetry_->Reset();
  }
  return now;
}

void MotorService::OnCommand(const rover_ddl_MotorCommand& command) {
  const Time now = Now();
  const ManagerOutput out = manager_->HandleCommand(msg::MotorCommandFromIdl(command), now);
  for (const MotorStatus& s : out.statuses) {
    if (s.state == GroupState::kRejected) {
      log::Warn("motor command rejected", {{"command_id", s.command_id},
                                           {"error", CommandErrorName(s.error)},
                                           {"reason", s.message}});
    }
  }
  Publish(out);
}

void MotorService::OnTelemetry(const rover_hw_MotorTelemetry& telemetry) {
  const Time now = Now();
  const Status s = telemetry_->Accept(telemetry.header.stamp_ns, now, ctx_->clock().valid());
  if (!s.ok()) {
    if (IsLogWorthy(telemetry_->rejected())) {
      log::Warn("motor telemetry dropped",
                {{"reason", s.message()}, {"dropped_so_far", telemetry_->rejected()}});
    }
    return;
  }
  Publish(manager_->HandleTelemetry(msg::MotorTelemetryFromIdl(telemetry), now));
}

void MotorService::OnTick() {
  const Time now = Now();
  Publish(manager_->Tick(now));
  UpdateHealth(now);
}

void MotorService::Publish(const ManagerOutput& out) {
  // Goals first: a consumer that sees RUNNING can rely on the goals being on their way.
  if (out.goals) {
    rover_hw_MotorGoals g{};
    ctx_->Stamp(g.header, "rover");
    msg::MotorGoalsToIdl(*out.goals, &g);
    const Status s = goals_writer_.Write(g);
    if (!s.ok()) {
      write_error_ = s.message();
      log::Error("cannot send motor goals", {{"error", s.message()}});
    } else {
      write_error_.clear();
    }
  }
  for (const MotorStatus& status : out.statuses) {
    rover_ddl_MotorStatus m{};
    ctx_->Stamp(m.header, "rover");
    msg::MotorStatusToIdl(status, &m);
    (void)status_writer_.Write(m);
  }
}

void MotorService::UpdateHealth(Time now) {
  HealthSummary h;
  if (telemetry_->Stale(now)) h.Worsen(msg::SensorHealth::kStale, telemetry_->StaleReason(now));
  if (!write_error_.empty()) h.Worsen(msg::SensorHealth::kFailed, write_error_);
  ctx_->SetHealth(msg::HealthToIdl(h.health), h.reason);
}

}  // namespace rover::ddl::motor
