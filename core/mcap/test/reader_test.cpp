#include "rover/mcap/reader.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "mcap_test_util.hpp"
#include "rover/mcap/crc32.hpp"
#include "rover/mcap/writer.hpp"

namespace rover::mcap {
namespace {

using testing::FileBuilder;
using testing::InLogTimeOrder;
using testing::Msg;
using testing::OpenBytes;
using testing::ReadAll;
using testing::Sample;
using testing::SampleFile;
using testing::SampleSpec;

struct Layout {
  Compression compression;
  bool chunked;
  bool summary;
};

std::string LayoutName(const ::testing::TestParamInfo<Layout>& p) {
  std::string n = std::string(
      p.param.compression == Compression::kNone ? "none" : CompressionName(p.param.compression));
  n += p.param.chunked ? "_chunked" : "_unchunked";
  n += p.param.summary ? "_summary" : "_scan";
  return n;
}

WriterOptions OptionsOf(const Layout& l) {
  WriterOptions o;
  o.compression = l.compression;
  o.chunked = l.chunked;
  o.summary = l.summary;
  o.chunk_bytes = 1500;
  return o;
}

class EachLayout : public ::testing::TestWithParam<Layout> {};

TEST_P(EachLayout, ReadsBackEveryMessageInLogTimeOrder) {
  SampleSpec spec;
  spec.jitter_ns = 5'000'000;  // +-5 ms around 1 ms steps: consecutive chunks overlap in time
  Sample sample;
  const Bytes file = SampleFile(OptionsOf(GetParam()), spec, &sample);
  for (Verification v : {Verification::kSummary, Verification::kDataSection, Verification::kFull}) {
    auto r = OpenBytes(file, v);
    ASSERT_TRUE(r.ok()) << r.status().ToString();
    EXPECT_EQ((*r)->has_summary(), GetParam().summary);
    auto all = ReadAll(**r);
    ASSERT_TRUE(all.ok()) << all.status().ToString();
    EXPECT_EQ(*all, InLogTimeOrder(sample.written));

    ASSERT_EQ((*r)->channels().size(), 3u);
    const Channel& pose = (*r)->channels().at(1);
    EXPECT_EQ(pose.topic, "dl/pose");
    EXPECT_EQ(pose.message_encoding, "cdr");
    EXPECT_EQ(pose.metadata, (StringMap{{"qos", "state"}}));
    EXPECT_EQ((*r)->channels().at(3).schema_id, 0);
    ASSERT_EQ((*r)->schemas().size(), 2u);
    EXPECT_EQ((*r)->schemas().at(2).name, "rover::dl::RangeImage");
    EXPECT_EQ((*r)->schemas().at(2).encoding, "omgidl");
    const std::string idl = testing::SampleIdl("dl", "RangeImage");
    EXPECT_EQ((*r)->schemas().at(2).data, Bytes(idl.begin(), idl.end()));

    ASSERT_TRUE((*r)->statistics().has_value());
    const Statistics& st = *(*r)->statistics();
    EXPECT_EQ(st.message_count, sample.written.size());
    EXPECT_EQ(st.message_start_time, InLogTimeOrder(sample.written).front().log_time);
    EXPECT_EQ(st.message_end_time, InLogTimeOrder(sample.written).back().log_time);
    std::uint64_t pose_count = 0;
    for (const Msg& m : sample.written) pose_count += m.topic == "dl/pose" ? 1 : 0;
    EXPECT_EQ(st.channel_message_counts.at(1), pose_count);
    EXPECT_EQ(st.attachment_count, 1u);
    EXPECT_EQ(st.metadata_count, 1u);
    EXPECT_EQ((*r)->chunk_indexes().size(), GetParam().chunked ? st.chunk_count : 0u);
    ASSERT_EQ((*r)->ReadAllMetadata().value().size(), 1u);
    ASSERT_EQ((*r)->attachment_indexes().size(), 1u);
    EXPECT_EQ((*r)->ReadAttachment((*r)->attachment_indexes()[0]).value().name, "calibration.yaml");
  }
}

TEST_P(EachLayout, FiltersByTopicTimeAndChannel) {
  SampleSpec spec;
  spec.jitter_ns = 2'000'000;
  Sample sample;
  const Bytes file = SampleFile(OptionsOf(GetParam()), spec, &sample);
  auto r = OpenBytes(file);
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  const std::vector<Msg> ordered = InLogTimeOrder(sample.written);
  auto expect = [&](auto pred) {
    std::vector<Msg> v;
    for (const Msg& m : ordered) {
      if (pred(m)) v.push_back(m);
    }
    return v;
  };
  MessageFilter by_topic;
  by_topic.topics = {"dl/range_image", "sys/event"};
  EXPECT_EQ(ReadAll(**r, by_topic).value(),
            expect([](const Msg& m) { return m.topic != "dl/pose"; }));
  MessageFilter by_time;
  by_time.start_time = 1'100'000'000;
  by_time.end_time = 1'150'000'000;
  EXPECT_EQ(ReadAll(**r, by_time).value(), expect([](const Msg& m) {
              return m.log_time >= 1'100'000'000 && m.log_time <= 1'150'000'000;
            }));
  MessageFilter by_channel;
  by_channel.channel = [](const Channel& c) { return c.topic.rfind("dl/", 0) == 0; };
  by_channel.start_time = 1'200'000'000;
  EXPECT_EQ(ReadAll(**r, by_channel).value(), expect([](const Msg& m) {
              return m.topic.rfind("dl/", 0) == 0 && m.log_time >= 1'200'000'000;
            }));
  MessageFilter none;
  none.topics = {"no/such/topic"};
  EXPECT_TRUE(ReadAll(**r, none).value().empty());
}

INSTANTIATE_TEST_SUITE_P(Layouts, EachLayout,
                         ::testing::Values(Layout{Compression::kNone, true, true},
                                           Layout{Compression::kZstd, true, true},
                                           Layout{Compression::kLz4, true, true},
                                           Layout{Compression::kZstd, true, false},
                                           Layout{Compression::kLz4, true, false},
                                           Layout{Compression::kNone, false, true},
                                           Layout{Compression::kNone, false, false}),
                         LayoutName);

TEST(Reader, ScanningAndTheSummaryAgree) {
  WriterOptions with;
  with.chunk_bytes = 2000;
  WriterOptions without = with;
  without.summary = false;
  SampleSpec spec;
  spec.jitter_ns = 4'000'000;
  const Bytes a = SampleFile(with, spec);
  const Bytes b = SampleFile(without, spec);
  auto ra = OpenBytes(a);
  auto rb = OpenBytes(b);
  ASSERT_TRUE(ra.ok() && rb.ok());
  EXPECT_TRUE((*ra)->has_summary());
  EXPECT_FALSE((*rb)->has_summary());
  EXPECT_EQ((*ra)->channels(), (*rb)->channels());
  EXPECT_EQ((*ra)->schemas(), (*rb)->schemas());
  EXPECT_EQ(*(*ra)->statistics(), *(*rb)->statistics());
  EXPECT_EQ((*ra)->chunk_indexes(), (*rb)->chunk_indexes()) << "the scan rebuilds the index";
  EXPECT_EQ((*ra)->attachment_indexes(), (*rb)->attachment_indexes());
  EXPECT_EQ((*ra)->metadata_indexes(), (*rb)->metadata_indexes());
  EXPECT_EQ(ReadAll(**ra).value(), ReadAll(**rb).value());
}

TEST(Reader, EqualLogTimesComeInFileOrder) {
  Bytes file;
  WriterOptions o;
  o.chunk_bytes = 60;  // about one message per chunk
  {
    auto w = Writer::Create(std::make_unique<BufferSink>(&file), o).value();
    const std::uint16_t c = w->AddChannel("t", "cdr", 0).value();
    for (std::uint32_t i = 0; i < 40; ++i) {
      // Times 5, 5, 5, 4, 4, 4, ...: many ties, across and inside chunks.
      ASSERT_TRUE(w->WriteMessage({c, i, Timestamp(100 - i / 3), 0, Bytes{1, 2}}).ok());
    }
    ASSERT_TRUE(w->Close().ok());
  }
  auto r = OpenBytes(file);
  ASSERT_TRUE(r.ok());
  const std::vector<Msg> all = ReadAll(**r).value();
  ASSERT_EQ(all.size(), 40u);
  for (std::size_t k = 1; k < all.size(); ++k) {
    ASSERT_LE(all[k - 1].log_time, all[k].log_time);
    if (all[k - 1].log_time == all[k].log_time) {
      EXPECT_LT(all[k - 1].sequence, all[k].sequence);
    }
  }
}

TEST(Reader, ACursorKeepsTheLastMessageValidUntilTheNextCall) {
  WriterOptions o;
  o.chunk_bytes = 200;
  Sample sample;
  const Bytes file = SampleFile(o, {}, &sample);
  auto r = OpenBytes(file);
  ASSERT_TRUE(r.ok());
  auto cursor = (*r)->Messages();
  ASSERT_TRUE(cursor.ok());
  const std::vector<Msg> expected = InLogTimeOrder(sample.written);
  for (const Msg& m : expected) {
    auto e = cursor->Next();
    ASSERT_TRUE(e.ok() && e->has_value());
    const MessageEvent& ev = **e;
    EXPECT_EQ(Bytes(ev.message.data.begin(), ev.message.data.end()), m.data);
    EXPECT_EQ(ev.channel->topic, m.topic);
    if (ev.channel->schema_id == 0) {
      EXPECT_EQ(ev.schema, nullptr);
    } else {
      ASSERT_NE(ev.schema, nullptr);
      EXPECT_EQ(ev.schema->id, ev.channel->schema_id);
    }
  }
  auto end = cursor->Next();
  ASSERT_TRUE(end.ok());
  EXPECT_FALSE(end->has_value());
  EXPECT_FALSE(cursor->Next()->has_value());
}

// ---- corruption and truncation -----------------------------------------------------------------

Bytes SmallFile(bool summary, bool chunked = true) {
  WriterOptions o;
  o.chunk_bytes = 400;
  o.summary = summary;
  o.chunked = chunked;
  SampleSpec spec;
  spec.messages = 30;
  spec.max_data_bytes = 40;
  spec.jitter_ns = 2'000'000;
  return SampleFile(o, spec);
}

TEST(Reader, EveryFlippedByteOfAnIndexedFileFailsOpen) {
  // The data-section CRC covers every byte before DataEnd, the summary CRC the rest up to the
  // footer's crc field, and the footer and magic are checked: no byte is unguarded.
  const Bytes good = SmallFile(true);
  for (std::size_t i = 0; i < good.size(); ++i) {
    Bytes bad = good;
    bad[i] ^= 0x10;
    auto r = OpenBytes(bad);
    ASSERT_FALSE(r.ok()) << "a flip at byte " << i << " of " << good.size() << " went unnoticed";
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument) << r.status().ToString();
    EXPECT_EQ(r.status().message().rfind("test.mcap: ", 0), 0u) << r.status().message();
    EXPECT_NE(r.status().message().find("offset "), std::string::npos) << r.status().message();
  }
}

TEST(Reader, FlippedBytesNeverYieldWrongMessages) {
  // With only the summary checked (kSummary), or without a summary, a flip may pass Open; then
  // reading must fail, or give exactly the original messages (the flip hit something that is
  // not read: a message index, a CRC field of a file without summary, ...).
  for (const bool summary : {true, false}) {
    for (const bool chunked : {true, false}) {
      const Bytes good = SmallFile(summary, chunked);
      const auto original = ReadAll(*OpenBytes(good).value()).value();
      int opened = 0;
      for (std::size_t i = 0; i < good.size(); ++i) {
        Bytes bad = good;
        bad[i] ^= 0x01;
        auto r = OpenBytes(bad, Verification::kSummary);
        if (!r.ok()) continue;
        ++opened;
        auto all = ReadAll(**r);
        if (all.ok()) {
          EXPECT_EQ(*all, original) << "byte " << i << " (summary " << summary << ")";
        } else {
          EXPECT_NE(all.status().message().find("offset "), std::string::npos);
        }
      }
      if (summary && chunked) {
        EXPECT_GT(opened, 0) << "kSummary does not read the data section up front";
      }
    }
  }
}

TEST(Reader, EveryTruncationFailsNamingTheOffset) {
  for (const bool summary : {true, false}) {
    const Bytes good = SmallFile(summary);
    for (std::size_t n = 0; n < good.size(); ++n) {
      const Bytes cut(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(n));
      for (Verification v : {Verification::kSummary, Verification::kDataSection}) {
        auto r = OpenBytes(cut, v);
        ASSERT_FALSE(r.ok()) << "a file cut to " << n << " bytes opened";
        EXPECT_NE(r.status().message().find("offset "), std::string::npos) << r.status().message();
      }
    }
  }
}

TEST(Reader, ATruncatedRecordingSaysSo) {
  const Bytes good = SmallFile(true);
  const Bytes cut(good.begin(), good.begin() + 700);
  EXPECT_EQ(OpenBytes(cut).status().message(),
            "test.mcap: offset 663: no Footer record and trailing magic at the end (the file is "
            "truncated or was not closed)");
  EXPECT_EQ(OpenBytes(Bytes(good.begin(), good.begin() + 20)).status().message(),
            "test.mcap: Header record at offset 8: length 20 runs past the end of the file (20 "
            "bytes; the file is truncated or corrupt)");
  EXPECT_EQ(OpenBytes(Bytes(good.begin(), good.begin() + 40)).status().message(),
            "test.mcap: offset 37: no Footer record and trailing magic after the Header (the file "
            "of 40 bytes is truncated or was not closed)");
  EXPECT_EQ(OpenBytes(Bytes{}).status().message(),
            "test.mcap: offset 0: not an MCAP file: 0 bytes are too few for the magic");
  EXPECT_EQ(OpenBytes(Bytes(100, 'x')).status().message(),
            "test.mcap: offset 0: not an MCAP file (the first bytes are not the MCAP magic)");
  Bytes v1 = good;
  v1[5] = '1';
  EXPECT_EQ(OpenBytes(v1).status().message(),
            "test.mcap: offset 0: MCAP major version '1' is not supported (this reader knows "
            "version '0')");
}

/// A sample in uncompressed chunks of 400 bytes, so that tests can edit bytes in place.
Bytes UncompressedSmallChunks() {
  WriterOptions o;
  o.chunk_bytes = 400;
  o.compression = Compression::kNone;
  return SampleFile(o, {});
}

TEST(Reader, CorruptChunksNameTheChunkAndTheirOffset) {
  const Bytes good = UncompressedSmallChunks();
  auto reference = OpenBytes(good);
  ASSERT_TRUE(reference.ok());
  const ChunkIndex chunk = (*reference)->chunk_indexes()[3];
  Bytes bad = good;
  bad[chunk.chunk_start_offset + chunk.chunk_length - 5] ^= 0xFF;  // a message's data byte

  // Full checks: the data-section CRC catches it at once.
  EXPECT_NE(OpenBytes(bad).status().message().find("DataEnd record at offset"), std::string::npos);
  // Summary only: the chunk's own CRC, when the cursor gets there; the error is final.
  auto r = OpenBytes(bad, Verification::kSummary);
  ASSERT_TRUE(r.ok());
  auto cursor = (*r)->Messages();
  ASSERT_TRUE(cursor.ok());
  Status failed;
  int yielded = 0;
  while (failed.ok()) {
    auto e = cursor->Next();
    if (!e.ok()) {
      failed = e.status();
      break;
    }
    ASSERT_TRUE(e->has_value()) << "the corrupt chunk was not noticed";
    ++yielded;
  }
  EXPECT_EQ(
      failed.message().rfind("test.mcap: Chunk record at offset " +
                                 std::to_string(chunk.chunk_start_offset) + ": uncompressed_crc 0x",
                             0),
      0u)
      << failed.message();
  EXPECT_NE(failed.message().find("(the chunk is corrupt)"), std::string::npos);
  EXPECT_EQ(cursor->Next().status().message(), failed.message()) << "the error is final";
  EXPECT_GT(yielded, 0);
  // kFull at Open refuses it before any message is read.
  EXPECT_FALSE(OpenBytes(bad, Verification::kFull).ok());
}

TEST(Reader, WithoutADataCrcEveryChunkIsCheckedAtOpen) {
  // A writer may leave data_section_crc at 0; then kDataSection decompresses every chunk.
  WriterOptions o;
  o.chunk_bytes = 400;
  const Bytes good = SampleFile(o, {});
  auto reference = OpenBytes(good);
  ASSERT_TRUE(reference.ok());
  const std::uint64_t data_end = (*reference)->data_end_offset();
  const ChunkIndex chunk = (*reference)->chunk_indexes()[2];
  Bytes no_crc = good;
  for (int i = 0; i < 4; ++i) no_crc[data_end + kRecordPrefixBytes + i] = 0;
  // The summary CRC does not cover DataEnd, so the file stays consistent.
  ASSERT_TRUE(OpenBytes(no_crc).ok());
  Bytes bad = no_crc;
  bad[chunk.chunk_start_offset + chunk.chunk_length - 3] ^= 0x40;
  const auto r = OpenBytes(bad);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message().rfind(
                "test.mcap: Chunk record at offset " + std::to_string(chunk.chunk_start_offset), 0),
            0u)
      << r.status().message();
}

