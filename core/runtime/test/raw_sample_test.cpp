#include "rover/runtime/raw_sample.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cstring>
#include <thread>
#include <vector>

#include "rover/runtime/topic_catalog.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::dds {
namespace {

class RawSampleTest : public ::testing::Test {
 protected:
  void SetUp() override {
    lease_ = testing::IsolatedDomain();
    auto p = Participant::Create(lease_.domain());
    ASSERT_TRUE(p.ok()) << p.status().message();
    participant_ = std::move(*p);
  }
  DomainLease lease_;
  Participant participant_;
};

TEST(TypeTable, EveryCatalogTypeHasItsDescriptorAndScopedName) {
  for (const auto& t : TopicCatalog()) {
    const dds_topic_descriptor_t* d = dds::DescriptorForType(t.type_name);
    ASSERT_NE(d, nullptr) << t.name;
    // rover_dl_PoseEstimate -> rover::dl::PoseEstimate
    std::string scoped(t.type_name);
    scoped.replace(scoped.find('_'), 1, "::");
    scoped.replace(scoped.find('_'), 1, "::");
    EXPECT_EQ(std::string(d->m_typename), scoped) << t.name;
  }
  EXPECT_EQ(dds::DescriptorForType("rover_dl_Nothing"), nullptr);
}

TEST_F(RawSampleTest, TypedToRawToRawToTypedKeepsTheBytes) {
  auto typed_w = Writer<rover_dl_PoseEstimate>::Create(participant_, "dl/pose");
  const auto* desc = dds::DescriptorForType("rover_dl_PoseEstimate");
  auto raw_r = RawReader::Create(participant_, "dl/pose", desc, QosProfile::kState);
  ASSERT_TRUE(typed_w.ok() && raw_r.ok()) << raw_r.status().message();
  ASSERT_TRUE(testing::WaitFor([&] { return raw_r->MatchedWriters() == 1; }));

  rover_dl_PoseEstimate pose{};
  pose.header.stamp_ns = 123'456'789;
  CopyString(pose.header.frame_id, "site");
  pose.header.seq = 5;
  pose.pose.position.x = 1.25;
  pose.pose.orientation.w = 1;
  ASSERT_TRUE(typed_w->Write(pose).ok());
  std::vector<std::uint8_t> bytes;
  ASSERT_TRUE(testing::WaitFor([&] {
    raw_r->TakeEach([&](std::span<const std::uint8_t> b, const dds_sample_info_t& info) {
      EXPECT_TRUE(info.valid_data);
      bytes.assign(b.begin(), b.end());
    });
    return !bytes.empty();
  }));
  // XCDR1 little-endian (the types are @final): header 00 01, stamp first in the payload.
  ASSERT_GE(bytes.size(), 12u);
  EXPECT_EQ(bytes[0], 0x00);
  EXPECT_EQ(bytes[1], 0x01);
  std::int64_t stamp = 0;
  std::memcpy(&stamp, bytes.data() + 4, 8);
  EXPECT_EQ(stamp, 123'456'789);

  // The bytes republished by a raw writer on another topic of the type reach a typed reader
  // and a raw reader unchanged.
  auto raw_w = RawWriter::Create(participant_, "dl/pose_odometry", desc, QosProfile::kState);
  auto typed_r = Reader<rover_dl_PoseEstimate>::Create(participant_, "dl/pose_odometry");
  auto raw_r2 = RawReader::Create(participant_, "dl/pose_odometry", desc, QosProfile::kState);
  ASSERT_TRUE(raw_w.ok() && typed_r.ok() && raw_r2.ok()) << raw_w.status().message();
  ASSERT_TRUE(testing::WaitFor([&] { return raw_w->MatchedReaders() == 2; }));
  ASSERT_TRUE(raw_w->Write(bytes).ok());
  std::vector<OwnedSample<rover_dl_PoseEstimate>> got;
  ASSERT_TRUE(testing::WaitFor([&] {
    for (auto& s : typed_r->Take()) got.push_back(std::move(s));
    return !got.empty();
  }));
  EXPECT_EQ(got[0]->header.stamp_ns, 123'456'789);
  EXPECT_EQ(got[0]->header.seq, 5u);
  EXPECT_STREQ(got[0]->header.frame_id, "site");
  EXPECT_EQ(got[0]->pose.position.x, 1.25);
  std::vector<std::uint8_t> again;
  ASSERT_TRUE(testing::WaitFor([&] {
    raw_r2->TakeEach([&](std::span<const std::uint8_t> b, const dds_sample_info_t&) {
      again.assign(b.begin(), b.end());
    });
    return !again.empty();
  }));
  EXPECT_EQ(again, bytes);
  EXPECT_EQ(raw_r->LostSamples(), 0u);
}

TEST_F(RawSampleTest, KeyedLatchedTopicsAndKeepAllHistory) {
  // dl/drive_status is latched (transient-local) and keyed by command_id: a raw reader created
  // after the writes still gets the last sample of every key.
  auto w = Writer<rover_dl_DriveStatus>::Create(participant_, "dl/drive_status");
  ASSERT_TRUE(w.ok());
  for (std::uint32_t id = 1; id <= 3; ++id) {
    rover_dl_DriveStatus s{};
    s.command_id = id;
    s.header.seq = id;
    ASSERT_TRUE(w->Write(s).ok());
  }
  const auto* desc = dds::DescriptorForType("rover_dl_DriveStatus");
  auto r = RawReader::Create(participant_, "dl/drive_status", desc, QosProfile::kLatched);
  ASSERT_TRUE(r.ok());
  std::size_t n = 0;
  ASSERT_TRUE(testing::WaitFor([&] {
    n += r->TakeEach([](std::span<const std::uint8_t>, const dds_sample_info_t&) {});
    return n == 3;
  }));
  // A state (keep-last 1) topic: the raw reader keeps all 50 samples until taken.
  auto sw = Writer<rover_dl_PoseEstimate>::Create(participant_, "dl/pose");
  auto sr = RawReader::Create(participant_, "dl/pose", dds::DescriptorForType("rover_dl_PoseEstimate"),
                              QosProfile::kState);
  ASSERT_TRUE(sw.ok() && sr.ok());
  ASSERT_TRUE(testing::WaitFor([&] { return sr->MatchedWriters() == 1; }));
  for (int i = 0; i < 50; ++i) {
    rover_dl_PoseEstimate p{};
    p.header.seq = static_cast<std::uint32_t>(i + 1);
    ASSERT_TRUE(sw->Write(p).ok());
  }
  std::size_t got = 0;
  ASSERT_TRUE(testing::WaitFor([&] {
    got += sr->TakeEach([](std::span<const std::uint8_t>, const dds_sample_info_t&) {});
    return got >= 50;
  }));
  EXPECT_EQ(got, 50u);
}

TEST_F(RawSampleTest, MalformedBytesAreRefusedAndNothingIsPublished) {
  const auto* desc = dds::DescriptorForType("rover_dl_PoseEstimate");
  auto w = RawWriter::Create(participant_, "dl/pose", desc, QosProfile::kState);
  auto r = RawReader::Create(participant_, "dl/pose", desc, QosProfile::kState);
  ASSERT_TRUE(w.ok() && r.ok());
  ASSERT_TRUE(testing::WaitFor([&] { return w->MatchedReaders() == 1; }));
  const Status short_sample = w->Write(std::vector<std::uint8_t>{0, 1});
  EXPECT_EQ(short_sample.code(), StatusCode::kInvalidArgument);
  // A frame_id length that runs past the end of the sample.
  std::vector<std::uint8_t> bad = {0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 0xff, 0xff, 0, 0};
  const Status s = w->Write(bad);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument) << s.message();
  EXPECT_NE(s.message().find("is not a valid sample of its type"), std::string::npos);
  std::this_thread::sleep_for(std::chrono::milliseconds(200));
  EXPECT_EQ(r->TakeEach([](std::span<const std::uint8_t>, const dds_sample_info_t&) {}), 0u);
}

}  // namespace
}  // namespace rover::dds
