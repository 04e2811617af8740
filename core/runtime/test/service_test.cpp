#include "rover/runtime/service.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "rover/base/range_check.hpp"
#include "rover/testing/service_harness.hpp"
#include "rover/testing/test_support.hpp"

namespace rover {
namespace {

class CountingService : public Service {
 public:
  CountingService() : Service("counting") {}
  void DeclareParameters(ParamSet& p) override {
    p.Declare("rate_hz", 10.0, "rate").Range(1.0, 100.0);
  }
  Status OnConfigure(ServiceContext& ctx, const ParamSet& p) override {
    ++configured;
    rate = p.GetDouble("rate_hz");
    ctx.executor().AddTimer(Seconds(1.0 / rate), [this] { ++ticks; });
    return Status::Ok();
  }
  Status OnActivate(ServiceContext&) override {
    ++activated;
    return Status::Ok();
  }
  Status OnDeactivate(ServiceContext&) override {
    ++deactivated;
    return Status::Ok();
  }
  void OnShutdown(ServiceContext&) override { ++shut_down; }
  int configured = 0, activated = 0, deactivated = 0, shut_down = 0, ticks = 0;
  double rate = 0;
};

class ServiceTest : public ::testing::Test {
 protected:
  void SetUp() override { lease_ = testing::IsolatedDomain(); }
  ServiceOptions Options() {
    ServiceOptions o;
    o.name = "counting-1";
    o.domain = lease_.domain();
    return o;
  }
  dds::DomainLease lease_;
};

TEST_F(ServiceTest, FullLifecycle) {
  auto ctx = ServiceContext::Create(Options());
  ASSERT_TRUE(ctx.ok()) << ctx.status().message();
  CountingService svc;
  Lifecycle lc(svc, **ctx, Options());
  EXPECT_EQ(lc.state(), LifecycleState::kUnconfigured);
  ASSERT_TRUE(lc.Configure().ok());
  EXPECT_EQ(lc.state(), LifecycleState::kInactive);
  EXPECT_EQ(lc.Configure().code(), StatusCode::kFailedPrecondition);  // only once
  ASSERT_TRUE(lc.Activate().ok());
  EXPECT_EQ(lc.state(), LifecycleState::kActive);
  EXPECT_TRUE((*ctx)->executor().active());
  ASSERT_TRUE(lc.Deactivate().ok());
  EXPECT_FALSE((*ctx)->executor().active());
  ASSERT_TRUE(lc.Activate().ok());
  ASSERT_TRUE(lc.Shutdown().ok());
  EXPECT_EQ(lc.state(), LifecycleState::kFinalized);
  EXPECT_EQ(svc.configured, 1);
  EXPECT_EQ(svc.activated, 2);
  EXPECT_EQ(svc.deactivated, 2);
  EXPECT_EQ(svc.shut_down, 1);
  EXPECT_EQ(lc.Activate().code(), StatusCode::kFailedPrecondition);
}

TEST_F(ServiceTest, RefusesToActivateWithInvalidParameterAndNamesIt) {
  ServiceOptions o = Options();
  o.overrides = {"rate_hz=500"};
  auto ctx = ServiceContext::Create(o);
  ASSERT_TRUE(ctx.ok());
  CountingService svc;
  Lifecycle lc(svc, **ctx, o);
  const Status c = lc.Configure();
  EXPECT_EQ(c.code(), StatusCode::kOutOfRange);
  EXPECT_EQ(svc.configured, 0);  // OnConfigure never ran on bad parameters
  const Status a = lc.Activate();
  EXPECT_EQ(a.code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(a.message().find("not configured"), std::string::npos);
  EXPECT_NE(a.message().find("key 'rate_hz': 500 is out of range [1, 100]"), std::string::npos)
      << a.message();
  EXPECT_EQ(lc.state(), LifecycleState::kUnconfigured);
  EXPECT_EQ(svc.activated, 0);
}

class CrossCheckedService : public CountingService {
 public:
  void DeclareParameters(ParamSet& p) override {
    CountingService::DeclareParameters(p);
    p.Declare("min_hz", 1.0, "lower bound").Range(0.1, 100.0);
  }
  Status ValidateParameters(const ParamSet& p) const override {
    if (p.GetDouble("min_hz") > p.GetDouble("rate_hz")) {
      return InvalidArgument(p.Origin("min_hz").ToString() + ": key 'min_hz': above rate_hz");
    }
    return Status::Ok();
  }
};

TEST_F(ServiceTest, CrossParameterRulesAreCheckedWithTheRanges) {
  CrossCheckedService svc;
  ServiceOptions o = Options();
  o.overrides = {"min_hz=20"};
  ParamSet p;
  const Status s = LoadParameters(svc, o, &p);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("key 'min_hz': above rate_hz"), std::string::npos) << s.message();
}

TEST_F(ServiceTest, BadOptionsAreRejected) {
  ServiceOptions o = Options();
  o.clock = "sundial";
  EXPECT_NE(ValidateOptions(o).message().find("'sundial' is not one of: wall, sim"), std::string::npos);
  o = Options();
  o.domain = 300;
  EXPECT_FALSE(ServiceContext::Create(o).ok());
}

TEST_F(ServiceTest, HeartbeatCarriesNameStateAndPid) {
  ServiceOptions o = Options();
  o.heartbeat_period_s = 0.05;
  auto ctx = ServiceContext::Create(o);
  ASSERT_TRUE(ctx.ok());
  auto p = dds::Participant::Create(lease_.domain());
  ASSERT_TRUE(p.ok());
  auto r = dds::Reader<rover_sys_Heartbeat>::Create(*p, "sys/health");
  ASSERT_TRUE(r.ok());
  CountingService svc;
  Lifecycle lc(svc, **ctx, o);
  ASSERT_TRUE(lc.Configure().ok());
  ASSERT_TRUE(lc.Activate().ok());
  bool seen_active = false;
  ASSERT_TRUE(testing::WaitFor([&] {
    (*ctx)->executor().SpinOnce(std::chrono::milliseconds(10));
    for (auto& s : r->Take()) {
      EXPECT_STREQ(s->service, "counting-1");
      EXPECT_EQ(s->pid, getpid());
      if (s->state == rover_sys_LIFECYCLE_ACTIVE && s->count > 2) seen_active = true;
    }
    return seen_active;
  }));
}

TEST_F(ServiceTest, SimClockDrivesServiceTimers) {
  ServiceOptions o = Options();
  o.clock = "sim";
  auto ctx = ServiceContext::Create(o);
  ASSERT_TRUE(ctx.ok());
  EXPECT_TRUE((*ctx)->clock().simulated());
  EXPECT_FALSE((*ctx)->clock().valid());
  CountingService svc;  // 10 Hz on the run clock
  Lifecycle lc(svc, **ctx, o);
  ASSERT_TRUE(lc.Configure().ok());
  ASSERT_TRUE(lc.Activate().ok());
  auto p = dds::Participant::Create(lease_.domain());
  auto w = dds::Writer<rover_sim_Clock>::Create(*p, "sim/clock");
  ASSERT_TRUE(w.ok());
  ASSERT_TRUE(testing::WaitFor([&] { return w->MatchedReaders() >= 1; }));
  // Publish 2 simulated seconds in 100 steps, as fast as possible, and wait for each to land.
  for (int i = 0; i <= 100; ++i) {
    rover_sim_Clock c{};
    c.sim_time_ns = Time::FromSeconds(0.02 * i).ns;
    ASSERT_TRUE(w->Write(c).ok());
    ASSERT_TRUE(testing::WaitFor([&] {
      (*ctx)->executor().SpinOnce(std::chrono::milliseconds(5));
      return (*ctx)->Now().ns == c.sim_time_ns;
    }));
  }
  // Timer armed at the first sample (t = 0), then every 0.1 s: 20 fires in 2 s.
  EXPECT_EQ(svc.ticks, 20);
}


// header.seq counts per writer (the IDL's promise, which drop detection relies on): two writers
// stamping with the same frame id each number their own samples 1, 2, 3, ...
TEST_F(ServiceTest, HeaderSeqCountsPerWriterNotPerFrameId) {
  auto ctx = ServiceContext::Create(Options());
  ASSERT_TRUE(ctx.ok()) << ctx.status().message();
  // Topics outside the catalog, keep-all, so that every sample arrives.
  constexpr auto kKeepAll = dds::QosProfile::kCommand;
  auto pose = (*ctx)->MakeWriter<rover_dl_PoseEstimate>("test/pose_a", kKeepAll);
  auto odometry = (*ctx)->MakeWriter<rover_dl_PoseEstimate>("test/pose_b", kKeepAll);
  ASSERT_TRUE(pose.ok() && odometry.ok());
  auto p = dds::Participant::Create(lease_.domain());
  ASSERT_TRUE(p.ok());
  auto pose_r = dds::Reader<rover_dl_PoseEstimate>::Create(*p, "test/pose_a", kKeepAll);
  auto odo_r = dds::Reader<rover_dl_PoseEstimate>::Create(*p, "test/pose_b", kKeepAll);
  ASSERT_TRUE(pose_r.ok() && odo_r.ok());
  ASSERT_TRUE(testing::WaitFor(
      [&] { return pose->MatchedReaders() == 1 && odometry->MatchedReaders() == 1; }));
  for (int i = 0; i < 3; ++i) {
    for (auto* w : {&*pose, &*odometry}) {
      rover_dl_PoseEstimate m{};
      (*ctx)->Stamp(m.header, "site");  // the same frame id on both topics
      ASSERT_TRUE(w->Write(m).ok());
    }
  }
  for (auto* r : {&*pose_r, &*odo_r}) {
    std::vector<std::uint32_t> seqs;
    ASSERT_TRUE(testing::WaitFor([&] {
      for (auto& s : r->Take()) seqs.push_back(s->header.seq);
      return seqs.size() >= 3;
    }));
    EXPECT_EQ(seqs, (std::vector<std::uint32_t>{1, 2, 3})) << r->topic_name();
  }
}

// ---- input monitoring through the harness (issue 12) ---------------------------------------

// Reads dl/pose (limit 0.5 s): rejects a non-finite x, throws on y = 7 (a handler bug), and
// counts what it used.
class PoseReader : public Service {
 public:
  PoseReader() : Service("pose-reader") {}
  std::vector<runtime::InputSpec> Inputs() const override {
    return {{"dl/pose", {.max_age_s = 0.5}}};
  }
  Status OnConfigure(ServiceContext& ctx, const ParamSet&) override {
    return ctx.Subscribe<rover_dl_PoseEstimate>(
        "dl/pose", [this](const dds::Sample<rover_dl_PoseEstimate>& s) {
          ROVER_RETURN_IF_ERROR(CheckFinite("pose.position.x", s->pose.position.x));
          if (s->pose.position.y == 7.0) throw std::runtime_error("y = 7 is not handled");
          ++used;
          return Status::Ok();
        });
  }
  int used = 0;
};

class InputHealthTest : public ::testing::Test {
 protected:
  void SetUp() override {
    h_ = std::make_unique<testing::ServiceHarness>(svc_, "pose-reader-test",
                                                   std::vector<std::string>{"inputs.hold_s=1"});
    ASSERT_TRUE(h_->ok()) << h_->status().message();
    pose_ = h_->Writer<rover_dl_PoseEstimate>("dl/pose");
  }
  // Publishes a pose stamped now (x, y), then moves the clock on by dt.
  void Send(double t, double x = 0.0, double y = 0.0) {
    ASSERT_TRUE(h_->AdvanceTo(Time::FromSeconds(t)));
    rover_dl_PoseEstimate m{};
    m.header.stamp_ns = Time::FromSeconds(t).ns;
    m.pose.position.x = x;
    m.pose.position.y = y;
    ASSERT_TRUE(pose_.Write(m).ok());
  }
  bool HealthBecomes(rover_SensorHealth want) {
    return h_->SpinUntil([&] { return h_->health() == want; });
  }