TEST(Reader, FullVerificationComparesStatisticsAndMessageIndexes) {
  const Bytes good = UncompressedSmallChunks();
  auto reference = OpenBytes(good);
  ASSERT_TRUE(reference.ok());
  ASSERT_TRUE((*reference)->VerifyFull().ok());
  const std::uint64_t footer_at = good.size() - 8 - kFooterRecordBytes;
  // Statistics lie about the message count (the summary CRC is set to 0 to let it through).
  std::uint64_t stats_at = 0;
  for (std::uint64_t pos = (*reference)->footer().summary_start; pos < footer_at;) {
    auto rec = SplitRecord(good, pos).value();
    if (rec.opcode == 0x0B) stats_at = pos;
    pos += rec.size();
  }
  ASSERT_NE(stats_at, 0u);
  Bytes lie = good;
  lie[stats_at + kRecordPrefixBytes] += 1;
  for (int i = 0; i < 4; ++i) lie[footer_at + 25 + i] = 0;
  ASSERT_TRUE(OpenBytes(lie).ok()) << "kDataSection does not count messages";
  EXPECT_EQ(OpenBytes(lie, Verification::kFull).status().message(),
            "test.mcap: Statistics record at offset " +
                std::to_string((*reference)->footer().summary_start) +
                ": message_count 301, the file holds 300 messages (the statistics disagree with "
                "the data)");
  // A message index entry points elsewhere (the data CRC is set to 0 to let it through).
  const ChunkIndex c = (*reference)->chunk_indexes()[1];
  Bytes wrong_index = good;
  const std::uint64_t entry = c.chunk_start_offset + c.chunk_length + kRecordPrefixBytes + 2 + 4;
  wrong_index[entry + 8] ^= 0x01;  // the first entry's offset
  for (int i = 0; i < 4; ++i) {
    wrong_index[(*reference)->data_end_offset() + kRecordPrefixBytes + i] = 0;
  }
  const auto r = OpenBytes(wrong_index);  // no data CRC: kDataSection checks everything
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("MessageIndex record at offset"), std::string::npos)
      << r.status().message();
}

