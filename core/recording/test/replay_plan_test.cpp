#include "rover/recording/replay_plan.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <functional>

#include "recording_test_util.hpp"
#include "rover/recording/schema.hpp"
#include "rover/recording/session.hpp"

namespace rover::recording {
namespace {

namespace fs = std::filesystem;

const std::vector<CatalogTopic> kCatalog = {
    {"sim/clock", "rover_sim_Clock"},
    {"ddl/imu", "rover_ddl_Imu"},
    {"ddl/joint_state", "rover_ddl_JointState"},
    {"dl/pose", "rover_dl_PoseEstimate"},
};

class ReplayPlanTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::MakeTempDir("replay-plan"); }
  void TearDown() override { fs::remove_all(dir_); }

  /// A recording of ddl/imu, ddl/joint_state and dl/pose (and sim/clock when `clock`).
  std::string Record(bool clock) {
    const std::string path = dir_ + (clock ? "/with-clock.mcap" : "/no-clock.mcap");
    auto s = RecordingSession::Create(path, mcap::WriterOptions{});
    EXPECT_TRUE(s.ok());
    std::vector<std::size_t> ids;
    for (const auto& t : kCatalog) {
      if (t.name == "sim/clock" && !clock) continue;
      ids.push_back(*(*s)->AddTopic(t.name, t.c_type_name));
    }
    for (int i = 1; i <= 10; ++i) {
      for (std::size_t k = 0; k < ids.size(); ++k) {
        EXPECT_TRUE((*s)->Write(ids[k], i * 10'000'000, testing::HeaderSample(i * 10'000'000, i)).ok());
      }
    }
    EXPECT_TRUE((*s)->Close().ok());
    return path;
  }

  /// A recording with one channel on `topic` as given (schema name, encodings, text).
  std::string Odd(const std::string& topic, const std::string& schema_name,
                  const std::string& schema_encoding, const std::string& text,
                  const std::string& message_encoding = "cdr") {
    const std::string path = dir_ + "/odd.mcap";
    auto w = mcap::Writer::Create(path, mcap::WriterOptions{});
    EXPECT_TRUE(w.ok());
    std::uint16_t schema = 0;
    if (!schema_name.empty()) schema = *(*w)->AddSchema(schema_name, schema_encoding, mcap::AsBytes(text));
    const std::uint16_t ch = *(*w)->AddChannel(topic, message_encoding, schema);
    const auto data = testing::HeaderSample(1, 1);
    EXPECT_TRUE((*w)->WriteMessage({ch, 1, 5, 5, data}).ok());
    EXPECT_TRUE((*w)->Close().ok());
    return path;
  }

  Result<ReplayPlan> Plan(const std::string& path, ReplaySelection sel = {}) {
    auto r = mcap::Reader::Open(path);
    EXPECT_TRUE(r.ok()) << r.status().message();
    reader_ = std::move(*r);
    return PlanReplay(*reader_, sel, kCatalog);
  }

  std::string dir_;
  std::unique_ptr<mcap::Reader> reader_;
};

TEST_F(ReplayPlanTest, SelectsTopicsAndTheRecordedClock) {
  ReplaySelection sel;
  sel.topics.include = {"ddl/*"};
  auto plan = Plan(Record(true), sel);
  ASSERT_TRUE(plan.ok()) << plan.status().message();
  std::vector<std::string> names;
  for (const auto& t : plan->topics) names.push_back(t.name);
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"ddl/imu", "ddl/joint_state", "sim/clock"}));
  EXPECT_TRUE(plan->clock_recorded);
  EXPECT_FALSE(plan->synthesize_clock);
  EXPECT_EQ(plan->messages, 30u);
  EXPECT_EQ(plan->start_time, 10'000'000u);
  EXPECT_EQ(plan->end_time, 100'000'000u);
  for (const auto& t : plan->topics) {
    EXPECT_EQ(t.messages, 10u);
    ASSERT_EQ(t.channels.size(), 1u);
    EXPECT_EQ(plan->topics[plan->topic_of_channel.at(t.channels[0])].name, t.name);
  }
}

TEST_F(ReplayPlanTest, ClockIsMadeUpWhenNotRecordedAndLeftOutOnRequest) {
  ReplaySelection sel;
  sel.topics.include = {"dl/pose"};
  auto plan = Plan(Record(false), sel);
  ASSERT_TRUE(plan.ok()) << plan.status().message();
  EXPECT_EQ(plan->topics.size(), 1u);
  EXPECT_FALSE(plan->clock_recorded);
  EXPECT_TRUE(plan->synthesize_clock);
  sel.clock = false;
  auto no_clock = Plan(Record(true), sel);
  ASSERT_TRUE(no_clock.ok());
  EXPECT_EQ(no_clock->topics.size(), 1u);
  EXPECT_FALSE(no_clock->synthesize_clock);
}