  PoseReader svc_;
  std::unique_ptr<testing::ServiceHarness> h_;
  dds::Writer<rover_dl_PoseEstimate> pose_;
};

TEST_F(InputHealthTest, RejectedStaleAndRecoveredInputsReachTheHeartbeat) {
  Send(0.1);
  ASSERT_TRUE(h_->SpinUntil([&] { return svc_.used == 1; }));
  EXPECT_EQ(h_->health(), rover_HEALTH_OK) << h_->health_message();
  // A non-finite sample: rejected with the check's message, at once.
  Send(0.2, std::nan(""));
  ASSERT_TRUE(HealthBecomes(rover_HEALTH_DEGRADED)) << h_->health_message();
  EXPECT_EQ(h_->health_message(), "dl/pose rejected: pose.position.x is nan (must be finite)");
  EXPECT_EQ(svc_.used, 1);
  EXPECT_EQ(h_->ctx().inputs().rejected("dl/pose"), 1u);
  // Nothing usable for longer than 0.5 s: stale (a fault).
  ASSERT_TRUE(h_->AdvanceTo(Time::FromSeconds(0.8)));
  ASSERT_TRUE(HealthBecomes(rover_HEALTH_STALE)) << h_->health_message();
  const std::string stale = "dl/pose stale: no sample since t = 0.1 s (limit 0.5 s)";
  EXPECT_EQ(h_->health_message().rfind(stale, 0), 0u) << h_->health_message();
  // Good samples again: stale clears at once, the rejection hold_s (1 s) after it happened.
  for (double t = 0.9; t < 2.0; t += 0.1) Send(t);
  ASSERT_TRUE(HealthBecomes(rover_HEALTH_OK)) << h_->health_message();
  EXPECT_EQ(h_->health_message(), "");
}

TEST_F(InputHealthTest, AHandlerThatThrowsIsARejectionNotACrash) {
  Send(0.1);
  Send(0.2, 0.0, 7.0);
  ASSERT_TRUE(HealthBecomes(rover_HEALTH_DEGRADED)) << h_->health_message();
  EXPECT_NE(h_->health_message().find("dl/pose rejected: handling the sample threw: y = 7"),
            std::string::npos)
      << h_->health_message();
  Send(0.3);
  ASSERT_TRUE(h_->SpinUntil([&] { return svc_.used == 2; }));  // still serving
}

TEST_F(InputHealthTest, TheWorseOfOwnAndInputHealthIsReported) {
  Send(0.1);
  Send(0.2, std::nan(""));
  ASSERT_TRUE(HealthBecomes(rover_HEALTH_DEGRADED));
  h_->ctx().SetHealth(rover_HEALTH_FAILED, "calibration lost");
  ASSERT_TRUE(HealthBecomes(rover_HEALTH_FAILED));
  EXPECT_EQ(h_->health_message(), "calibration lost");
  h_->ctx().SetHealth(rover_HEALTH_OK, "");
  ASSERT_TRUE(HealthBecomes(rover_HEALTH_DEGRADED));
  EXPECT_NE(h_->health_message().find("dl/pose rejected"), std::string::npos);
}

TEST(InputParamsOfServices, DeclaredAndCheckedLikeAnyParameter) {
  PoseReader svc;
  ServiceOptions o;
  o.name = "pose-reader";
  o.overrides = {"inputs.dl_pose.max_age_s=-2"};
  ParamSet params;
  const Status s = LoadParameters(svc, o, &params);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("inputs.dl_pose.max_age_s"), std::string::npos) << s.message();
  o.overrides = {"inputs.dl_pose.max_age_s=2", "inputs.startup_s=1"};
  ASSERT_TRUE(LoadParameters(svc, o, &params).ok());
  EXPECT_DOUBLE_EQ(params.GetDouble("inputs.dl_pose.max_age_s"), 2.0);
}

}  // namespace
}  // namespace rover