TEST(Reader, TheRecordLimitGuardsMemory) {
  WriterOptions o;
  o.compression = Compression::kNone;
  const Bytes file = SampleFile(o, {});
  ReaderOptions ro;
  ro.max_record_bytes = 1000;
  const auto r = Reader::Open(std::make_unique<BufferSource>(file, "x.mcap"), ro);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("exceeds the reader's limit of 1000 bytes"),
            std::string::npos)
      << r.status().message();
}

// ---- hand-made files ----------------------------------------------------------------------------

TEST(Reader, SkipsPrivateAndFutureRecordsAndReadsChannelZero) {
  // Channel 0 is valid (the reference writer starts there); opcodes 0x10..0xFF are skipped,
  // in the data section and inside chunks alike.
  Bytes inner;
  AppendRecord(inner, Channel{0, 0, "zero", "json", {}});
  inner.insert(inner.end(), {0x80, 3, 0, 0, 0, 0, 0, 0, 0, 'p', 'r', 'v'});
  const Bytes payload{'{', '}'};
  AppendRecord(inner, MessageView{0, 1, 50, 50, payload});
  FileBuilder b;
  b.Raw(Bytes{0x42, 1, 0, 0, 0, 0, 0, 0, 0, 9});  // a future record
  b.Raw(testing::ChunkOf(inner, 50, 50));
  b.Data(MessageView{0, 2, 40, 40, payload});  // outside the chunk, earlier in time
  b.EndData();
  const Bytes file = b.Finish(false);
  auto r = OpenBytes(file, Verification::kFull);
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  const auto all = ReadAll(**r).value();
  ASSERT_EQ(all.size(), 2u);
  EXPECT_EQ(all[0].sequence, 2u) << "the loose message at 40 comes first";
  EXPECT_EQ(all[1].sequence, 1u);
  EXPECT_EQ(all[0].topic, "zero");
  EXPECT_EQ((*r)->statistics()->message_count, 2u);
}

