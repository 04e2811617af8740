#pragma once
/// @file
/// Test harness for the ddl services: runs one rover::Service in-process (ServiceContext +
/// Lifecycle, as core/runtime's service tests do) on an isolated DDS domain with the SIMULATED
/// run clock, and gives the test its own participant to play the simulator and the consumers.
/// Time only moves when the test publishes sim/clock (AdvanceTo), so timers, staleness and
/// rates are deterministic in simulated time; wall time only bounds how long the test waits
/// for DDS delivery (testing::WaitFor's liveness limit), never what it asserts.

#include <gtest/gtest.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rover/runtime/service.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::ddl::testing {

class ServiceHarness {
 public:
  /// Declares, configures (with `overrides`, key=value) and activates `service` under
  /// instance name `name`. Check ok() before use.
  ServiceHarness(Service& service, const std::string& name, std::vector<std::string> overrides = {})
      : lease_(rover::testing::IsolatedDomain()) {
    options_.name = name;
    options_.domain = lease_.domain();
    options_.clock = "sim";
    options_.overrides = std::move(overrides);
    options_.heartbeat_period_s = 0.2;
    auto ctx = ServiceContext::Create(options_);
    if (!ctx.ok()) {
      status_ = ctx.status();
      return;
    }
    ctx_ = std::move(*ctx);
    lifecycle_ = std::make_unique<Lifecycle>(service, *ctx_, options_);
    status_ = lifecycle_->Configure();
    if (status_.ok()) status_ = lifecycle_->Activate();
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
    if (status_.ok() && !rover::testing::WaitFor([&] { return clock_.MatchedReaders() >= 1; })) {
      status_ = Unavailable("sim/clock reader of the service never matched");
    }
  }

  ~ServiceHarness() {
    if (lifecycle_) (void)lifecycle_->Shutdown();
  }

  const Status& status() const { return status_; }
  bool ok() const { return status_.ok(); }
  ServiceContext& ctx() { return *ctx_; }
  Lifecycle& lifecycle() { return *lifecycle_; }
  const dds::Participant& peer() const { return peer_; }

  /// A writer on the test's participant, waiting until the service's reader matched it.
  template <class T>
  dds::Writer<T> Writer(const std::string& topic, int matched = 1) {
    auto w = dds::Writer<T>::Create(peer_, topic);
    EXPECT_TRUE(w.ok()) << w.status().message();
    if (!w.ok()) return {};
    EXPECT_TRUE(rover::testing::WaitFor([&] {
      Spin(1);
      return w->MatchedReaders() >= matched;
    })) << topic;
    return std::move(*w);
  }

  /// A reader on the test's participant, waiting until the service's writer matched it
  /// (`matched` = 0 for topics whose writer is created later or not at all).
  template <class T>
  dds::Reader<T> Reader(const std::string& topic, int matched = 1) {
    auto r = dds::Reader<T>::Create(peer_, topic);
    EXPECT_TRUE(r.ok()) << r.status().message();
    if (!r.ok()) return {};
    EXPECT_TRUE(rover::testing::WaitFor([&] {
      Spin(1);
      return r->MatchedWriters() >= matched;
    })) << topic;
    return std::move(*r);
  }

  /// Serves whatever has arrived: `rounds` executor passes that do not block.
  void Spin(int rounds = 3) {
    for (int i = 0; i < rounds; ++i) ctx_->executor().SpinOnce(std::chrono::milliseconds(1));
  }

  /// Publishes sim/clock = t and spins the service until its run clock reads t.
  bool AdvanceTo(Time t) {
    rover_sim_Clock c{};
    c.sim_time_ns = t.ns;
    c.real_time_factor = 1.0;
    if (!clock_.Write(c).ok()) return false;
    return rover::testing::WaitFor([&] {
      Spin(1);
      return ctx_->Now().ns == t.ns;
    });
  }

  /// Spins until `condition` holds (the liveness limit of testing::WaitFor).
  bool SpinUntil(const std::function<bool()>& condition) {
    return rover::testing::WaitFor([&] {
      Spin(1);
      return condition();
    });
  }

 private:
  dds::DomainLease lease_;
  ServiceOptions options_;
  std::unique_ptr<ServiceContext> ctx_;
  std::unique_ptr<Lifecycle> lifecycle_;
  dds::Participant peer_;
  dds::Writer<rover_sim_Clock> clock_;
  Status status_;
};

/// Takes every sample of `reader` into `out` (owned copies); returns how many arrived.
template <class T>
std::size_t Drain(dds::Reader<T>& reader, std::vector<dds::OwnedSample<T>>* out) {
  std::size_t n = 0;
  for (auto& s : reader.Take()) {
    out->push_back(std::move(s));
    ++n;
  }
  return n;
}

}  // namespace rover::ddl::testing
