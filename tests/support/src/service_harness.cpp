#include "rover/testing/service_harness.hpp"

namespace rover::testing {

ServiceHarness::ServiceHarness(Service& service, const std::string& name,
                               std::vector<std::string> overrides)
    : lease_(IsolatedDomain()) {
  options_.name = name;
  options_.domain = lease_.domain();
  options_.clock = "sim";
  options_.overrides = std::move(overrides);
  options_.heartbeat_period_s = kHeartbeatPeriodS;
  auto ctx = ServiceContext::Create(options_);
  if (!ctx.ok()) {
    status_ = ctx.status();
    return;
  }
  ctx_ = std::move(*ctx);
  lifecycle_ = std::make_unique<Lifecycle>(service, *ctx_, options_);
  status_ = lifecycle_->Configure();
  if (status_.ok()) status_ = lifecycle_->Activate();
  if (!status_.ok()) return;
  auto peer = dds::Participant::Create(lease_.domain());
  if (!peer.ok()) {
    status_ = peer.status();
    return;
  }
  peer_ = std::move(*peer);
  auto clock = dds::Writer<rover_sim_Clock>::Create(peer_, "sim/clock");
  if (!clock.ok()) {
    status_ = clock.status();
    return;
  }
  clock_ = std::move(*clock);
  auto health = dds::Reader<rover_sys_Heartbeat>::Create(peer_, "sys/health");
  if (!health.ok()) {
    status_ = health.status();
    return;
  }
  health_ = std::move(*health);
  if (!SpinUntil([&] { return clock_.MatchedReaders() >= 1 && health_.MatchedWriters() >= 1; })) {
    status_ = Unavailable("the service's sim/clock reader or sys/health writer never matched");
  }
}

ServiceHarness::~ServiceHarness() {
  if (lifecycle_) (void)lifecycle_->Shutdown();
}

void ServiceHarness::Spin(int rounds, std::chrono::milliseconds max_wait) {
  for (int i = 0; i < rounds; ++i) ctx_->executor().SpinOnce(max_wait);
  if (!health_.valid()) return;
  for (auto& h : health_.Take()) {
    if (options_.name == h->service) heartbeats_.push_back(h.data());
  }
}

rover_SensorHealth ServiceHarness::health() const {
  return heartbeats_.empty() ? rover_HEALTH_OK : heartbeats_.back().health;
}

std::string ServiceHarness::health_message() const {
  return heartbeats_.empty() ? std::string() : std::string(heartbeats_.back().message);
}

bool ServiceHarness::AdvanceTo(Time t) {
  rover_sim_Clock c{};
  c.sim_time_ns = t.ns;
  c.real_time_factor = 1.0;
  if (!clock_.Write(c).ok()) return false;
  now_ = t;
  return SpinUntil([&] { return ctx_->Now().ns == t.ns; });
}

bool ServiceHarness::SpinUntil(const std::function<bool()>& condition,
                               std::chrono::milliseconds timeout) {
  return WaitFor(
      [&] {
        Spin(1, std::chrono::milliseconds(5));
        return condition();
      },
      timeout);
}

}  // namespace rover::testing