TEST(Reader, RefusesWhatTheSpecificationForbids) {
  {  // a message before its channel
    FileBuilder b;
    b.Data(MessageView{4, 0, 1, 1, {}});
    b.EndData();
    EXPECT_EQ(
        OpenBytes(b.Finish(false)).status().message(),
        "test.mcap: Message record at offset 29: channel 4 is not defined before the message");
  }
  {  // a channel redefined differently
    FileBuilder b;
    b.Data(Channel{1, 0, "a", "cdr", {}});
    b.Data(Channel{1, 0, "b", "cdr", {}});
    b.EndData();
    EXPECT_EQ(OpenBytes(b.Finish(false)).status().message(),
              "test.mcap: Channel record at offset 58: channel 1 ('b') differs from its earlier "
              "definition ('a')");
  }
  {  // a channel on an undefined schema
    FileBuilder b;
    b.Data(Channel{1, 3, "a", "cdr", {}});
    b.EndData();
    EXPECT_NE(OpenBytes(b.Finish(false))
                  .status()
                  .message()
                  .find("uses schema 3, which is not defined before it"),
              std::string::npos);
  }
  {  // no DataEnd
    FileBuilder b;
    b.Data(Channel{1, 0, "a", "cdr", {}});
    EXPECT_EQ(OpenBytes(b.Finish(false)).status().message(),
              "test.mcap: offset 58: the data section ends without a DataEnd record (0 bytes "
              "before the footer at 58; the file is truncated or corrupt)");
  }
  {  // a summary record in the data section
    FileBuilder b;
    b.Data(Statistics{});
    b.EndData();
    EXPECT_NE(OpenBytes(b.Finish(false))
                  .status()
                  .message()
                  .find("Statistics record at offset 29: a summary record is not allowed"),
              std::string::npos);
  }
  {  // an attachment inside a chunk
    Bytes inner;
    AppendRecord(inner, Attachment{1, 1, "a", "b", Bytes{1}});
    FileBuilder b;
    b.Raw(testing::ChunkOf(inner, 0, 0));
    b.EndData();
    EXPECT_NE(OpenBytes(b.Finish(false))
                  .status()
                  .message()
                  .find("Attachment record is not allowed inside a chunk"),
              std::string::npos);
  }
  {  // a message outside its chunk's time range
    Bytes inner;
    AppendRecord(inner, Channel{1, 0, "a", "cdr", {}});
    AppendRecord(inner, MessageView{1, 0, 99, 99, {}});
    FileBuilder b;
    b.Raw(testing::ChunkOf(inner, 10, 20));
    b.EndData();
    EXPECT_NE(OpenBytes(b.Finish(false))
                  .status()
                  .message()
                  .find("Message log_time 99 is outside the chunk's [10, 20]"),
              std::string::npos);
  }
}

