#include "rover/recording/bus_replayer.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <thread>

#include "recording_test_util.hpp"
#include "rover/recording/bus_recorder.hpp"
#include "rover/recording/session.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::recording {
namespace {

namespace fs = std::filesystem;

// A serialised dl/pose sample exactly as Cyclone writes one: PoseEstimate's fields after the
// header are doubles and a few integers; the easiest way to get its bytes right is to let a
// raw reader take a typed sample.
class BusReplayerTest : public ::testing::Test {
 protected:
  void SetUp() override {
    lease_ = rover::testing::IsolatedDomain();
    auto a = dds::Participant::Create(lease_.domain());
    auto b = dds::Participant::Create(lease_.domain());
    ASSERT_TRUE(a.ok() && b.ok());
    replay_ = std::move(*a);
    service_ = std::move(*b);
    dir_ = testing::MakeTempDir("bus-replayer");
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// Records `n` dl/pose samples (x = i) at log times i * 50 ms, and sim/clock when `clock`,
  /// through the bus recorder, so the bytes are Cyclone's own.
  std::string Record(int n, bool clock) {
    const std::string path = dir_ + (clock ? "/clock.mcap" : "/pose.mcap");
    BusRecorderOptions o;
    o.record.path = path;
    o.record.topics.include = {"dl/pose"};
    if (clock) o.record.topics.include.push_back("sim/clock");
    auto rec = BusRecorder::Create(service_, o);
    EXPECT_TRUE(rec.ok()) << rec.status().message();
    EXPECT_TRUE((*rec)->Start().ok());
    auto cw = dds::Writer<rover_sim_Clock>::Create(replay_, "sim/clock");
    auto pw = dds::Writer<rover_dl_PoseEstimate>::Create(replay_, "dl/pose");
    EXPECT_TRUE(rover::testing::WaitFor([&] { return pw->MatchedReaders() >= 1 && cw->MatchedReaders() >= 1; }));
    for (int i = 1; i <= n; ++i) {
      rover_sim_Clock c{};
      c.sim_time_ns = i * 50'000'000LL;
      c.header.stamp_ns = c.sim_time_ns;
      EXPECT_TRUE(cw->Write(c).ok());
      EXPECT_TRUE(rover::testing::WaitFor([&] {
        for (const auto& t : (*rec)->Snapshot().topics) {
          if (t.topic == "sim/clock" && clock) return t.messages == static_cast<std::uint64_t>(i);
        }
        return !clock;
      }));
      if (!clock) std::this_thread::sleep_for(std::chrono::milliseconds(30));
      rover_dl_PoseEstimate p{};
      p.header.stamp_ns = c.sim_time_ns;
      p.header.seq = static_cast<std::uint32_t>(i);
      p.pose.position.x = i;
      EXPECT_TRUE(pw->Write(p).ok());
    }
    EXPECT_TRUE(rover::testing::WaitFor([&] {
      for (const auto& t : (*rec)->Snapshot().topics) {
        if (t.topic == "dl/pose") return t.messages == static_cast<std::uint64_t>(n);
      }
      return false;
    }));
    const RecordingReport report = (*rec)->Stop();
    EXPECT_TRUE(report.status.ok()) << report.status.message();
    return path;
  }

  dds::DomainLease lease_;
  dds::Participant replay_, service_;
  std::string dir_;
};

TEST_F(BusReplayerTest, RepublishesInOrderWithTheRecordedClock) {
  const std::string path = Record(20, true);
  auto reader = mcap::Reader::Open(path);
  ASSERT_TRUE(reader.ok()) << reader.status().message();
  ReplaySelection sel;
  sel.topics.include = {"dl/pose"};
  auto plan = PlanReplay(**reader, sel, CatalogTopics());
  ASSERT_TRUE(plan.ok()) << plan.status().message();
  EXPECT_TRUE(plan->clock_recorded);

  // Keep-last 1 readers, taken on this thread while the replay runs on another.
  auto pose_r = dds::Reader<rover_dl_PoseEstimate>::Create(service_, "dl/pose");
  auto clock_r = dds::Reader<rover_sim_Clock>::Create(service_, "sim/clock");
  ASSERT_TRUE(pose_r.ok() && clock_r.ok());
  std::vector<double> xs;
  std::vector<std::int64_t> clocks;
  std::atomic<bool> done{false};
  Result<ReplayReport> report = Internal("not run");
  std::thread t([&] {
    BusReplayOptions o;
    o.rate = 0.5;  // 100 ms apart: room for a loaded machine to take each one
    o.settle_s = 2.0;  // discovery of the replay's writers, also on a loaded machine
    report = ReplayOnBus(replay_, **reader, *plan, o);
    done = true;
  });
  while (!done) {
    for (auto& s : pose_r->Take()) xs.push_back(s->pose.position.x);
    for (auto& s : clock_r->Take()) clocks.push_back(s->sim_time_ns);
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  t.join();
  // What arrived after the loop's last take (the last clock tick and pose among it).
  ASSERT_TRUE(rover::testing::WaitFor([&] {
    for (auto& s : pose_r->Take()) xs.push_back(s->pose.position.x);
    for (auto& s : clock_r->Take()) clocks.push_back(s->sim_time_ns);
    return !clocks.empty() && clocks.back() == 20 * 50'000'000LL && !xs.empty() &&
           xs.back() == 20.0;
  }));
  ASSERT_TRUE(report.ok()) << report.status().message();
  EXPECT_EQ(report->published.at("dl/pose"), 20u);
  EXPECT_EQ(report->published.at("sim/clock"), 20u);
  EXPECT_EQ(report->clock_ticks, 0u);
  // In order, ending on the last one. dl/pose is a state topic (keep-last 1, latest wins): a
  // loaded machine may let one sample supersede another in the reader, so not every one need
  // be seen, but most are.
  ASSERT_FALSE(xs.empty());
  EXPECT_TRUE(std::adjacent_find(xs.begin(), xs.end(), std::greater_equal<double>()) == xs.end())
      << ::testing::PrintToString(xs);
  EXPECT_EQ(xs.back(), 20.0);
  EXPECT_GE(xs.size(), 15u) << ::testing::PrintToString(xs);
  ASSERT_FALSE(clocks.empty());
  EXPECT_EQ(clocks.back(), 20 * 50'000'000LL);
  EXPECT_TRUE(std::is_sorted(clocks.begin(), clocks.end()));
  // Rate 0.5 takes about twice the recording's span (0.95 s); it is paced, not instant.
  EXPECT_GT(report->wall_s, 1.5);
}

TEST_F(BusReplayerTest, MakesUpTheClockWhenTheRecordingHasNone) {
  const std::string path = Record(5, false);
  auto reader = mcap::Reader::Open(path);
  ASSERT_TRUE(reader.ok());
  auto plan = PlanReplay(**reader, ReplaySelection{}, CatalogTopics());
  ASSERT_TRUE(plan.ok()) << plan.status().message();
  ASSERT_TRUE(plan->synthesize_clock);
  auto clock_r = dds::Reader<rover_sim_Clock>::Create(service_, "sim/clock");
  ASSERT_TRUE(clock_r.ok());
  BusReplayOptions o;
  o.rate = 0;
  o.settle_s = 0.5;
  auto report = ReplayOnBus(replay_, **reader, *plan, o);
  ASSERT_TRUE(report.ok()) << report.status().message();
  EXPECT_EQ(report->published.at("dl/pose"), 5u);
  EXPECT_GT(report->clock_ticks, 0u);
  std::int64_t last = -1;
  ASSERT_TRUE(rover::testing::WaitFor([&] {
    for (auto& s : clock_r->Take()) last = s->sim_time_ns;
    return last >= 0;
  }));
  EXPECT_EQ(static_cast<std::uint64_t>(last), report->last_log_time - report->last_log_time % 10'000'000);
}

TEST_F(BusReplayerTest, ARecordedSampleCycloneRefusesStopsTheReplayNamingIt) {
  const std::string path = dir_ + "/bad.mcap";
  {
    auto s = RecordingSession::Create(path, mcap::WriterOptions{});
    ASSERT_TRUE(s.ok());
    auto t = (*s)->AddTopic("dl/pose", "rover_dl_PoseEstimate");
    ASSERT_TRUE(t.ok());
    // Only a header: PoseEstimate has more fields, so the sample is too short.
    ASSERT_TRUE((*s)->Write(*t, 1'000'000'000, testing::HeaderSample(1, 1)).ok());
    ASSERT_TRUE((*s)->Close().ok());
  }
  auto reader = mcap::Reader::Open(path);
  ASSERT_TRUE(reader.ok());
  ReplaySelection sel;
  sel.clock = false;
  auto plan = PlanReplay(**reader, sel, CatalogTopics());
  ASSERT_TRUE(plan.ok()) << plan.status().message();
  BusReplayOptions o;
  o.settle_s = 0;
  auto report = ReplayOnBus(replay_, **reader, *plan, o);
  ASSERT_FALSE(report.ok());
  EXPECT_NE(report.status().message().find("bad.mcap: message at log time 1.000000000"),
            std::string::npos)
      << report.status().message();
  EXPECT_NE(report.status().message().find("not a valid sample"), std::string::npos);
}

}  // namespace
}  // namespace rover::recording
