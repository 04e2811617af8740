#include "rover/runtime/input_monitor.hpp"

#include <gtest/gtest.h>

#include "rover/base/params.hpp"

namespace rover::runtime {
namespace {

Time T(double s) { return Time::FromSeconds(s); }

InputMonitor MakeMonitor(InputMonitorOptions options = {}) {
  auto m = InputMonitor::Create(options);
  EXPECT_TRUE(m.ok()) << m.status().message();
  return std::move(*m);
}

InputLimits Limit(double max_age_s) {
  InputLimits l;
  l.max_age_s = max_age_s;
  return l;
}

// One accepted sample of input `i`, stamped `stamp` and received at `now`, seq `seq`.
void Accept(InputMonitor& m, std::size_t i, std::uint32_t seq, double stamp, double now,
            std::uint64_t writer = 7) {
  m.OnArrival(i, writer, seq, T(now));
  m.OnAccepted(i, T(stamp), T(now));
}

TEST(InputMonitorOptions, ValidateNamesTheField) {
  InputMonitorOptions o;
  o.hold_s = 0.0;
  EXPECT_NE(o.Validate().message().find("hold_s"), std::string::npos);
  InputLimits l;
  l.max_age_s = -1.0;
  EXPECT_NE(l.Validate().message().find("max_age_s"), std::string::npos);
  EXPECT_FALSE(InputMonitor::Create(o).ok());
  InputMonitor m = MakeMonitor();
  EXPECT_FALSE(m.Declare("dl/pose", l).ok());
  EXPECT_FALSE(m.Declare("", InputLimits{}).ok());
}

TEST(InputMonitor, FreshInputIsNominal) {
  InputMonitor m = MakeMonitor();
  ASSERT_TRUE(m.Declare("dl/pose", Limit(0.5)).ok());
  const std::size_t i = m.Watch("dl/pose", 0.0);
  m.Start(T(0.0));
  for (int k = 1; k <= 10; ++k) Accept(m, i, k, 0.1 * k, 0.1 * k);
  const InputReport r = m.Report(T(1.2));
  EXPECT_EQ(r.verdict, InputVerdict::kNominal);
  EXPECT_TRUE(r.reason.empty());
  EXPECT_EQ(m.accepted("dl/pose"), 10u);
}

TEST(InputMonitor, StaleThenRecovered) {
  InputMonitor m = MakeMonitor();
  ASSERT_TRUE(m.Declare("dl/pose", Limit(0.5)).ok());
  const std::size_t i = m.Watch("dl/pose", 0.0);
  m.Start(T(0.0));
  Accept(m, i, 1, 1.0, 1.0);
  EXPECT_EQ(m.Report(T(1.5)).verdict, InputVerdict::kNominal);  // exactly at the limit
  const InputReport r = m.Report(T(2.8));
  ASSERT_EQ(r.verdict, InputVerdict::kFault);
  ASSERT_EQ(r.findings.size(), 1u);
  EXPECT_EQ(r.findings[0].problem, InputProblem::kStale);
  EXPECT_EQ(r.findings[0].topic, "dl/pose");
  EXPECT_EQ(r.reason, "dl/pose stale: no sample since t = 1 s (limit 0.5 s)");
  EXPECT_EQ(r.findings[0].since, T(1.5));
  // The reason does not change while the input stays stale.
  EXPECT_EQ(m.Report(T(9.0)).reason, r.reason);
  // A fresh sample clears it at once.
  Accept(m, i, 2, 9.0, 9.0);
  EXPECT_EQ(m.Report(T(9.1)).verdict, InputVerdict::kNominal);
}

TEST(InputMonitor, StaleUsesTheStampSoAFrozenSourceGoesStale) {
  InputMonitor m = MakeMonitor();
  ASSERT_TRUE(m.Declare("ddl/imu", Limit(0.5)).ok());
  const std::size_t i = m.Watch("ddl/imu", 0.0);
  m.Start(T(0.0));
  Accept(m, i, 1, 1.0, 1.0);
  // The same sample again and again (stamp and seq repeated), received on time.
  for (int k = 1; k <= 10; ++k) Accept(m, i, 1, 1.0, 1.0 + 0.1 * k);
  const InputReport r = m.Report(T(2.0));
  ASSERT_EQ(r.verdict, InputVerdict::kFault);
  EXPECT_EQ(r.findings[0].problem, InputProblem::kStale);
  ASSERT_EQ(r.findings.size(), 2u);
  EXPECT_EQ(r.findings[1].problem, InputProblem::kSeqRepeat);
  EXPECT_EQ(r.reason, "ddl/imu stale: no sample since t = 1 s (limit 0.5 s) (+1 more)");
  // A stamp ahead of the clock counts as the receipt time (it cannot keep an input fresh).
  Accept(m, i, 2, 1e6, 2.0);
  EXPECT_EQ(m.Report(T(2.4)).findings.front().problem, InputProblem::kSeqRepeat);
  EXPECT_EQ(m.Report(T(2.6)).findings.front().problem, InputProblem::kStale);
}

TEST(InputMonitor, NoSampleCountsFromStartWithTheStartupAllowance) {
  InputMonitorOptions o;
  o.startup_s = 3.0;
  InputMonitor m = MakeMonitor(o);
  ASSERT_TRUE(m.Declare("dl/pose", Limit(0.5)).ok());
  m.Watch("dl/pose", 0.0);
  m.Start(T(10.0));
  EXPECT_EQ(m.Report(T(12.9)).verdict, InputVerdict::kNominal);
  const InputReport r = m.Report(T(13.5));
  ASSERT_EQ(r.verdict, InputVerdict::kFault);
  EXPECT_EQ(r.reason, "dl/pose stale: no sample since the start at t = 10 s (limit 3 s)");
}

TEST(InputMonitor, InputsWithoutALimitNeverGoStale) {
  InputMonitor m = MakeMonitor();
  const std::size_t i = m.Watch("apl/mobility_command", 0.0);
  m.Start(T(0.0));
  EXPECT_EQ(m.Report(T(1000.0)).verdict, InputVerdict::kNominal);
  Accept(m, i, 1, 1.0, 1.0);
  EXPECT_EQ(m.Report(T(1000.0)).verdict, InputVerdict::kNominal);
}

TEST(InputMonitor, SeqGapPerWriterIsDegradedForHoldSeconds) {
  InputMonitorOptions o;
  o.hold_s = 2.0;
  InputMonitor m = MakeMonitor(o);
  const std::size_t i = m.Watch("ddl/imu", 0.0);
  m.Start(T(0.0));
  // Two writers, each counting from its own start: no gap across writers.
  Accept(m, i, 36, 0.1, 0.1, /*writer=*/1);
  Accept(m, i, 1, 0.1, 0.1, /*writer=*/2);
  Accept(m, i, 37, 0.2, 0.2, 1);
  Accept(m, i, 2, 0.2, 0.2, 2);
  EXPECT_EQ(m.Report(T(0.2)).verdict, InputVerdict::kNominal);
  EXPECT_TRUE(m.OnArrival(i, 1, 41, T(0.3)));  // 38, 39, 40 lost
  m.OnAccepted(i, T(0.3), T(0.3));
  InputReport r = m.Report(T(0.4));
  ASSERT_EQ(r.verdict, InputVerdict::kDegraded);
  EXPECT_EQ(r.findings[0].problem, InputProblem::kSeqGap);
  EXPECT_EQ(r.reason, "ddl/imu seq gap: seq 41 after 37 (3 samples lost)");
  // A second gap within the hold keeps the episode's reason.
  m.OnArrival(i, 1, 45, T(1.0));
  EXPECT_EQ(m.Report(T(1.1)).reason, r.reason);
  EXPECT_EQ(m.Report(T(2.9)).verdict, InputVerdict::kDegraded);  // 1.9 s after the last gap
  EXPECT_EQ(m.Report(T(3.1)).verdict, InputVerdict::kNominal);
}

TEST(InputMonitor, StreamsTolerateSomeLossButNotAHalf) {
  InputMonitor m = MakeMonitor();
  const std::size_t i = m.Watch("ddl/imu", kStreamTolerableLoss);
  m.Start(T(0.0));
  // One sample in ten lost, for 500 samples: 10 % is tolerated.
  std::uint32_t seq = 1;
  double t = 0.0;
  for (int k = 0; k < 500; ++k) {
    seq += (k % 10 == 9) ? 2 : 1;
    t += 0.01;
    EXPECT_FALSE(m.OnArrival(i, 7, seq, T(t))) << k;
  }
  EXPECT_EQ(m.Report(T(t)).verdict, InputVerdict::kNominal);
  // Every other sample lost: a finding once the average passes 20 %.
  int first = -1;
  for (int k = 0; k < 100; ++k) {
    seq += 2;
    t += 0.01;
    if (m.OnArrival(i, 7, seq, T(t)) && first < 0) first = k;
  }
  ASSERT_GE(first, 0);
  EXPECT_LT(first, 30);
  const InputReport r = m.Report(T(t));
  ASSERT_EQ(r.verdict, InputVerdict::kDegraded);
  EXPECT_NE(r.reason.find("ddl/imu seq gap: seq "), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("1 sample lost; "), std::string::npos) << r.reason;
  EXPECT_NE(r.reason.find("% of recent samples, tolerated 20 %"), std::string::npos) << r.reason;
}

TEST(InputMonitor, GapsOnKeepLastOneTopicsAreNoFinding) {
  InputMonitor m = MakeMonitor();
  const std::size_t i = m.Watch("dl/pose", /*tolerated_loss=*/1.0);
  m.Start(T(0.0));
  Accept(m, i, 1, 0.1, 0.1);
  EXPECT_FALSE(m.OnArrival(i, 7, 5, T(0.2)));
  EXPECT_EQ(m.Report(T(0.3)).verdict, InputVerdict::kNominal);
  // A repeat or a step back still is one.
  EXPECT_TRUE(m.OnArrival(i, 7, 5, T(0.3)));
  EXPECT_TRUE(m.OnArrival(i, 7, 3, T(0.4)));
  const InputReport r = m.Report(T(0.5));
  ASSERT_EQ(r.findings.size(), 2u);
  EXPECT_EQ(r.findings[0].problem, InputProblem::kSeqRepeat);
  EXPECT_EQ(r.findings[1].problem, InputProblem::kSeqReorder);
  EXPECT_EQ(r.findings[1].reason, "dl/pose out of order: seq 3 after 5");
}

TEST(InputMonitor, SeqChecksCanBeTurnedOffAndUnnumberedSamplesAreSkipped) {
  InputMonitor m = MakeMonitor();
  InputLimits l;
  l.check_seq = false;
  ASSERT_TRUE(m.Declare("a/b", l).ok());
  const std::size_t i = m.Watch("a/b", 0.0);
  const std::size_t j = m.Watch("c/d", 0.0);
  m.Start(T(0.0));
  EXPECT_FALSE(m.OnArrival(i, 1, 1, T(0.1)));
  EXPECT_FALSE(m.OnArrival(i, 1, 9, T(0.2)));
  EXPECT_FALSE(m.OnArrival(j, 1, 0, T(0.1)));
  EXPECT_FALSE(m.OnArrival(j, 1, 0, T(0.2)));
  EXPECT_EQ(m.Report(T(0.3)).verdict, InputVerdict::kNominal);
}

TEST(InputMonitor, RejectionCarriesTheConversionMessageUntilRecovered) {
  InputMonitorOptions o;
  o.hold_s = 1.0;
  InputMonitor m = MakeMonitor(o);
  ASSERT_TRUE(m.Declare("dl/pose", Limit(0.5)).ok());
  const std::size_t i = m.Watch("dl/pose", 0.0);
  m.Start(T(0.0));
  Accept(m, i, 1, 0.1, 0.1);
  m.OnArrival(i, 7, 2, T(0.2));
  m.OnRejected(i, "pose.position.x is nan (must be finite)", T(0.2));
  m.OnArrival(i, 7, 3, T(0.3));
  m.OnRejected(i, "pose.position.y is inf (must be finite)", T(0.3));
  InputReport r = m.Report(T(0.4));
  ASSERT_EQ(r.verdict, InputVerdict::kDegraded);
  EXPECT_EQ(r.reason, "dl/pose rejected: pose.position.x is nan (must be finite)");
  EXPECT_EQ(m.rejected("dl/pose"), 2u);
  // Nothing accepted since: past the hold the rejection still shows, and the input goes stale
  // with the rejection named.
  r = m.Report(T(2.0));
  ASSERT_EQ(r.verdict, InputVerdict::kFault);
  EXPECT_EQ(r.findings[0].reason,
            "dl/pose stale: no sample since t = 0.1 s (limit 0.5 s); since then rejected: "
            "pose.position.x is nan (must be finite)");
  ASSERT_EQ(r.findings.size(), 2u);
  EXPECT_EQ(r.findings[1].problem, InputProblem::kRejected);
  // Recovery: accepted samples; the rejection clears hold_s after the last one.
  Accept(m, i, 4, 2.0, 2.0);
  EXPECT_EQ(m.Report(T(2.05)).verdict, InputVerdict::kNominal);  // 1.75 s after the last one
  // A new episode gets its own reason.
  Accept(m, i, 5, 2.9, 2.9);
  m.OnRejected(i, "pose.orientation is not a unit quaternion", T(3.0));
  EXPECT_EQ(m.Report(T(3.1)).reason, "dl/pose rejected: pose.orientation is not a unit quaternion");
  Accept(m, i, 6, 3.2, 3.2);
  EXPECT_EQ(m.Report(T(3.5)).verdict, InputVerdict::kDegraded);
  Accept(m, i, 7, 4.0, 4.0);
  EXPECT_EQ(m.Report(T(4.1)).verdict, InputVerdict::kNominal);
}

TEST(InputMonitor, SeveralInputsWorstFirst) {
  InputMonitor m = MakeMonitor();
  ASSERT_TRUE(m.Declare("ddl/imu", Limit(0.5)).ok());
  ASSERT_TRUE(m.Declare("dl/pose", Limit(1.0)).ok());
  const std::size_t imu = m.Watch("ddl/imu", 0.0);
  const std::size_t pose = m.Watch("dl/pose", 1.0);
  const std::size_t cmd = m.Watch("dl/drive_command", 0.0);
  m.Start(T(0.0));
  Accept(m, imu, 1, 0.1, 0.1);
  Accept(m, pose, 1, 0.1, 0.1);
  Accept(m, cmd, 1, 0.1, 0.1);
  m.OnRejected(cmd, "primitive = 9 is not a DrivePrimitive", T(0.2));
  Accept(m, imu, 5, 0.3, 0.3);  // gap
  // At 0.9 s: imu stale (fault), the command rejected, imu gap (degraded); pose fresh.
  InputReport r = m.Report(T(0.9));
  ASSERT_EQ(r.verdict, InputVerdict::kFault);
  ASSERT_EQ(r.findings.size(), 3u);
  EXPECT_EQ(r.findings[0].topic, "ddl/imu");
  EXPECT_EQ(r.findings[0].problem, InputProblem::kStale);
  EXPECT_EQ(r.findings[1].topic, "dl/drive_command");
  EXPECT_EQ(r.findings[1].problem, InputProblem::kRejected);
  EXPECT_EQ(r.findings[2].problem, InputProblem::kSeqGap);
  EXPECT_EQ(r.reason, "ddl/imu stale: no sample since t = 0.3 s (limit 0.5 s) (+2 more)");
  // Later the pose goes stale too; two stale inputs: the one stale most recently first.
  r = m.Report(T(1.2));
  ASSERT_GE(r.findings.size(), 2u);
  EXPECT_EQ(r.findings[0].topic, "dl/pose");
  EXPECT_EQ(r.findings[1].topic, "ddl/imu");
}

TEST(InputMonitor, StartClearsEverything) {
  InputMonitor m = MakeMonitor();
  ASSERT_TRUE(m.Declare("dl/pose", Limit(0.5)).ok());
  const std::size_t i = m.Watch("dl/pose", 0.0);
  m.Start(T(0.0));
  Accept(m, i, 1, 0.1, 0.1);
  m.OnRejected(i, "bad", T(0.2));
  EXPECT_NE(m.Report(T(0.3)).verdict, InputVerdict::kNominal);
  m.Start(T(10.0));
  EXPECT_EQ(m.Report(T(10.1)).verdict, InputVerdict::kNominal);
  Accept(m, i, 900, 10.2, 10.2);  // a writer's first sample after the restart: no gap
  EXPECT_EQ(m.Report(T(10.3)).verdict, InputVerdict::kNominal);
}

TEST(InputParams, DeclaredOnceAndReadBack) {
  ParamSet params("svc");
  const std::vector<InputSpec> inputs = {{"dl/pose", Limit(1.0)}, {"ddl/imu", Limit(0.25)}};
  DeclareInputParams(params, inputs);
  EXPECT_EQ(InputParamKey("dl/pose"), "dl_pose");
  ASSERT_TRUE(params.SetFromString("inputs.dl_pose.max_age_s=2.5").ok());
  ASSERT_TRUE(params.SetFromString("inputs.hold_s=4").ok());
  ASSERT_TRUE(params.SetFromString("inputs.ddl_imu.check_seq=false").ok());
  auto m = InputMonitor::FromParams(params, inputs);
  ASSERT_TRUE(m.ok()) << m.status().message();
  EXPECT_DOUBLE_EQ(m->options().hold_s, 4.0);
  ASSERT_NE(m->LimitsOf("dl/pose"), nullptr);
  EXPECT_DOUBLE_EQ(m->LimitsOf("dl/pose")->max_age_s, 2.5);
  EXPECT_FALSE(m->LimitsOf("ddl/imu")->check_seq);
  EXPECT_DOUBLE_EQ(m->LimitsOf("ddl/imu")->max_age_s, 0.25);
  // A bad value is an error naming the key.
  const Status bad = params.SetFromString("inputs.dl_pose.max_age_s=-1");
  if (bad.ok()) {
    auto r = InputMonitor::FromParams(params, inputs);
    ASSERT_FALSE(r.ok());
    EXPECT_NE(r.status().message().find("inputs.dl_pose.max_age_s"), std::string::npos);
  } else {
    EXPECT_NE(bad.message().find("inputs.dl_pose.max_age_s"), std::string::npos);
  }
}

// Data captured long before it arrives (a range image delayed 3 s) is late while it keeps
// arriving: a staleness limit alone never saw it (issue 37: "delay dl/range_image 3 s" went
// unnoticed).
TEST(InputMonitor, LateSamplesAreDegradedWhileTheyComeAndForgottenAfterHold) {
  InputMonitor m = MakeMonitor();
  InputLimits l;
  l.max_latency_s = 2.0;
  ASSERT_TRUE(m.Declare("dl/range_image", l).ok());
  const std::size_t i = m.Watch("dl/range_image", 0.0);
  m.Start(T(0.0));
  Accept(m, i, 1, 10.0, 10.5);  // 0.5 s after capture: fine
  EXPECT_EQ(m.Report(T(10.6)).verdict, InputVerdict::kNominal);
  Accept(m, i, 2, 12.0, 15.0);  // 3 s: late
  Accept(m, i, 3, 14.0, 16.5);  // still late: the episode keeps its first reason
  const InputReport r = m.Report(T(16.6));
  EXPECT_EQ(r.verdict, InputVerdict::kDegraded);
  EXPECT_EQ(r.reason, "dl/range_image late: a sample stamped t = 12 s arrived 3 s later (limit 2 s)");
  ASSERT_EQ(r.findings.size(), 1u);
  EXPECT_EQ(r.findings[0].problem, InputProblem::kLate);
  // hold_s (2 s) after the last late sample it is forgotten.
  EXPECT_EQ(m.Report(T(18.6)).verdict, InputVerdict::kNominal);
  // Without a limit nothing is late.
  InputMonitor open = MakeMonitor();
  const std::size_t j = open.Watch("dl/range_image", 0.0);
  open.Start(T(0.0));
  Accept(open, j, 1, 1.0, 60.0);
  EXPECT_EQ(open.Report(T(60.1)).verdict, InputVerdict::kNominal);
  InputLimits bad;
  bad.max_latency_s = -1.0;
  EXPECT_NE(bad.Validate().message().find("max_latency_s"), std::string::npos);
}

}  // namespace
}  // namespace rover::runtime