TEST(Reader, ReadsASummaryWithoutStatisticsOrOffsets) {
  FileBuilder b;
  const Schema s{1, "S", "omgidl", Bytes{'x'}};
  const Channel c{1, 1, "t", "cdr", {}};
  b.Data(s);
  b.Data(c);
  b.Data(MessageView{1, 0, 7, 7, Bytes{1}});
  b.EndData();
  b.Data(s);
  b.Data(c);
  const Bytes file = b.Finish(true);
  for (Verification v : {Verification::kSummary, Verification::kDataSection, Verification::kFull}) {
    auto r = OpenBytes(file, v);
    ASSERT_TRUE(r.ok()) << r.status().ToString();
    EXPECT_FALSE((*r)->statistics().has_value());
    const auto all = ReadAll(**r).value();  // the loose message is found by the scan
    ASSERT_EQ(all.size(), 1u);
    EXPECT_EQ(all[0].log_time, 7u);
  }
}

TEST(Reader, SummaryChecksNameTheirRecord) {
  {  // a record of the data section in the summary
    FileBuilder b;
    b.EndData();
    b.Data(MessageView{1, 0, 0, 0, {}});
    EXPECT_EQ(OpenBytes(b.Finish(true)).status().message(),
              "test.mcap: Message record at offset 42: not allowed in the summary section");
  }
  {  // a chunk index pointing outside the data section
    FileBuilder b;
    b.EndData();
    ChunkIndex ci;
    ci.chunk_start_offset = 5000;
    ci.chunk_length = 100;
    b.Data(ci);
    EXPECT_NE(OpenBytes(b.Finish(true))
                  .status()
                  .message()
                  .find("ChunkIndex record at offset 42: the chunk [5000, +100)"),
              std::string::npos);
  }
  {  // a wrong summary CRC
    FileBuilder b;
    b.EndData();
    b.Data(Statistics{});
    Bytes file = b.Finish(true);
    file[45] ^= 1;  // inside the Statistics record
    EXPECT_NE(
        OpenBytes(file, Verification::kSummary).status().message().find("Footer record at offset"),
        std::string::npos);
  }
}

TEST(Reader, OpensFilesOnDisk) {
  EXPECT_EQ(Reader::Open("/nonexistent/x.mcap").status().code(), StatusCode::kNotFound);
}

}  // namespace
}  // namespace rover::mcap
