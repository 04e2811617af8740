#include "sun_service.hpp"

#include "rover/base/log.hpp"
#include "rover/ddl/driver_support/driver_params.hpp"
#include "rover/msg/health_idl.hpp"
#include "rover/msg/hw_idl.hpp"
#include "rover/msg/sensors_idl.hpp"

namespace rover::ddl::sun_sensor {

using driver_support::DeclareDriverHardwareParams;
using driver_support::DriverHardwareConfig;
using driver_support::HealthSummary;
using driver_support::IsLogWorthy;

void SunService::DeclareParameters(ParamSet& p) {
  DeclareDriverHardwareParams(p);
  p.Declare("stale_after_s", 1.5,
            "[s] hw/sun_sensor not arriving for this long makes the service STALE")
      .Range(0.01, 600.0);
  p.Declare("watchdog_rate_hz", 4.0, "[Hz] how often staleness and health are judged (run clock)")
      .Range(0.1, 100.0);
  p.Declare("max_future_s", 1.0,
            "[s] hw/sun_sensor samples stamped further ahead of the run clock are dropped")
      .Range(0.001, 60.0);
}

Status SunService::ValidateParameters(const ParamSet& p) const {
  auto hw = DriverHardwareConfig(p);
  if (!hw.ok()) return hw.status();
  return SunSensorDriver::Create(hw->sun_sensor).status();
}

Status SunService::OnConfigure(ServiceContext& ctx, const ParamSet& p) {
  ctx_ = &ctx;
  auto hw = DriverHardwareConfig(p);
  if (!hw.ok()) return hw.status();
  auto driver = SunSensorDriver::Create(hw->sun_sensor);
  if (!driver.ok()) return driver.status();
  driver_.emplace(std::move(*driver));
  input_.emplace("hw/sun_sensor", p.GetDouble("stale_after_s"), p.GetDouble("max_future_s"));
  auto w = ctx.MakeWriter<rover_ddl_SunSensor>("ddl/sun_sensor");
  if (!w.ok()) return w.status();
  writer_ = std::move(*w);
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_hw_SunSensorRaw>(
      "hw/sun_sensor",
      [this](const dds::Sample<rover_hw_SunSensorRaw>& s) { OnSample(s.data()); }));
  ctx.executor().AddTimer(Seconds(1.0 / p.GetDouble("watchdog_rate_hz")), [this] { OnWatchdog(); });
  ctx.SetHealth(rover_HEALTH_STALE, input_->StaleReason(ctx.Now()));
  return Status::Ok();
}

Time SunService::Now() {
  const Time now = ctx_->Now();
  if (clock_jump_.WentBack(now, ctx_->clock().valid())) input_->Reset();
  return now;
}

void SunService::OnSample(const rover_hw_SunSensorRaw& raw) {
  const Time now = Now();
  const Status s = input_->Accept(raw.header.stamp_ns, now, ctx_->clock().valid());
  if (!s.ok()) {
    if (IsLogWorthy(input_->rejected())) {
      log::Warn("hw/sun_sensor sample dropped",
                {{"reason", s.message()}, {"dropped_so_far", input_->rejected()}});
    }
    return;
  }
  const SunSensor sun = driver_->Convert(msg::SunSensorRawFromIdl(raw));
  rover_ddl_SunSensor out{};
  ctx_->Stamp(out.header, "rover");
  msg::SunSensorToIdl(sun, &out);
  (void)writer_.Write(out);
  if (sun.health != msg::SensorHealth::kOk) {
    since_check_.Worsen(sun.health, "hw/sun_sensor: " + sun.reason);
    ++unhealthy_samples_;
    if (IsLogWorthy(unhealthy_samples_) || sun.reason != last_reason_) {
      log::Warn("sun sensor sample not healthy", {{"health", msg::SensorHealthName(sun.health)},
                                                  {"reason", sun.reason},
                                                  {"so_far", unhealthy_samples_}});
    }
  }
  last_reason_ = sun.health != msg::SensorHealth::kOk ? sun.reason : std::string();
}

void SunService::OnWatchdog() {
  const Time now = Now();
  HealthSummary h = since_check_;
  since_check_ = {};
  if (input_->Stale(now)) h.Worsen(msg::SensorHealth::kStale, input_->StaleReason(now));
  ctx_->SetHealth(msg::HealthToIdl(h.health), h.reason);
}

}  // namespace rover::ddl::sun_sensor
