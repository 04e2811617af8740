#include "imu_service.hpp"

#include "rover/base/log.hpp"
#include "rover/ddl/driver_support/driver_params.hpp"
#include "rover/msg/health_idl.hpp"
#include "rover/msg/hw_idl.hpp"
#include "rover/msg/sensors_idl.hpp"

namespace rover::ddl::imu {

using driver_support::DeclareDriverHardwareParams;
using driver_support::DriverHardwareConfig;
using driver_support::HealthSummary;
using driver_support::IsLogWorthy;

void ImuService::DeclareParameters(ParamSet& p) {
  DeclareDriverHardwareParams(p);
  p.Declare("stale_after_s", 0.1, "[s] hw/imu not arriving for this long makes the service STALE")
      .Range(0.005, 60.0);
  p.Declare("watchdog_rate_hz", 10.0, "[Hz] how often staleness and health are judged (run clock)")
      .Range(0.5, 1000.0);
  p.Declare("max_future_s", 1.0,
            "[s] hw/imu samples stamped further ahead of the run clock are dropped as corrupt")
      .Range(0.001, 60.0);
}

Status ImuService::ValidateParameters(const ParamSet& p) const {
  auto hw = DriverHardwareConfig(p);
  if (!hw.ok()) return hw.status();
  return ImuDriver::Create(hw->imu).status();
}

Status ImuService::OnConfigure(ServiceContext& ctx, const ParamSet& p) {
  ctx_ = &ctx;
  auto hw = DriverHardwareConfig(p);
  if (!hw.ok()) return hw.status();
  auto driver = ImuDriver::Create(hw->imu);
  if (!driver.ok()) return driver.status();
  driver_.emplace(std::move(*driver));
  input_.emplace("hw/imu", p.GetDouble("stale_after_s"), p.GetDouble("max_future_s"));
  auto w = ctx.MakeWriter<rover_ddl_Imu>("ddl/imu");
  if (!w.ok()) return w.status();
  writer_ = std::move(*w);
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_hw_ImuRaw>(
      "hw/imu", [this](const dds::Sample<rover_hw_ImuRaw>& s) { OnSample(s.data()); }));
  ctx.executor().AddTimer(Seconds(1.0 / p.GetDouble("watchdog_rate_hz")), [this] { OnWatchdog(); });
  ctx.SetHealth(rover_HEALTH_STALE, input_->StaleReason(ctx.Now()));
  return Status::Ok();
}

Time ImuService::Now() {
  const Time now = ctx_->Now();
  if (clock_jump_.WentBack(now, ctx_->clock().valid())) input_->Reset();
  return now;
}

void ImuService::OnSample(const rover_hw_ImuRaw& raw) {
  const Time now = Now();
  const Status s = input_->Accept(raw.header.stamp_ns, now, ctx_->clock().valid());
  if (!s.ok()) {
    if (IsLogWorthy(input_->rejected())) {
      log::Warn("hw/imu sample dropped",
                {{"reason", s.message()}, {"dropped_so_far", input_->rejected()}});
    }
    return;
  }
  const Imu imu = driver_->Convert(msg::ImuRawFromIdl(raw));
  rover_ddl_Imu out{};
  ctx_->Stamp(out.header, "rover");
  msg::ImuToIdl(imu, &out);
  (void)writer_.Write(out);
  if (imu.health != msg::SensorHealth::kOk) {
    since_check_.Worsen(imu.health, "hw/imu: " + imu.health_reason);
    ++unhealthy_samples_;
    if (IsLogWorthy(unhealthy_samples_) || imu.health_reason != last_reason_) {
      log::Warn("IMU sample not healthy", {{"health", msg::SensorHealthName(imu.health)},
                                           {"reason", imu.health_reason},
                                           {"so_far", unhealthy_samples_}});
    }
  }
  last_reason_ = imu.health_reason;
}

void ImuService::OnWatchdog() {
  const Time now = Now();
  HealthSummary h = since_check_;
  since_check_ = {};
  if (input_->Stale(now)) h.Worsen(msg::SensorHealth::kStale, input_->StaleReason(now));
  ctx_->SetHealth(msg::HealthToIdl(h.health), h.reason);
}

}  // namespace rover::ddl::imu
