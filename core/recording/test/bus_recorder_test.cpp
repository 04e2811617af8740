#include "rover/recording/bus_recorder.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <algorithm>
#include <chrono>
#include <map>
#include <thread>

#include "recording_test_util.hpp"
#include "rover/mcap/reader.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::recording {
namespace {

namespace fs = std::filesystem;

class BusRecorderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    lease_ = rover::testing::IsolatedDomain();
    auto a = dds::Participant::Create(lease_.domain());
    auto b = dds::Participant::Create(lease_.domain());
    ASSERT_TRUE(a.ok() && b.ok());
    recorder_participant_ = std::move(*a);
    stack_ = std::move(*b);
    dir_ = testing::MakeTempDir("bus-recorder");
  }
  void TearDown() override { fs::remove_all(dir_); }

  void Tick(dds::Writer<rover_sim_Clock>& clock, std::int64_t t) {
    rover_sim_Clock c{};
    c.header.stamp_ns = t;
    c.sim_time_ns = t;
    ASSERT_TRUE(clock.Write(c).ok());
  }

  dds::DomainLease lease_;
  dds::Participant recorder_participant_, stack_;
  std::string dir_;
};

TEST_F(BusRecorderTest, RecordsCatalogTopicsWithRunClockLogTimes) {
  // A latched status published before the recorder exists is caught (transient-local).
  auto status = dds::Writer<rover_dl_DriveStatus>::Create(stack_, "dl/drive_status");
  ASSERT_TRUE(status.ok());
  rover_dl_DriveStatus st{};
  st.command_id = 9;
  st.header.stamp_ns = 1;
  ASSERT_TRUE(status->Write(st).ok());

  BusRecorderOptions o;
  o.record.path = dir_ + "/run.mcap";
  o.record.topics.exclude = {"sim/truth"};
  o.metadata = {{"domain", std::to_string(lease_.domain())}};
  auto rec = BusRecorder::Create(recorder_participant_, o);
  ASSERT_TRUE(rec.ok()) << rec.status().message();
  const auto topics = (*rec)->topics();
  EXPECT_EQ(std::count(topics.begin(), topics.end(), "sim/truth"), 0);
  EXPECT_EQ(std::count(topics.begin(), topics.end(), "sys/event"), 1);
  ASSERT_TRUE((*rec)->Start().ok());

  auto clock = dds::Writer<rover_sim_Clock>::Create(stack_, "sim/clock");
  auto pose = dds::Writer<rover_dl_PoseEstimate>::Create(stack_, "dl/pose");
  auto truth = dds::Writer<rover_sim_Truth>::Create(stack_, "sim/truth");
  ASSERT_TRUE(clock.ok() && pose.ok() && truth.ok());
  ASSERT_TRUE(rover::testing::WaitFor([&] { return pose->MatchedReaders() >= 1 && clock->MatchedReaders() >= 1; }));
  constexpr int kPoses = 40;
  for (int i = 1; i <= kPoses; ++i) {
    const std::int64_t t = i * 100'000'000LL;
    Tick(*clock, t);
    // Wait until the recorder has taken the tick, so the pose is stamped with it.
    ASSERT_TRUE(rover::testing::WaitFor([&] {
      for (const auto& ts : (*rec)->Snapshot().topics) {
        if (ts.topic == "sim/clock") return ts.messages == static_cast<std::uint64_t>(i);
      }
      return false;
    }));
    rover_dl_PoseEstimate p{};
    p.header.stamp_ns = t - 5'000'000;  // valid 5 ms before it was received
    p.header.seq = static_cast<std::uint32_t>(i);
    ASSERT_TRUE(pose->Write(p).ok());
    rover_sim_Truth tr{};
    ASSERT_TRUE(truth->Write(tr).ok());
    // And until it has taken the pose, before the clock moves on.
    ASSERT_TRUE(rover::testing::WaitFor([&] {
      for (const auto& ts : (*rec)->Snapshot().topics) {
        if (ts.topic == "dl/pose") return ts.messages == static_cast<std::uint64_t>(i);
      }
      return false;
    }));
  }
  ASSERT_TRUE(rover::testing::WaitFor([&] {
    for (const auto& ts : (*rec)->Snapshot().topics) {
      if (ts.topic == "dl/pose") return ts.messages == kPoses;
    }
    return false;
  }));
  const RecordingReport report = (*rec)->Stop();
  ASSERT_TRUE(report.status.ok()) << report.status.message();
  EXPECT_EQ(report.stats.lost, 0u);
  EXPECT_GT(report.cpu_s, 0.0);

  auto r = mcap::Reader::Open(report.path);
  ASSERT_TRUE(r.ok()) << r.status().message();
  std::map<std::string, int> count;
  std::vector<std::pair<mcap::Timestamp, mcap::Timestamp>> pose_times;
  ASSERT_TRUE((*r)->ForEachMessage({}, [&](const mcap::MessageEvent& e) {
                  ++count[e.channel->topic];
                  if (e.channel->topic == "dl/pose") {
                    pose_times.emplace_back(e.message.log_time, e.message.publish_time);
                    EXPECT_EQ(e.schema->name, "rover::dl::PoseEstimate");
                    EXPECT_EQ(e.schema->encoding, "omgidl");
                  }
                  return Status::Ok();
                }).ok());
  EXPECT_EQ(count["dl/pose"], kPoses);
  EXPECT_EQ(count["sim/clock"], kPoses);
  EXPECT_EQ(count["dl/drive_status"], 1);
  EXPECT_EQ(count.count("sim/truth"), 0u);
  ASSERT_EQ(pose_times.size(), static_cast<std::size_t>(kPoses));
  for (int i = 0; i < kPoses; ++i) {
    const auto t = static_cast<mcap::Timestamp>((i + 1) * 100'000'000LL);
    EXPECT_EQ(pose_times[i].first, t) << "log time = the run clock at reception";
    EXPECT_EQ(pose_times[i].second, t - 5'000'000) << "publish time = header.stamp_ns";
  }
}

