#include "joints_service.hpp"

#include "rover/base/check.hpp"
#include "rover/base/log.hpp"
#include "rover/ddl/driver_support/driver_params.hpp"
#include "rover/msg/health_idl.hpp"
#include "rover/msg/hw_idl.hpp"
#include "rover/msg/sensors_idl.hpp"

namespace rover::ddl::joints {

using driver_support::DeclareDriverHardwareParams;
using driver_support::DriverHardwareConfig;
using driver_support::HealthSummary;
using driver_support::InputMonitor;
using driver_support::IsLogWorthy;

namespace {

void WarnDropped(const InputMonitor& m, const Status& s) {
  if (IsLogWorthy(m.rejected())) {
    log::Warn("input sample dropped",
              {{"topic", m.name()}, {"reason", s.message()}, {"dropped_so_far", m.rejected()}});
  }
}

}  // namespace

void JointsService::DeclareParameters(ParamSet& p) {
  DeclareDriverHardwareParams(p);
  const JointReaderOptions d;
  p.Declare("rate_hz", 50.0, "[Hz] ddl/joint_state publication rate (run clock)")
      .Range(1.0, 1000.0);
  p.Declare("joint_reader.rate_window_s", d.rate_window_s,
            "[s] least-squares window of the wheel-rate estimate")
      .Range(0.01, 5.0);
  p.Declare("joint_reader.stale_after_s", d.stale_after_s,
            "[s] an input older than this makes ddl/joint_state STALE")
      .Range(0.005, 60.0);
  p.Declare("joint_reader.pot_limit_margin", d.pot_limit_margin,
            "[rad] a rocker/bogie pot beyond its mechanical stop by more than this: DEGRADED")
      .Range(0.001, 1.0);
  p.Declare("joint_reader.joint_limit_margin", d.joint_limit_margin,
            "[rad] a steering/mast angle beyond its limits by more than this: DEGRADED")
      .Range(0.001, 1.0);
  p.Declare("max_future_s", 1.0,
            "[s] input samples stamped further ahead of the run clock are dropped as corrupt")
      .Range(0.001, 60.0);
}

namespace {
JointReaderOptions ReaderOptions(const ParamSet& p) {
  JointReaderOptions o;
  o.rate_window_s = p.GetDouble("joint_reader.rate_window_s");
  o.stale_after_s = p.GetDouble("joint_reader.stale_after_s");
  o.pot_limit_margin = p.GetDouble("joint_reader.pot_limit_margin");
  o.joint_limit_margin = p.GetDouble("joint_reader.joint_limit_margin");
  return o;
}
}  // namespace

Status JointsService::ValidateParameters(const ParamSet& p) const {
  auto hw = DriverHardwareConfig(p);
  if (!hw.ok()) return hw.status();
  return JointReader::Create(*hw, ReaderOptions(p)).status();
}

Status JointsService::OnConfigure(ServiceContext& ctx, const ParamSet& p) {
  ctx_ = &ctx;
  auto hw = DriverHardwareConfig(p);
  if (!hw.ok()) return hw.status();
  hardware_ = *hw;
  options_ = ReaderOptions(p);
  auto reader = JointReader::Create(hardware_, options_);
  if (!reader.ok()) return reader.status();
  reader_.emplace(std::move(*reader));
  const double max_future = p.GetDouble("max_future_s");
  telemetry_.emplace("hw/motor_telemetry", options_.stale_after_s, max_future);
  pots_.emplace("hw/suspension_pots", options_.stale_after_s, max_future);
  contact_.emplace("hw/arm_contact", options_.stale_after_s, max_future);

  auto w = ctx.MakeWriter<rover_ddl_JointState>("ddl/joint_state");
  if (!w.ok()) return w.status();
  writer_ = std::move(*w);
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_hw_MotorTelemetry>(
      "hw/motor_telemetry",
      [this](const dds::Sample<rover_hw_MotorTelemetry>& s) { return OnTelemetry(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_hw_SuspensionPots>(
      "hw/suspension_pots",
      [this](const dds::Sample<rover_hw_SuspensionPots>& s) { return OnPots(s.data()); }));
  ROVER_RETURN_IF_ERROR(ctx.Subscribe<rover_hw_ArmContact>(
      "hw/arm_contact",
      [this](const dds::Sample<rover_hw_ArmContact>& s) { return OnContact(s.data()); }));
  ctx.executor().AddTimer(Seconds(1.0 / p.GetDouble("rate_hz")), [this] { OnTimer(); });
  ctx.SetHealth(rover_HEALTH_STALE, telemetry_->StaleReason(ctx.Now()));
  return Status::Ok();
}

Time JointsService::Now() {
  const Time now = ctx_->Now();
  if (clock_jump_.WentBack(now, ctx_->clock().valid())) {
    log::Warn("run clock went back (simulator reset): joint reader restarted",
              {{"now_s", now.seconds()}});
    auto fresh = JointReader::Create(hardware_, options_);
    ROVER_DEMAND(fresh.ok());  // accepted at configure time
    reader_.emplace(std::move(*fresh));
    telemetry_->Reset();
    pots_->Reset();
    contact_->Reset();
  }
  return now;
}

Status JointsService::OnTelemetry(const rover_hw_MotorTelemetry& t) {
  const Time now = Now();
  const Status s = telemetry_->Accept(t.header.stamp_ns, now, ctx_->clock().valid());
  if (!s.ok()) {
    WarnDropped(*telemetry_, s);
    return s;
  }
  reader_->OnMotorTelemetry(msg::MotorTelemetryFromIdl(t));
  return Status::Ok();
}

Status JointsService::OnPots(const rover_hw_SuspensionPots& p) {
  const Time now = Now();
  const Status s = pots_->Accept(p.header.stamp_ns, now, ctx_->clock().valid());
  if (!s.ok()) {
    WarnDropped(*pots_, s);
    return s;
  }
  reader_->OnSuspensionPots(msg::SuspensionPotsFromIdl(p));
  return Status::Ok();
}

Status JointsService::OnContact(const rover_hw_ArmContact& c) {
  const Time now = Now();
  const Status s = contact_->Accept(c.header.stamp_ns, now, ctx_->clock().valid());
  if (!s.ok()) {
    WarnDropped(*contact_, s);
    return s;
  }
  reader_->OnArmContact(msg::ArmContactFromIdl(c));
  return Status::Ok();
}

void JointsService::OnTimer() {
  const Time now = Now();
  JointState js = reader_->State(now);
  HealthSummary h;
  h.Worsen(js.health, js.health_reason);
  for (const InputMonitor* m : {&*telemetry_, &*pots_}) {
    if (m->Stale(now)) h.Worsen(msg::SensorHealth::kStale, m->StaleReason(now));
  }
  js.health = h.health;
  rover_ddl_JointState out{};
  ctx_->Stamp(out.header, "rover");
  if (js.stamp.ns <= 0) js.stamp = Time{out.header.stamp_ns};  // no input yet: now
  // The stamp is the newest input's time of validity. A tick that found no input newer than the
  // last sample's (the run clock advanced two timer periods between inputs, as it does in
  // lockstep with the simulator) would publish the same state with the same stamp again, which
  // consumers reject as not after the previous sample. So each input state goes out once; only a
  // STALE state is repeated at the timer rate, so that consumers hear that the inputs stopped.
  const bool repeat = last_stamp_ns_.has_value() && js.stamp.ns == *last_stamp_ns_;
  if (!repeat || h.health == msg::SensorHealth::kStale) {
    msg::JointStateToIdl(js, &out);
    (void)writer_.Write(out);
    last_stamp_ns_ = js.stamp.ns;
  }
  ctx_->SetHealth(msg::HealthToIdl(h.health), h.reason);
}

}  // namespace rover::ddl::joints
