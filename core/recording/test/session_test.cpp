#include "rover/recording/session.hpp"

#include <gtest/gtest.h>

#include <filesystem>

#include "recording_test_util.hpp"
#include "rover/mcap/info.hpp"
#include "rover/mcap/reader.hpp"
#include "rover/recording/schema.hpp"

namespace rover::recording {
namespace {

namespace fs = std::filesystem;

class SessionTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::MakeTempDir("session"); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string dir_;
};

TEST_F(SessionTest, ChannelsSchemasAndTimes) {
  const std::string path = dir_ + "/run.mcap";
  auto s = RecordingSession::Create(path, mcap::WriterOptions{});
  ASSERT_TRUE(s.ok()) << s.status().message();
  auto pose = (*s)->AddTopic("dl/pose", "rover_dl_PoseEstimate", {{"qos_profile", "state"}});
  auto imu = (*s)->AddTopic("ddl/imu", "rover_ddl_Imu");
  auto unused = (*s)->AddTopic("dl/drive_command", "rover_dl_DriveCommand");
  ASSERT_TRUE(pose.ok() && imu.ok() && unused.ok());
  EXPECT_EQ((*s)->AddTopic("x/y", "rover_x_Nothing").status().message(),
            "topic 'x/y': no @topic type 'rover_x_Nothing' in this build's IDL files");
  // Log time = reception; publish time = header.stamp_ns (log time when the stamp is 0).
  ASSERT_TRUE((*s)->Write(*pose, 2'000, testing::HeaderSample(1'500, 1)).ok());
  ASSERT_TRUE((*s)->Write(*imu, 2'100, testing::HeaderSample(0, 1)).ok());
  ASSERT_TRUE((*s)->Write(*pose, 3'000, testing::HeaderSample(2'500, 2, 40)).ok());
  ASSERT_TRUE((*s)->Write(*imu, -5, std::vector<std::uint8_t>{0, 1}).ok());  // no header: kept
  (*s)->CountLost(*imu, 3);
  ASSERT_TRUE((*s)->Close({{"domain", "117"}}).ok());
  const SessionStats& st = (*s)->stats();
  EXPECT_EQ(st.messages, 4u);
  EXPECT_EQ(st.lost, 3u);
  EXPECT_EQ(st.topics[1].header_errors, 1u);
  EXPECT_EQ(st.topics[0].messages, 2u);
  EXPECT_EQ(st.first_log_time_ns, 0);
  EXPECT_EQ(st.last_log_time_ns, 3'000);
  EXPECT_EQ(st.file_bytes, fs::file_size(path));

  mcap::ReaderOptions ro;
  ro.verification = mcap::Verification::kFull;
  auto r = mcap::Reader::Open(path, ro);
  ASSERT_TRUE(r.ok()) << r.status().message();
  ASSERT_EQ((*r)->channels().size(), 2u) << "a topic without messages gets no channel";
  std::map<std::string, const mcap::Channel*> by_topic;
  for (const auto& [id, c] : (*r)->channels()) by_topic[c.topic] = &c;
  ASSERT_TRUE(by_topic.count("dl/pose"));
  const mcap::Channel& pc = *by_topic["dl/pose"];
  EXPECT_EQ(pc.message_encoding, "cdr");
  EXPECT_EQ(pc.metadata.at("qos_profile"), "state");
  const mcap::Schema& schema = (*r)->schemas().at(pc.schema_id);
  EXPECT_EQ(schema.name, "rover::dl::PoseEstimate");
  EXPECT_EQ(schema.encoding, "omgidl");
  EXPECT_EQ(std::string(schema.data.begin(), schema.data.end()),
            SchemaForType("rover_dl_PoseEstimate")->text);
  std::vector<std::tuple<std::string, std::uint32_t, mcap::Timestamp, mcap::Timestamp>> got;
  ASSERT_TRUE((*r)->ForEachMessage({}, [&](const mcap::MessageEvent& e) {
                  got.emplace_back(e.channel->topic, e.message.sequence, e.message.log_time,
                                   e.message.publish_time);
                  return Status::Ok();
                }).ok());
  using T = std::tuple<std::string, std::uint32_t, mcap::Timestamp, mcap::Timestamp>;
  EXPECT_EQ(got, (std::vector<T>{T{"ddl/imu", 2, 0, 0}, T{"dl/pose", 1, 2000, 1500},
                                 T{"ddl/imu", 1, 2100, 2100}, T{"dl/pose", 2, 3000, 2500}}));
  auto meta = (*r)->ReadAllMetadata();
  ASSERT_TRUE(meta.ok());
  bool found = false;
  for (const auto& m : *meta) {
    if (m.name != kRecorderMetadataName) continue;
    found = true;
    EXPECT_EQ(m.metadata.at("domain"), "117");
    EXPECT_EQ(m.metadata.at("messages"), "4");
    EXPECT_EQ(m.metadata.at("samples_lost"), "3");
  }
  EXPECT_TRUE(found);
}

TEST_F(SessionTest, SizeCapEndsWithACompleteMarkedPrefix) {
  const std::string path = dir_ + "/capped.mcap";
  mcap::WriterOptions o;
  o.size_cap_bytes = 60'000;  // the schema (ddl + hw + common IDL) takes ~2 x 10 kB of it
  o.chunk_bytes = 4'096;
  o.compression = mcap::Compression::kNone;
  auto s = RecordingSession::Create(path, o);
  ASSERT_TRUE(s.ok());
  auto t = (*s)->AddTopic("ddl/imu", "rover_ddl_Imu");
  ASSERT_TRUE(t.ok());
  for (int i = 0; i < 400; ++i) {
    ASSERT_TRUE((*s)->Write(*t, i * 1000, testing::HeaderSample(i * 1000, i, 200)).ok()) << i;
  }
  EXPECT_TRUE((*s)->capped());
  ASSERT_TRUE((*s)->Close().ok());
  const SessionStats& st = (*s)->stats();
  EXPECT_TRUE(st.capped);
  EXPECT_GT(st.messages, 0u);
  EXPECT_GT(st.dropped, 0u);
  EXPECT_EQ(st.messages + st.dropped, 400u);
  EXPECT_LE(fs::file_size(path), 60'000u);
  auto info = mcap::SummarizeFile(path);
  ASSERT_TRUE(info.ok()) << info.status().message();
  EXPECT_TRUE(info->truncation.has_value());
  EXPECT_EQ(info->message_count, st.messages);
}

TEST_F(SessionTest, FullDiskAndUnwritablePathsAreErrorsAndNothingLooksComplete) {
  auto bad = RecordingSession::Create(dir_ + "/no/such/dir/x.mcap", mcap::WriterOptions{});
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("cannot record to " + dir_ + "/no/such/dir/x.mcap"),
            std::string::npos)
      << bad.status().message();

  auto full = RecordingSession::Create("/dev/full", mcap::WriterOptions{});
  if (!full.ok()) {
    EXPECT_NE(full.status().message().find("/dev/full"), std::string::npos);
    return;
  }
  auto t = (*full)->AddTopic("ddl/imu", "rover_ddl_Imu");
  ASSERT_TRUE(t.ok());
  Status first;
  for (int i = 0; i < 20'000 && first.ok(); ++i) {
    first = (*full)->Write(*t, i, testing::HeaderSample(i, i, 400));
  }
  const Status closed = (*full)->Close();
  EXPECT_FALSE(closed.ok());
  EXPECT_EQ(closed.code(), StatusCode::kUnavailable);
  EXPECT_NE(closed.message().find("No space left on device"), std::string::npos)
      << closed.message();
  EXPECT_FALSE((*full)->failure().ok());
  EXPECT_FALSE((*full)->Write(*t, 1, testing::HeaderSample(1, 1)).ok()) << "errors are sticky";
}

TEST(LogClock, SimTimeFromClockSamplesOrWallTime) {
  LogClock sim(LogClock::Mode::kSim);
  EXPECT_EQ(sim.Now(), 0);
  EXPECT_FALSE(sim.heard_clock());
  ClockSample c;
  c.sim_time_ns = 42'000;
  sim.OnClockSample(WriteClockSample(c));
  EXPECT_EQ(sim.Now(), 42'000);
  EXPECT_TRUE(sim.heard_clock());
  sim.OnClockSample(std::vector<std::uint8_t>{0, 1, 0});
  EXPECT_EQ(sim.Now(), 42'000);
  EXPECT_EQ(sim.unreadable(), 1u);
  LogClock wall(LogClock::Mode::kWall);
  wall.OnClockSample(WriteClockSample(c));
  EXPECT_GT(wall.Now(), 1'600'000'000'000'000'000);  // after 2020: CLOCK_REALTIME
}

}  // namespace
}  // namespace rover::recording