TEST_F(BusRecorderTest, BadOptionsAndPathsFailAtCreate) {
  BusRecorderOptions o;
  o.record.path = dir_ + "/missing/dir/x.mcap";
  auto bad = BusRecorder::Create(recorder_participant_, o);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("cannot record to"), std::string::npos);
  o.record.path = dir_ + "/x.mcap";
  o.record.topics.include = {"nothing/*"};
  auto none = BusRecorder::Create(recorder_participant_, o);
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.status().message().find("select no topic of the catalog"), std::string::npos);
  o.record.topics.include.clear();
  o.qos_overrides = {{"dl/pose", "sometimes"}};
  auto qos = BusRecorder::Create(recorder_participant_, o);
  ASSERT_FALSE(qos.ok());
  EXPECT_NE(qos.status().message().find("QoS override of dl/pose"), std::string::npos);
}

TEST_F(BusRecorderTest, FullDiskFailsTheRecording) {
  if (!fs::exists("/dev/full")) GTEST_SKIP() << "no /dev/full here";
  BusRecorderOptions o;
  o.record.path = "/dev/full";
  o.record.compression = mcap::Compression::kNone;
  o.clock = LogClock::Mode::kWall;
  auto rec = BusRecorder::Create(recorder_participant_, o);
  ASSERT_TRUE(rec.ok()) << rec.status().message();
  ASSERT_TRUE((*rec)->Start().ok());
  auto frames = dds::Writer<rover_hw_CameraFrame>::Create(stack_, "hw/camera_frame");
  ASSERT_TRUE(frames.ok());
  ASSERT_TRUE(rover::testing::WaitFor([&] { return frames->MatchedReaders() >= 1; }));
  std::vector<std::uint8_t> image(640 * 480, 7);
  rover_hw_CameraFrame f{};
  f.width = 640;
  f.height = 480;
  dds::BorrowSequence(f.left, image);
  dds::BorrowSequence(f.right, image);
  for (int i = 0; i < 30 && (*rec)->health().ok(); ++i) {
    ASSERT_TRUE(frames->Write(f).ok());
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(rover::testing::WaitFor([&] { return !(*rec)->health().ok(); }));
  const RecordingReport report = (*rec)->Stop();
  EXPECT_EQ(report.status.code(), StatusCode::kUnavailable);
  EXPECT_NE(report.status.message().find("No space left on device"), std::string::npos)
      << report.status.message();
}

}  // namespace
}  // namespace rover::recording