TEST_F(ReplayPlanTest, NothingSelectedIsAnError) {
  ReplaySelection sel;
  sel.topics.include = {"apl/*"};
  auto plan = Plan(Record(true), sel);
  EXPECT_EQ(plan.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(plan.status().message().find("apl/* selects no topic of the recording"),
            std::string::npos)
      << plan.status().message();
}

TEST_F(ReplayPlanTest, TypeDifferingFromTheCatalogNamesTopicAndBothTypes) {
  auto range = SchemaForType("rover_dl_RangeImage");
  ASSERT_TRUE(range.ok());
  auto plan = Plan(Odd("dl/pose", range->name, "omgidl", range->text));
  ASSERT_FALSE(plan.ok());
  EXPECT_NE(plan.status().message().find("odd.mcap: topic 'dl/pose': the recording's type is "
                                         "rover::dl::RangeImage, the catalog's is "
                                         "rover::dl::PoseEstimate"),
            std::string::npos)
      << plan.status().message();
}

TEST_F(ReplayPlanTest, UnknownSchemasAndTopicsAreRefused) {
  auto pose = SchemaForType("rover_dl_PoseEstimate");
  ASSERT_TRUE(pose.ok());
  const std::vector<std::pair<std::function<std::string()>, std::string>> cases = {
      {[&] { return Odd("dl/pose", "", "", ""); }, "topic 'dl/pose' has no schema"},
      {[&] { return Odd("dl/pose", pose->name, "ros2msg", "float64 x"); },
       "schema 'rover::dl::PoseEstimate' has encoding 'ros2msg', not omgidl"},
      {[&] { return Odd("dl/pose", pose->name, "omgidl", pose->text, "json"); },
       "topic 'dl/pose': message encoding 'json', not cdr"},
      {[&] { return Odd("x/unknown", pose->name, "omgidl", pose->text); },
       "topic 'x/unknown' is not in this build's topic catalog"},
      {[&] { return Odd("dl/pose", pose->name, "omgidl", "module rover { module dl { struct PoseEstimate { double x; }; }; };"); },
       "the recording's IDL of rover::dl::PoseEstimate differs from this build's"},
  };
  for (const auto& [make, expected] : cases) {
    auto plan = Plan(make());
    ASSERT_FALSE(plan.ok()) << expected;
    EXPECT_EQ(plan.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(plan.status().message().find(expected), std::string::npos)
        << plan.status().message();
  }
  // The same IDL with other comments and layout is this build's; a changed one may be forced.
  const std::string relaid = "/* recorded elsewhere */\n" + pose->text + "\n// the end\n";
  EXPECT_TRUE(Plan(Odd("dl/pose", pose->name, "omgidl", relaid)).ok());
  ReplaySelection force;
  force.accept_schema_changes = true;
  EXPECT_TRUE(Plan(Odd("dl/pose", pose->name, "omgidl",
                       "module rover { module dl { struct PoseEstimate { double x; }; }; };"),
                   force)
                  .ok());
}

TEST(ReplayPacer, RateScalesLogTimeAndZeroIsAtOnce) {
  ReplayPacer real(1.0);
  EXPECT_EQ(real.DueAfterNs(5'000'000'000), 0);
  EXPECT_EQ(real.DueAfterNs(6'000'000'000), 1'000'000'000);
  EXPECT_EQ(real.DueAfterNs(4'000'000'000), 0) << "earlier than the first (a reset): at once";
  ReplayPacer fast(4.0);
  EXPECT_EQ(fast.DueAfterNs(0), 0);
  EXPECT_EQ(fast.DueAfterNs(2'000'000'000), 500'000'000);
  ReplayPacer slow(0.5);
  (void)slow.DueAfterNs(0);
  EXPECT_EQ(slow.DueAfterNs(1'000), 2'000);
  ReplayPacer now(0);
  (void)now.DueAfterNs(0);
  EXPECT_EQ(now.DueAfterNs(9'000'000'000), 0);
}

TEST(ClockTicks, OnePerPeriodOnMultiplesAndOneAtTheStart) {
  ClockTicks ticks(10);
  EXPECT_EQ(ticks.Before(25), (std::vector<mcap::Timestamp>{25}));
  EXPECT_EQ(ticks.Before(29), (std::vector<mcap::Timestamp>{}));
  EXPECT_EQ(ticks.Before(30), (std::vector<mcap::Timestamp>{30}));
  EXPECT_EQ(ticks.Before(62), (std::vector<mcap::Timestamp>{40, 50, 60}));
  EXPECT_EQ(ticks.Before(62), (std::vector<mcap::Timestamp>{}));
  EXPECT_EQ(ticks.Before(5), (std::vector<mcap::Timestamp>{5})) << "the log went back";
  EXPECT_EQ(ticks.Before(10), (std::vector<mcap::Timestamp>{10}));
}

}  // namespace
}  // namespace rover::recording
