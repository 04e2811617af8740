#include "rover/mcap/info.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "mcap_test_util.hpp"
#include "rover/mcap/writer.hpp"

namespace rover::mcap {
namespace {

using testing::OpenBytes;
using testing::Sample;
using testing::SampleFile;
using testing::SampleSpec;

TEST(Info, SummarizesTopicsCountsTimesAndChunks) {
  WriterOptions o;
  o.chunk_bytes = 2000;
  Sample sample;
  const Bytes file = SampleFile(o, {}, &sample);
  auto r = OpenBytes(file, Verification::kSummary, "run.mcap");
  ASSERT_TRUE(r.ok());
  const RecordingInfo info = Summarize(**r).value();
  EXPECT_EQ(info.name, "run.mcap");
  EXPECT_EQ(info.file_size, file.size());
  EXPECT_TRUE(info.indexed);
  EXPECT_EQ(info.library, "rover_mcap 1");
  EXPECT_EQ(info.message_count, 300u);
  EXPECT_EQ(info.start_time, 1'000'000'000u);
  EXPECT_EQ(info.end_time, 1'000'000'000u + 299u * 1'000'000u);
  ASSERT_EQ(info.topics.size(), 3u);
  EXPECT_EQ(info.topics[0].topic, "dl/pose");
  EXPECT_EQ(info.topics[0].schema_name, "rover::dl::PoseEstimate");
  EXPECT_EQ(info.topics[0].schema_encoding, "omgidl");
  EXPECT_EQ(info.topics[0].message_encoding, "cdr");
  EXPECT_EQ(info.topics[2].topic, "sys/event");
  EXPECT_EQ(info.topics[2].schema_name, "");
  std::uint64_t total = 0;
  for (const TopicInfo& t : info.topics) {
    std::uint64_t n = 0;
    for (const auto& m : sample.written) n += m.topic == t.topic ? 1 : 0;
    EXPECT_EQ(t.message_count, n) << t.topic;
    total += t.message_count;
  }
  EXPECT_EQ(total, 300u);
  EXPECT_EQ(info.chunk_count, (*r)->chunk_indexes().size());
  EXPECT_EQ(info.chunks_by_compression.at("zstd"), info.chunk_count);
  EXPECT_LT(info.chunk_compressed_bytes, info.chunk_uncompressed_bytes);
  EXPECT_EQ(info.attachment_count, 1u);
  EXPECT_EQ(info.metadata_names, (std::vector<std::string>{"run"}));
  EXPECT_FALSE(info.truncation.has_value());
}

TEST(Info, AFileWithoutSummaryGivesTheSameInformation) {
  WriterOptions with;
  WriterOptions without;
  without.summary = false;
  RecordingInfo a = Summarize(*OpenBytes(SampleFile(with, {})).value()).value();
  RecordingInfo b = Summarize(*OpenBytes(SampleFile(without, {})).value()).value();
  EXPECT_FALSE(b.indexed);
  EXPECT_EQ(a.message_count, b.message_count);
  EXPECT_EQ(a.start_time, b.start_time);
  EXPECT_EQ(a.end_time, b.end_time);
  ASSERT_EQ(a.topics.size(), b.topics.size());
  for (std::size_t i = 0; i < a.topics.size(); ++i) {
    EXPECT_EQ(a.topics[i].message_count, b.topics[i].message_count);
  }
}

TEST(Info, CountsMessagesWhenTheSummaryHasNoStatistics) {
  testing::FileBuilder b;
  const Channel c{1, 0, "t", "cdr", {}};
  b.Data(c);
  for (Timestamp t : {5, 3, 9}) b.Data(MessageView{1, 0, t, t, {}});
  b.EndData();
  b.Data(c);
  const RecordingInfo info = Summarize(*OpenBytes(b.Finish(true)).value()).value();
  EXPECT_EQ(info.message_count, 3u);
  EXPECT_EQ(info.start_time, 3u);
  EXPECT_EQ(info.end_time, 9u);
  ASSERT_EQ(info.topics.size(), 1u);
  EXPECT_EQ(info.topics[0].message_count, 3u);
}

TEST(Info, ReportsACapThatCutTheRecording) {
  Bytes file;
  WriterOptions o;
  o.size_cap_bytes = 8192;
  {
    auto w = Writer::Create(std::make_unique<BufferSink>(&file), o).value();
    const std::uint16_t c = w->AddChannel("t", "cdr", 0).value();
    for (std::uint32_t i = 0; i < 10000; ++i) {
      Bytes d(100);
      for (std::size_t k = 0; k < d.size(); ++k)
        d[k] = static_cast<std::uint8_t>(k * i * 2654435761u >> 7);
      if (!w->WriteMessage({c, i, 2'000'000'000ull + i * 10'000'000ull, 0, d}).ok()) break;
    }
    ASSERT_TRUE(w->Close().ok());
  }
  const RecordingInfo info = Summarize(*OpenBytes(file).value()).value();
  ASSERT_TRUE(info.truncation.has_value());
  const std::string expected_start = "by the size_cap of 8192 bytes: messages from log time ";
  EXPECT_EQ(info.truncation->rfind(expected_start, 0), 0u) << *info.truncation;
  EXPECT_NE(info.truncation->find(" s on were not recorded (1 refused)"), std::string::npos)
      << *info.truncation;
  EXPECT_NE(FormatRecordingInfo(info).find("truncated:    by the size_cap of 8192 bytes"),
            std::string::npos)
      << FormatRecordingInfo(info);
}

TEST(Info, FormatsTheReport) {
  RecordingInfo info;
  info.name = "runs/a/run.mcap";
  info.file_size = 2'500'000;
  info.indexed = true;
  info.library = "rover_mcap 1";
  info.message_count = 1500;
  info.start_time = 1'000'000'000;
  info.end_time = 61'500'000'000;
  info.topics = {{"dl/pose", 1, "rover::dl::PoseEstimate", "omgidl", "cdr", 1200},
                 {"sys/event", 2, "", "", "cdr", 300}};
  info.chunk_count = 3;
  info.chunks_by_compression = {{"zstd", 2}, {"none", 1}};
  info.chunk_compressed_bytes = 2'000'000;
  info.chunk_uncompressed_bytes = 8'000'000;
  info.metadata_names = {"run"};
  EXPECT_EQ(FormatRecordingInfo(info),
            "file:         runs/a/run.mcap (2.5 MB, indexed)\n"
            "library:      rover_mcap 1\n"
            "messages:     1500 on 2 topics\n"
            "start:        1.000000000 s\n"
            "end:          61.500000000 s\n"
            "duration:     60.500000000 s\n"
            "chunks:       3 (none 1, zstd 2), 8 MB stored in 2 MB (25 %)\n"
            "metadata:     run\n"
            "topics:\n"
            "  dl/pose    1200 msgs  rover::dl::PoseEstimate  cdr/omgidl\n"
            "  sys/event   300 msgs  -                        cdr\n");
  EXPECT_EQ(FormatTimestamp(0), "0.000000000");
  EXPECT_EQ(FormatTimestamp(12'000'000'345ull), "12.000000345");
}

TEST(Info, SummarizeFileOpensThePath) {
  const std::string dir = testing::MakeTempDir("mcap-info");
  const std::string path = dir + "/x.mcap";
  {
    auto w = Writer::Create(path, {});
    ASSERT_TRUE(w.ok());
    testing::WriteSample(**w, {});
    ASSERT_TRUE((*w)->Close().ok());
  }
  const auto info = SummarizeFile(path);
  ASSERT_TRUE(info.ok()) << info.status().ToString();
  EXPECT_EQ(info->message_count, 300u);
  EXPECT_EQ(SummarizeFile(dir + "/missing.mcap").status().code(), StatusCode::kNotFound);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace rover::mcap
