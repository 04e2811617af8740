#pragma once
/// @file
/// The one harness for in-process service tests: runs one rover::Service (ServiceContext +
/// Lifecycle, as RunServiceMain would) on a DDS domain of its own, on the SIMULATED run clock,
/// and gives the test a second participant ("the peer") to play everything around the service:
/// the simulator, drivers below it, consumers above it (fakes in rover/testing/fakes/). The
/// harness records the service's heartbeats (health()).
///
/// Time only moves when the test publishes sim/clock (AdvanceTo), so timers, staleness limits
/// and rates are deterministic in simulated time. Wall time only bounds how long the harness
/// waits for DDS delivery (testing::WaitFor's liveness limit), never what a test asserts.
///
/// DDS configuration: the constructor leases a free domain and points CYCLONEDDS_URI at
/// deploy/cyclonedds/loopback.xml (testing::IsolatedDomain) before any participant exists, so a
/// test needs nothing exported and never sees another test's traffic.
///
///   MyService service;
///   testing::ServiceHarness h(service, "my-service-test", {"rate_hz=10"});
///   ASSERT_TRUE(h.ok()) << h.status().message();
///   auto in = h.Writer<rover_ddl_Imu>("ddl/imu");        // waits until the service matched
///   auto out = h.Reader<rover_dl_PoseEstimate>("dl/pose");
///   ASSERT_TRUE(in.Write(sample).ok());
///   ASSERT_TRUE(h.AdvanceTo(Time::FromSeconds(0.1)));   // the service's clock reads 0.1 s
///   ASSERT_TRUE(h.SpinUntil([&] { return !out.Take().empty(); }));

#include <gtest/gtest.h>

#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "rover/runtime/domain.hpp"
#include "rover/runtime/service.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::testing {

class ServiceHarness {
 public:
  /// Wall seconds between the service's periodic heartbeats (sys/health): short, so a test that
  /// waits for one is not slowed down. Health changes are published at once regardless.
  static constexpr double kHeartbeatPeriodS = 0.2;

  /// Declares, configures (with `overrides`, key=value) and activates `service` under instance
  /// name `name`, then creates the peer participant and its sim/clock writer and waits until
  /// the service's clock reader matched it. Check ok() before use: a failed transition (e.g. a
  /// bad parameter) is kept in status() and the lifecycle stays where it stopped.
  ServiceHarness(Service& service, const std::string& name,
                 std::vector<std::string> overrides = {});
  /// Shuts the service down.
  ~ServiceHarness();
  ServiceHarness(const ServiceHarness&) = delete;
  ServiceHarness& operator=(const ServiceHarness&) = delete;

  const Status& status() const { return status_; }
  bool ok() const { return status_.ok(); }
  int domain() const { return lease_.domain(); }
  const ServiceOptions& options() const { return options_; }
  ServiceContext& ctx() { return *ctx_; }
  Lifecycle& lifecycle() { return *lifecycle_; }
  /// The test's own participant on the service's domain.
  const dds::Participant& peer() const { return peer_; }
  /// The last run-clock time published with AdvanceTo (zero before the first).
  Time now() const { return now_; }

  /// The service's heartbeats (sys/health samples naming it), oldest first: all that had
  /// arrived by the end of the last Spin (AdvanceTo and SpinUntil spin too).
  const std::vector<rover_sys_Heartbeat>& heartbeats() const { return heartbeats_; }
  /// The health of the last heartbeat (OK before the first).
  rover_SensorHealth health() const;
  /// The message of the last heartbeat ("" before the first).
  std::string health_message() const;

  /// A writer on the peer, once the service's reader matched it (`matched` readers).
  template <class T>
  dds::Writer<T> Writer(const std::string& topic, int matched = 1) {
    auto w = dds::Writer<T>::Create(peer_, topic);
    EXPECT_TRUE(w.ok()) << w.status().message();
    if (!w.ok()) return {};
    EXPECT_TRUE(SpinUntil([&] { return w->MatchedReaders() >= matched; })) << topic;
    return std::move(*w);
  }

  /// A reader on the peer, once the service's writer matched it (`matched` = 0 for topics whose
  /// writer is created later or not at all).
  template <class T>
  dds::Reader<T> Reader(const std::string& topic, int matched = 1) {
    auto r = dds::Reader<T>::Create(peer_, topic);
    EXPECT_TRUE(r.ok()) << r.status().message();
    if (!r.ok()) return {};
    EXPECT_TRUE(SpinUntil([&] { return r->MatchedWriters() >= matched; })) << topic;
    return std::move(*r);
  }

  /// Serves whatever has arrived: `rounds` executor passes, each waiting at most `max_wait`;
  /// then collects the heartbeats that arrived.
  void Spin(int rounds = 3, std::chrono::milliseconds max_wait = std::chrono::milliseconds(1));

  /// Publishes sim/clock = t on the peer and spins the service until its run clock reads t.
  /// Returns false if it never did (within the liveness limit).
  bool AdvanceTo(Time t);

  /// Spins the service until `condition` holds; false if it did not within `timeout` (wall
  /// time: a liveness limit, never an assertion on speed).
  bool SpinUntil(const std::function<bool()>& condition,
                 std::chrono::milliseconds timeout = std::chrono::seconds(20));

 private:
  dds::DomainLease lease_;
  ServiceOptions options_;
  std::unique_ptr<ServiceContext> ctx_;
  std::unique_ptr<Lifecycle> lifecycle_;
  dds::Participant peer_;
  dds::Writer<rover_sim_Clock> clock_;
  dds::Reader<rover_sys_Heartbeat> health_;
  std::vector<rover_sys_Heartbeat> heartbeats_;
  Time now_;
  Status status_;
};

}  // namespace rover::testing
