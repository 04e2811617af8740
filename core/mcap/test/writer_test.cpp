#include "rover/mcap/writer.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "mcap_test_util.hpp"
#include "rover/base/param_binder.hpp"
#include "rover/mcap/compression.hpp"
#include "rover/mcap/crc32.hpp"
#include "rover/mcap/reader.hpp"

namespace rover::mcap {
namespace {

using testing::OpenBytes;
using testing::SampleFile;
using testing::SampleSpec;

struct Rec {
  std::uint64_t offset;
  std::uint8_t opcode;
  ByteSpan content;
};

// Every record between the leading magic and the trailing magic, in order.
std::vector<Rec> Records(const Bytes& file) {
  std::vector<Rec> out;
  EXPECT_TRUE(std::equal(kMagic.begin(), kMagic.end(), file.begin()));
  EXPECT_TRUE(std::equal(kMagic.begin(), kMagic.end(), file.end() - 8));
  const ByteSpan body = ByteSpan(file).first(file.size() - 8);
  for (std::uint64_t pos = 8; pos < body.size();) {
    auto r = SplitRecord(body, pos);
    EXPECT_TRUE(r.ok()) << r.status().ToString();
    if (!r.ok()) break;
    out.push_back({pos, r->opcode, r->content});
    pos += r->size();
  }
  return out;
}

std::vector<std::uint8_t> Opcodes(const std::vector<Rec>& recs) {
  std::vector<std::uint8_t> ops;
  for (const Rec& r : recs) ops.push_back(r.opcode);
  return ops;
}

std::unique_ptr<Writer> MemoryWriter(Bytes* out, const WriterOptions& o) {
  auto w = Writer::Create(std::make_unique<BufferSink>(out), o);
  EXPECT_TRUE(w.ok()) << w.status().ToString();
  return std::move(w).value();
}

// Checks the two CRCs of a closed file from first principles.
void ExpectCrcsHold(const Bytes& file) {
  const std::vector<Rec> recs = Records(file);
  const Footer footer = ParseFooter(recs.back().content).value();
  std::uint64_t data_end = 0;
  for (const Rec& r : recs) {
    if (r.opcode == 0x0F) data_end = r.offset;
  }
  ASSERT_NE(data_end, 0u);
  const DataEnd de = ParseDataEnd(SplitRecord(file, data_end)->content).value();
  EXPECT_EQ(de.data_section_crc, ComputeCrc32(ByteSpan(file).first(data_end)));
  if (footer.summary_start != 0) {
    EXPECT_EQ(footer.summary_start, data_end + kDataEndRecordBytes);
    const std::uint64_t footer_at = file.size() - 8 - kFooterRecordBytes;
    EXPECT_EQ(footer.summary_crc,
              ComputeCrc32(ByteSpan(file).subspan(footer.summary_start,
                                                  footer_at + 25 - footer.summary_start)));
  }
}

TEST(Writer, AnEmptyRecordingHasHeaderDataEndStatisticsAndFooter) {
  Bytes file;
  WriterOptions o;
  o.library = "test lib";
  auto w = MemoryWriter(&file, o);
  ASSERT_TRUE(w->Close().ok());
  const std::vector<Rec> recs = Records(file);
  EXPECT_EQ(Opcodes(recs), (std::vector<std::uint8_t>{0x01, 0x0F, 0x0B, 0x0E, 0x02}));
  EXPECT_EQ(ParseHeader(recs[0].content).value(), (Header{"", "test lib"}));
  const Statistics st = ParseStatistics(recs[2].content).value();
  EXPECT_EQ(st, Statistics{});
  const SummaryOffset so = ParseSummaryOffset(recs[3].content).value();
  EXPECT_EQ(so, (SummaryOffset{0x0B, recs[2].offset, recs[3].offset - recs[2].offset}));
  const Footer f = ParseFooter(recs[4].content).value();
  EXPECT_EQ(f.summary_start, recs[2].offset);
  EXPECT_EQ(f.summary_offset_start, recs[3].offset);
  ExpectCrcsHold(file);
}

TEST(Writer, OneChunkLayoutAndItsIndexes) {
  Bytes file;
  WriterOptions o;
  o.compression = Compression::kNone;
  auto w = MemoryWriter(&file, o);
  const std::string idl = testing::SampleIdl("dl", "PoseEstimate");
  const std::uint16_t schema =
      w->AddSchema("rover::dl::PoseEstimate", "omgidl", AsBytes(idl)).value();
  const std::uint16_t channel = w->AddChannel("dl/pose", "cdr", schema, {{"k", "v"}}).value();
  EXPECT_EQ(schema, 1);
  EXPECT_EQ(channel, 1);
  const Bytes cdr{0x00, 0x01, 0x00, 0x00, 7, 7, 7, 7};
  ASSERT_TRUE(w->WriteMessage({channel, 0, 2000, 1990, cdr}).ok());
  ASSERT_TRUE(w->WriteMessage({channel, 1, 1000, 990, cdr}).ok());
  ASSERT_TRUE(w->Close().ok());

  const std::vector<Rec> recs = Records(file);
  // Header, Chunk, MessageIndex, DataEnd | Schema, Channel, Statistics, ChunkIndex,
  // 4 SummaryOffsets | Footer.
  EXPECT_EQ(Opcodes(recs), (std::vector<std::uint8_t>{0x01, 0x06, 0x07, 0x0F, 0x03, 0x04, 0x0B,
                                                      0x08, 0x0E, 0x0E, 0x0E, 0x0E, 0x02}));
  const ChunkView chunk = ParseChunk(recs[1].content).value();
  EXPECT_EQ(chunk.message_start_time, 1000u);
  EXPECT_EQ(chunk.message_end_time, 2000u);
  EXPECT_EQ(chunk.compression, "");
  EXPECT_EQ(chunk.uncompressed_size, chunk.records.size());
  EXPECT_EQ(chunk.uncompressed_crc, ComputeCrc32(chunk.records));
  // Inside: Schema, Channel, Message, Message.
  std::vector<std::uint8_t> inner;
  std::vector<std::uint64_t> inner_at;
  for (std::uint64_t pos = 0; pos < chunk.records.size();) {
    auto r = SplitRecord(chunk.records, pos);
    ASSERT_TRUE(r.ok());
    inner.push_back(r->opcode);
    inner_at.push_back(pos);
    pos += r->size();
  }
  EXPECT_EQ(inner, (std::vector<std::uint8_t>{0x03, 0x04, 0x05, 0x05}));

  const MessageIndex mi = ParseMessageIndex(recs[2].content).value();
  EXPECT_EQ(mi.channel_id, channel);
  EXPECT_EQ(mi.records, (std::vector<std::pair<Timestamp, std::uint64_t>>{{2000, inner_at[2]},
                                                                          {1000, inner_at[3]}}));

  const ChunkIndex ci = ParseChunkIndex(recs[7].content).value();
  EXPECT_EQ(ci.chunk_start_offset, recs[1].offset);
  EXPECT_EQ(ci.chunk_length, recs[2].offset - recs[1].offset);
  EXPECT_EQ(ci.message_index_offsets,
            (std::map<std::uint16_t, std::uint64_t>{{1, recs[2].offset}}));
  EXPECT_EQ(ci.message_index_length, recs[3].offset - recs[2].offset);
  EXPECT_EQ(ci.compressed_size, chunk.records.size());
  EXPECT_EQ(ci.uncompressed_size, chunk.uncompressed_size);
  EXPECT_EQ(ci.message_start_time, 1000u);

  EXPECT_EQ(ParseSchema(recs[4].content).value(),
            (Schema{1, "rover::dl::PoseEstimate", "omgidl", Bytes(idl.begin(), idl.end())}));
  EXPECT_EQ(ParseChannel(recs[5].content).value(), (Channel{1, 1, "dl/pose", "cdr", {{"k", "v"}}}));
  Statistics st = ParseStatistics(recs[6].content).value();
  EXPECT_EQ(st.message_count, 2u);
  EXPECT_EQ(st.schema_count, 1);
  EXPECT_EQ(st.channel_count, 1u);
  EXPECT_EQ(st.chunk_count, 1u);
  EXPECT_EQ(st.message_start_time, 1000u);
  EXPECT_EQ(st.message_end_time, 2000u);
  EXPECT_EQ(st.channel_message_counts, (std::map<std::uint16_t, std::uint64_t>{{1, 2}}));
  // The summary offsets name each group in order.
  const std::vector<SummaryOffset> groups = {
      ParseSummaryOffset(recs[8].content).value(), ParseSummaryOffset(recs[9].content).value(),
      ParseSummaryOffset(recs[10].content).value(), ParseSummaryOffset(recs[11].content).value()};
  EXPECT_EQ(groups[0], (SummaryOffset{0x03, recs[4].offset, recs[5].offset - recs[4].offset}));
  EXPECT_EQ(groups[1], (SummaryOffset{0x04, recs[5].offset, recs[6].offset - recs[5].offset}));
  EXPECT_EQ(groups[2], (SummaryOffset{0x0B, recs[6].offset, recs[7].offset - recs[6].offset}));
  EXPECT_EQ(groups[3], (SummaryOffset{0x08, recs[7].offset, recs[8].offset - recs[7].offset}));
  const Footer f = ParseFooter(recs.back().content).value();
  EXPECT_EQ(f.summary_start, recs[4].offset);
  EXPECT_EQ(f.summary_offset_start, recs[8].offset);
  ExpectCrcsHold(file);
}

// A file of one channel and one message.
Bytes OneMessage(const WriterOptions& o) {
  Bytes file;
  auto w = MemoryWriter(&file, o);
  const std::uint16_t c = w->AddChannel("t", "cdr", 0).value();
  EXPECT_TRUE(w->WriteMessage({c, 0, 5, 5, Bytes{1}}).ok());
  EXPECT_TRUE(w->Close().ok());
  return file;
}

TEST(Writer, UnchunkedRecordsGoStraightIntoTheDataSection) {
  WriterOptions o;
  o.chunked = false;
  const Bytes file = OneMessage(o);
  EXPECT_EQ(Opcodes(Records(file)),
            (std::vector<std::uint8_t>{0x01, 0x04, 0x05, 0x0F, 0x04, 0x0B, 0x0E, 0x0E, 0x02}));
  ExpectCrcsHold(file);
}

TEST(Writer, WithoutSummaryTheFooterIsZeros) {
  WriterOptions o;
  o.summary = false;
  const Bytes file = OneMessage(o);
  const std::vector<Rec> recs = Records(file);
  EXPECT_EQ(Opcodes(recs), (std::vector<std::uint8_t>{0x01, 0x06, 0x07, 0x0F, 0x02}));
  EXPECT_EQ(ParseFooter(recs.back().content).value(), Footer{});
  ExpectCrcsHold(file);
}

TEST(Writer, ChunksCloseAtTheirSizeAndAreIndexedEach) {
  WriterOptions o;
  o.chunk_bytes = 2000;
  SampleSpec spec;
  spec.messages = 400;
  const Bytes file = SampleFile(o, spec);
  std::vector<Rec> recs = Records(file);
  std::size_t chunks = 0;
  std::size_t chunk_indexes = 0;
  for (std::size_t i = 0; i < recs.size(); ++i) {
    if (recs[i].opcode == 0x06) {
      ++chunks;
      const ChunkView c = ParseChunk(recs[i].content).value();
      // Every chunk but the last reaches the size; none exceeds it by more than a message.
      EXPECT_LT(c.uncompressed_size, o.chunk_bytes + testing::SampleSpec{}.max_data_bytes + 40);
      EXPECT_EQ(c.compression, "zstd");
      EXPECT_EQ(recs[i + 1].opcode, 0x07) << "a message index follows every chunk";
    }
    if (recs[i].opcode == 0x08) ++chunk_indexes;
  }
  EXPECT_GT(chunks, 10u);
  EXPECT_EQ(chunk_indexes, chunks);
  ExpectCrcsHold(file);
}

TEST(Writer, IncompressibleChunksAreStoredUncompressed) {
  for (Compression kind : {Compression::kZstd, Compression::kLz4}) {
    WriterOptions o;
    o.compression = kind;
    SampleSpec spec;
    spec.compressible = false;
    spec.max_data_bytes = 5000;
    spec.messages = 50;
    const Bytes random = SampleFile(o, spec);
    spec.compressible = true;
    const Bytes text = SampleFile(o, spec);
    auto compression_of = [](const Bytes& f) {
      for (const Rec& r : Records(f)) {
        if (r.opcode == 0x06) return ParseChunk(r.content).value().compression;
      }
      return std::string("?");
    };
    EXPECT_EQ(compression_of(random), "");
    EXPECT_EQ(compression_of(text), CompressionName(kind));
  }
}

TEST(Writer, TheSameInputGivesTheSameBytes) {
  WriterOptions o;
  o.chunk_bytes = 3000;
  SampleSpec spec;
  spec.jitter_ns = 3'000'000;
  EXPECT_EQ(SampleFile(o, spec), SampleFile(o, spec));
}

TEST(Writer, DefinitionsAreDeduplicatedAndChecked) {
  Bytes file;
  auto w = MemoryWriter(&file, {});
  const auto a = w->AddSchema("A", "omgidl", AsBytes("struct A { long x; };"));
  const auto a2 = w->AddSchema("A", "omgidl", AsBytes("struct A { long x; };"));
  const auto b = w->AddSchema("A", "omgidl", AsBytes("struct A { long y; };"));
  EXPECT_EQ(a.value(), 1);
  EXPECT_EQ(a2.value(), 1);
  EXPECT_EQ(b.value(), 2);
  EXPECT_EQ(w->AddChannel("t", "cdr", 1).value(), 1);
  EXPECT_EQ(w->AddChannel("t", "cdr", 1).value(), 1);
  EXPECT_EQ(w->AddChannel("t", "cdr", 2).value(), 2);  // same topic, other type: a new channel
  EXPECT_EQ(w->AddChannel("u", "cdr", 9).status().message(),
            "<memory>: channel 'u': unknown schema id 9");
  const Status s = w->WriteMessage({7, 0, 0, 0, {}});
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(s.message(), "<memory>: message on unknown channel 7");
  ASSERT_TRUE(w->Close().ok());
  EXPECT_TRUE(w->Close().ok());  // the same status again
  EXPECT_EQ(w->WriteMessage({1, 0, 0, 0, {}}).code(), StatusCode::kFailedPrecondition);
}

TEST(Writer, OptionsAreValidatedNamingTheField) {
  WriterOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.compression_level = 30;
  EXPECT_EQ(o.Validate().message(), "compression_level = 30 is outside [-7, 22]");
  o = {};
  o.compression = Compression::kLz4;
  o.compression_level = 13;
  EXPECT_FALSE(o.Validate().ok());
  o = {};
  o.chunk_bytes = 0;
  EXPECT_EQ(o.Validate().message().rfind("chunk_bytes = 0 is outside", 0), 0u)
      << o.Validate().message();
  o = {};
  o.size_cap_bytes = 100;
  EXPECT_EQ(o.Validate().message(),
            "size_cap_bytes = 100 is below the smallest cap, 4096 (0 means no cap)");
  Bytes file;
  EXPECT_EQ(Writer::Create(std::make_unique<BufferSink>(&file), o).status().code(),
            StatusCode::kInvalidArgument);
}

TEST(Writer, ParametersAreDeclaredOnce) {
  ParamSet params("recorder");
  DeclareParams<WriterOptions>(params, "mcap.");
  EXPECT_EQ(params.GetString("mcap.compression"), "zstd");
  ASSERT_TRUE(params.SetFromString("mcap.compression=lz4").ok());
  ASSERT_TRUE(params.SetFromString("mcap.chunk_bytes=65536").ok());
  ASSERT_TRUE(params.SetFromString("mcap.size_cap_bytes=1000000").ok());
  const auto o = ReadParams<WriterOptions>(params, "mcap.");
  ASSERT_TRUE(o.ok()) << o.status().ToString();
  EXPECT_EQ(o->compression, Compression::kLz4);
  EXPECT_EQ(o->chunk_bytes, 65536u);
  EXPECT_EQ(o->size_cap_bytes, 1000000u);
  EXPECT_FALSE(params.SetFromString("mcap.compression=bz2").ok() &&
               ReadParams<WriterOptions>(params, "mcap.").ok());
}

TEST(Writer, MetadataAndAttachmentsAreIndexed) {
  WriterOptions o;
  SampleSpec spec;
  const Bytes file = SampleFile(o, spec);
  auto r = OpenBytes(file, Verification::kFull);
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  ASSERT_EQ((*r)->metadata_indexes().size(), 1u);
  EXPECT_EQ((*r)->ReadMetadata((*r)->metadata_indexes()[0]).value(),
            (Metadata{"run", {{"scenario", "drive_flat"}, {"seed", "7"}}}));
  ASSERT_EQ((*r)->attachment_indexes().size(), 1u);
  const Attachment a = (*r)->ReadAttachment((*r)->attachment_indexes()[0]).value();
  EXPECT_EQ(a.name, "calibration.yaml");
  EXPECT_EQ(a.media_type, "application/x-yaml");
  EXPECT_EQ(a.create_time, 1'500'000'000u);
  EXPECT_EQ(a.data, (Bytes{'k', ':', ' ', '1', '\n'}));
  EXPECT_EQ((*r)->statistics()->attachment_count, 1u);
  EXPECT_EQ((*r)->statistics()->metadata_count, 1u);
}

// The size cap: the closed file never exceeds it, stays valid, holds a prefix of what was
// written and says it was cut.
TEST(Writer, TheSizeCapStopsCleanlyAtManyCaps) {
  for (Compression kind : {Compression::kNone, Compression::kZstd, Compression::kLz4}) {
    for (std::uint64_t cap = 4096; cap <= 60000; cap += 3917) {
      Bytes file;
      WriterOptions o;
      o.compression = kind;
      o.chunk_bytes = 3000;
      o.size_cap_bytes = cap;
      auto w = MemoryWriter(&file, o);
      const std::uint16_t s = w->AddSchema("S", "omgidl", AsBytes("struct S { long x; };")).value();
      const std::uint16_t c = w->AddChannel("t", "cdr", s).value();
      std::mt19937 rng(static_cast<std::uint32_t>(cap));
      std::uint64_t accepted = 0;
      Timestamp first_refused = 0;
      Status last;
      for (int i = 0; i < 5000; ++i) {
        Bytes data(20 + rng() % 300);
        for (auto& b : data) b = static_cast<std::uint8_t>('a' + rng() % 3);
        last = w->WriteMessage({c, static_cast<std::uint32_t>(i), Timestamp(1000 + i), 0, data});
        if (!last.ok()) {
          first_refused = 1000 + i;
          break;
        }
        ++accepted;
      }
      ASSERT_EQ(last.code(), StatusCode::kOutOfRange) << cap << " " << last.ToString();
      EXPECT_NE(last.message().find("size cap of " + std::to_string(cap) + " bytes reached"),
                std::string::npos);
      EXPECT_TRUE(w->capped());
      // Later messages are refused too (no holes in the recording), even tiny ones.
      EXPECT_EQ(w->WriteMessage({c, 0, 999999, 0, Bytes{}}).code(), StatusCode::kOutOfRange);
      EXPECT_EQ(w->stats().dropped_messages, 2u);
      ASSERT_TRUE(w->Close().ok()) << cap;
      EXPECT_LE(file.size(), cap);
      EXPECT_GT(file.size(), cap / 2) << "the cap should not stop the recording early";

      auto r = OpenBytes(file, Verification::kFull);
      ASSERT_TRUE(r.ok()) << cap << ": " << r.status().ToString();
      EXPECT_EQ((*r)->statistics()->message_count, accepted);
      auto all = testing::ReadAll(**r);
      ASSERT_TRUE(all.ok());
      ASSERT_EQ(all->size(), accepted);
      for (std::size_t i = 0; i < all->size(); ++i) EXPECT_EQ((*all)[i].sequence, i);
      const auto notice = (*r)->ReadAllMetadata().value();
      ASSERT_EQ(notice.size(), 1u);
      EXPECT_EQ(notice[0].name, kRecordingMetadataName);
      EXPECT_EQ(notice[0].metadata.at(kTruncatedKey), "size_cap");
      EXPECT_EQ(notice[0].metadata.at(kSizeCapKey), std::to_string(cap));
      EXPECT_EQ(notice[0].metadata.at(kFirstDroppedKey), std::to_string(first_refused));
      EXPECT_EQ(notice[0].metadata.at(kDroppedKey), "2");
    }
  }
}

TEST(Writer, TheSizeCapCanBeReachedByDefinitionsAndMetadata) {
  Bytes file;
  WriterOptions o;
  o.size_cap_bytes = 4096;
  auto w = MemoryWriter(&file, o);
  const std::string big(5000, 'x');
  EXPECT_EQ(w->WriteMetadata({"big", {{"k", big}}}).code(), StatusCode::kOutOfRange);
  EXPECT_FALSE(w->capped()) << "a refused metadata record does not end the recording";
  EXPECT_TRUE(w->WriteMetadata({"small", {{"k", "v"}}}).ok());
  const auto schema = w->AddSchema("S", "omgidl", AsBytes(big));
  EXPECT_EQ(schema.status().code(), StatusCode::kOutOfRange);
  EXPECT_TRUE(w->capped());
  ASSERT_TRUE(w->Close().ok());
  EXPECT_LE(file.size(), 4096u);
  auto r = OpenBytes(file, Verification::kFull);
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_EQ((*r)->metadata_indexes().size(), 2u);
}

TEST(Writer, ACapBelowAnEmptyRecordingIsRefused) {
  Bytes file;
  WriterOptions o;
  o.size_cap_bytes = 4096;
  o.library = std::string(5000, 'L');
  const auto w = Writer::Create(std::make_unique<BufferSink>(&file), o);
  ASSERT_FALSE(w.ok());
  EXPECT_NE(w.status().message().find("is smaller than an empty recording"), std::string::npos);
}

TEST(Writer, ADiskErrorIsStickyAndLeavesNoFooter) {
  auto w = Writer::Create("/dev/full", {});
  if (!w.ok()) GTEST_SKIP() << "no /dev/full here: " << w.status().ToString();
  const std::uint16_t c = (*w)->AddChannel("t", "cdr", 0).value();
  Status first;
  std::mt19937 rng(1);
  Bytes d(100000);  // incompressible: the chunks reach the sink at full size
  for (int i = 0; i < 100 && first.ok(); ++i) {
    for (auto& b : d) b = static_cast<std::uint8_t>(rng());
    first = (*w)->WriteMessage({c, 0, Timestamp(i), 0, d});
  }
  ASSERT_FALSE(first.ok());
  EXPECT_EQ(first.code(), StatusCode::kUnavailable);
  EXPECT_NE(first.message().find("/dev/full: write of"), std::string::npos) << first.message();
  EXPECT_NE(first.message().find("No space left on device"), std::string::npos);
  EXPECT_EQ((*w)->WriteMessage({c, 0, 1, 0, Bytes{1}}).message(), first.message());
  EXPECT_EQ((*w)->Close().message(), first.message());
}

TEST(Writer, AnUnwritablePathIsAClearError) {
  const auto w = Writer::Create("/nonexistent-dir/run.mcap", {});
  ASSERT_FALSE(w.ok());
  EXPECT_EQ(w.status().message(),
            "/nonexistent-dir/run.mcap: cannot create: No such file or directory");
}

TEST(Writer, WritesAFileThatTheReaderOpens) {
  const std::string dir = testing::MakeTempDir("mcap-writer");
  const std::string path = dir + "/run.mcap";
  {
    auto w = Writer::Create(path, {});
    ASSERT_TRUE(w.ok());
    testing::WriteSample(**w, {});
    ASSERT_TRUE((*w)->Close().ok());
    EXPECT_EQ((*w)->stats().messages, 300u);
    EXPECT_GT((*w)->stats().uncompressed_chunk_bytes, (*w)->stats().compressed_chunk_bytes);
  }
  auto r = Reader::Open(path);
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_EQ((*r)->statistics()->message_count, 300u);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace rover::mcap
