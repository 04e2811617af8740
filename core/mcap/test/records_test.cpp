#include "rover/mcap/records.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "rover/mcap/crc32.hpp"

namespace rover::mcap {
namespace {

// The test's own little-endian packer: the layouts below are written out field by field from
// the specification's tables, independently of the library's encoder.
struct Le {
  Bytes b;
  Le& u8(std::uint8_t v) {
    b.push_back(v);
    return *this;
  }
  Le& u16(std::uint16_t v) { return n(v, 2); }
  Le& u32(std::uint32_t v) { return n(v, 4); }
  Le& u64(std::uint64_t v) { return n(v, 8); }
  Le& str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    b.insert(b.end(), s.begin(), s.end());
    return *this;
  }
  Le& raw(const Bytes& r) {
    b.insert(b.end(), r.begin(), r.end());
    return *this;
  }
  Le& n(std::uint64_t v, int k) {
    for (int i = 0; i < k; ++i) b.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
    return *this;
  }
  /// <opcode><uint64 length><content>.
  static Bytes Record(std::uint8_t op, const Le& content) {
    Le r;
    r.u8(op).u64(content.b.size()).raw(content.b);
    return r.b;
  }
};

template <class R>
Bytes Encode(const R& r) {
  Bytes out;
  AppendRecord(out, r);
  return out;
}

ByteSpan ContentOf(const Bytes& record) { return ByteSpan(record).subspan(kRecordPrefixBytes); }

TEST(Records, MagicIsTheSpecificationsEightBytes) {
  EXPECT_EQ(Bytes(kMagic.begin(), kMagic.end()),
            (Bytes{0x89, 0x4D, 0x43, 0x41, 0x50, 0x30, 0x0D, 0x0A}));
}

TEST(Records, HeaderLayout) {
  const Header h{"", "rover_mcap 1"};
  EXPECT_EQ(Encode(h), Le::Record(0x01, Le().str("").str("rover_mcap 1")));
  EXPECT_EQ(ParseHeader(ContentOf(Encode(h))).value(), h);
}

TEST(Records, FooterLayout) {
  const Footer f{0x1122334455667788ull, 0x0102030405060708ull, 0xCAFEBABEu};
  const Bytes e = Encode(f);
  EXPECT_EQ(e, Le::Record(
                   0x02, Le().u64(f.summary_start).u64(f.summary_offset_start).u32(f.summary_crc)));
  EXPECT_EQ(e.size(), kFooterRecordBytes);
  EXPECT_EQ(ParseFooter(ContentOf(e)).value(), f);
}

TEST(Records, SchemaLayout) {
  const Schema s{7, "rover::dl::PoseEstimate", "omgidl", Bytes{'s', 't', 'r'}};
  const Bytes e = Encode(s);
  EXPECT_EQ(e, Le::Record(0x03, Le().u16(7)
                                    .str("rover::dl::PoseEstimate")
                                    .str("omgidl")
                                    .u32(3)
                                    .raw(Bytes{'s', 't', 'r'})));
  EXPECT_EQ(RecordSize(s), e.size());
  EXPECT_EQ(ParseSchema(ContentOf(e)).value(), s);
}

TEST(Records, ChannelLayoutWithAMapSortedByKey) {
  const Channel c{3, 7, "dl/pose", "cdr", {{"b", "2"}, {"a", "1"}}};
  const Bytes e = Encode(c);
  Le map;
  map.str("a").str("1").str("b").str("2");
  EXPECT_EQ(e, Le::Record(0x04, Le().u16(3)
                                    .u16(7)
                                    .str("dl/pose")
                                    .str("cdr")
                                    .u32(static_cast<std::uint32_t>(map.b.size()))
                                    .raw(map.b)));
  EXPECT_EQ(RecordSize(c), e.size());
  EXPECT_EQ(ParseChannel(ContentOf(e)).value(), c);
}

TEST(Records, MessageLayoutDataIsTheRestOfTheRecord) {
  const Bytes data{0x00, 0x01, 0x00, 0x00, 0xAB};
  const MessageView m{3, 42, 1'000'000'123, 1'000'000'000, data};
  const Bytes e = Encode(m);
  EXPECT_EQ(e,
            Le::Record(0x05, Le().u16(3).u32(42).u64(1'000'000'123).u64(1'000'000'000).raw(data)));
  EXPECT_EQ(MessageRecordSize(data.size()), e.size());
  const MessageView back = ParseMessage(ContentOf(e)).value();
  EXPECT_EQ(back.channel_id, 3);
  EXPECT_EQ(back.sequence, 42u);
  EXPECT_EQ(back.log_time, 1'000'000'123u);
  EXPECT_EQ(back.publish_time, 1'000'000'000u);
  EXPECT_EQ(Bytes(back.data.begin(), back.data.end()), data);
}

TEST(Records, ChunkLayoutHasAUint64LengthBeforeItsRecords) {
  const Bytes records{1, 2, 3, 4};
  const ChunkView c{10, 20, 4, 0xDEADBEEFu, "zstd", records};
  const Bytes e = Encode(c);
  EXPECT_EQ(
      e, Le::Record(0x06,
                    Le().u64(10).u64(20).u64(4).u32(0xDEADBEEFu).str("zstd").u64(4).raw(records)));
  EXPECT_EQ(ChunkRecordSize(records.size(), "zstd"), e.size());
  const ChunkView back = ParseChunk(ContentOf(e)).value();
  EXPECT_EQ(back.compression, "zstd");
  EXPECT_EQ(back.uncompressed_crc, 0xDEADBEEFu);
  EXPECT_EQ(Bytes(back.records.begin(), back.records.end()), records);
}

TEST(Records, MessageIndexLayoutIsAnArrayOfTimeOffsetPairs) {
  const MessageIndex mi{5, {{100, 0}, {90, 37}}};
  const Bytes e = Encode(mi);
  EXPECT_EQ(e, Le::Record(0x07, Le().u16(5).u32(32).u64(100).u64(0).u64(90).u64(37)));
  EXPECT_EQ(MessageIndexRecordSize(2), e.size());
  EXPECT_EQ(ParseMessageIndex(ContentOf(e)).value(), mi);
}

TEST(Records, ChunkIndexLayout) {
  ChunkIndex ci;
  ci.message_start_time = 1;
  ci.message_end_time = 2;
  ci.chunk_start_offset = 30;
  ci.chunk_length = 400;
  ci.message_index_offsets = {{1, 430}, {4, 470}};
  ci.message_index_length = 80;
  ci.compression = "lz4";
  ci.compressed_size = 350;
  ci.uncompressed_size = 1000;
  const Bytes e = Encode(ci);
  EXPECT_EQ(e, Le::Record(0x08, Le().u64(1)
                                    .u64(2)
                                    .u64(30)
                                    .u64(400)
                                    .u32(20)
                                    .u16(1)
                                    .u64(430)
                                    .u16(4)
                                    .u64(470)
                                    .u64(80)
                                    .str("lz4")
                                    .u64(350)
                                    .u64(1000)));
  EXPECT_EQ(ChunkIndexRecordSize(2, "lz4"), e.size());
  EXPECT_EQ(ParseChunkIndex(ContentOf(e)).value(), ci);
}

TEST(Records, AttachmentLayoutEndsWithTheCrcOfEveryFieldBeforeIt) {
  const Attachment a{5, 4, "cal.yaml", "application/x-yaml", Bytes{'x', '\n'}};
  const Bytes e = Encode(a);
  Le fields;
  fields.u64(5).u64(4).str("cal.yaml").str("application/x-yaml").u64(2).raw(Bytes{'x', '\n'});
  const std::uint32_t crc = ComputeCrc32(fields.b);
  EXPECT_EQ(e, Le::Record(0x09, Le(fields).u32(crc)));
  EXPECT_EQ(ParseAttachment(ContentOf(e)).value(), a);

  Bytes bad = e;
  bad[kRecordPrefixBytes + 24] ^= 1;  // inside the name
  const auto r = ParseAttachment(ContentOf(bad));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("does not match"), std::string::npos) << r.status().message();

  // A crc of 0 means "not computed": not checked.
  Bytes unchecked = Le::Record(0x09, Le(fields).u32(0));
  unchecked[kRecordPrefixBytes + 24] ^= 1;
  EXPECT_TRUE(ParseAttachment(ContentOf(unchecked)).ok());
}

TEST(Records, AttachmentIndexLayout) {
  const AttachmentIndex ai{100, 80, 5, 4, 2, "cal.yaml", "text/plain"};
  const Bytes e = Encode(ai);
  EXPECT_EQ(
      e, Le::Record(0x0A,
                    Le().u64(100).u64(80).u64(5).u64(4).u64(2).str("cal.yaml").str("text/plain")));
  EXPECT_EQ(RecordSize(ai), e.size());
  EXPECT_EQ(ParseAttachmentIndex(ContentOf(e)).value(), ai);
}

TEST(Records, StatisticsLayout) {
  Statistics s;
  s.message_count = 9;
  s.schema_count = 2;
  s.channel_count = 3;
  s.attachment_count = 1;
  s.metadata_count = 4;
  s.chunk_count = 5;
  s.message_start_time = 11;
  s.message_end_time = 99;
  s.channel_message_counts = {{1, 6}, {2, 3}};
  const Bytes e = Encode(s);
  EXPECT_EQ(e, Le::Record(0x0B, Le().u64(9)
                                    .u16(2)
                                    .u32(3)
                                    .u32(1)
                                    .u32(4)
                                    .u32(5)
                                    .u64(11)
                                    .u64(99)
                                    .u32(20)
                                    .u16(1)
                                    .u64(6)
                                    .u16(2)
                                    .u64(3)));
  EXPECT_EQ(StatisticsRecordSize(2), e.size());
  EXPECT_EQ(ParseStatistics(ContentOf(e)).value(), s);
}

TEST(Records, MetadataAndItsIndexLayouts) {
  const Metadata m{"run", {{"seed", "1"}}};
  const Bytes e = Encode(m);
  EXPECT_EQ(e, Le::Record(0x0C, Le().str("run").u32(13).str("seed").str("1")));
  EXPECT_EQ(RecordSize(m), e.size());
  EXPECT_EQ(ParseMetadata(ContentOf(e)).value(), m);

  const MetadataIndex mi{64, e.size(), "run"};
  const Bytes ei = Encode(mi);
  EXPECT_EQ(ei, Le::Record(0x0D, Le().u64(64).u64(e.size()).str("run")));
  EXPECT_EQ(RecordSize(mi), ei.size());
  EXPECT_EQ(ParseMetadataIndex(ContentOf(ei)).value(), mi);
}

TEST(Records, SummaryOffsetAndDataEndLayouts) {
  const SummaryOffset so{0x04, 1234, 56};
  EXPECT_EQ(Encode(so), Le::Record(0x0E, Le().u8(4).u64(1234).u64(56)));
  EXPECT_EQ(Encode(so).size(), kSummaryOffsetRecordBytes);
  EXPECT_EQ(ParseSummaryOffset(ContentOf(Encode(so))).value(), so);
  const DataEnd de{0x01020304u};
  EXPECT_EQ(Encode(de), Le::Record(0x0F, Le().u32(0x01020304u)));
  EXPECT_EQ(Encode(de).size(), kDataEndRecordBytes);
  EXPECT_EQ(ParseDataEnd(ContentOf(Encode(de))).value(), de);
}

// Every strict prefix of a record's content must fail to parse (all fields have a fixed or a
// prefixed length), and the error names a field.
template <class R, class P>
void ExpectEveryPrefixFails(const R& record, P parse, const char* what) {
  const Bytes e = Encode(record);
  const ByteSpan content = ContentOf(e);
  for (std::size_t n = 0; n < content.size(); ++n) {
    const auto r = parse(content.first(n));
    ASSERT_FALSE(r.ok()) << what << " parsed from " << n << " of " << content.size() << " bytes";
    EXPECT_EQ(r.status().message().rfind("field '", 0), 0u) << r.status().message();
  }
}

TEST(Records, TruncatedContentFailsNamingTheField) {
  ExpectEveryPrefixFails(Header{"p", "lib"}, ParseHeader, "Header");
  ExpectEveryPrefixFails(Footer{1, 2, 3}, ParseFooter, "Footer");
  ExpectEveryPrefixFails(Schema{1, "n", "omgidl", Bytes{1, 2}}, ParseSchema, "Schema");
  ExpectEveryPrefixFails(Channel{1, 1, "t", "cdr", {{"k", "v"}}}, ParseChannel, "Channel");
  ExpectEveryPrefixFails(ChunkView{1, 2, 3, 4, "lz4", Bytes{9, 9, 9}}, ParseChunk, "Chunk");
  ExpectEveryPrefixFails(MessageIndex{1, {{1, 2}}}, ParseMessageIndex, "MessageIndex");
  ChunkIndex ci;
  ci.message_index_offsets = {{1, 2}};
  ci.compression = "zstd";
  ExpectEveryPrefixFails(ci, ParseChunkIndex, "ChunkIndex");
  ExpectEveryPrefixFails(Attachment{1, 2, "a", "b", Bytes{3}}, ParseAttachment, "Attachment");
  ExpectEveryPrefixFails(AttachmentIndex{1, 2, 3, 4, 5, "a", "b"}, ParseAttachmentIndex,
                         "AttachmentIndex");
  Statistics st;
  st.channel_message_counts = {{1, 1}};
  ExpectEveryPrefixFails(st, ParseStatistics, "Statistics");
  ExpectEveryPrefixFails(Metadata{"m", {{"k", "v"}}}, ParseMetadata, "Metadata");
  ExpectEveryPrefixFails(MetadataIndex{1, 2, "m"}, ParseMetadataIndex, "MetadataIndex");
  ExpectEveryPrefixFails(SummaryOffset{1, 2, 3}, ParseSummaryOffset, "SummaryOffset");
  ExpectEveryPrefixFails(DataEnd{1}, ParseDataEnd, "DataEnd");
  const MessageView m{1, 2, 3, 4, {}};
  const Bytes e = Encode(m);
  for (std::size_t n = 0; n < kMessageHeaderBytes; ++n) {
    EXPECT_FALSE(ParseMessage(ContentOf(e).first(n)).ok()) << n;
  }
}

TEST(Records, ErrorsSayWhatRanPastTheEnd) {
  Bytes e = Encode(Channel{1, 0, "dl/pose", "cdr", {}});
  e[kRecordPrefixBytes + 4] = 200;  // the topic's length
  EXPECT_EQ(ParseChannel(ContentOf(e)).status().message(),
            "field 'topic': a string of 200 bytes runs past the end of the record (18 bytes left)");
  EXPECT_EQ(ParseFooter(Bytes{1, 2, 3}).status().message(),
            "field 'summary_start': needs 8 bytes, 3 are left in the record");
  // A (uint16, uint64) map whose byte length is no multiple of 10.
  const Bytes stats =
      Le().u64(0).u16(0).u32(0).u32(0).u32(0).u32(0).u64(0).u64(0).u32(3).raw(Bytes{1, 2, 3}).b;
  EXPECT_EQ(ParseStatistics(stats).status().message(),
            "field 'channel_message_counts': a map of (uint16, uint64) entries has 3 bytes, not a "
            "multiple of 10");
  const Bytes chunk = Le().u64(5).u64(4).u64(0).u32(0).str("").u64(0).b;
  EXPECT_EQ(ParseChunk(chunk).status().message(),
            "message_start_time 5 is after message_end_time 4");
}

TEST(Records, FieldsAddedByLaterVersionsAreIgnored) {
  // "Records may be extended by adding new fields at the end": readers skip what follows.
  const Channel c{2, 1, "t", "cdr", {{"k", "v"}}};
  Bytes e = Encode(c);
  e.insert(e.end(), {0xEE, 0xEE, 0xEE});
  EXPECT_EQ(ParseChannel(ContentOf(e)).value(), c);
  Statistics s;
  s.message_count = 3;
  Bytes es = Encode(s);
  es.insert(es.end(), 16, 0x77);
  EXPECT_EQ(ParseStatistics(ContentOf(es)).value(), s);
}

TEST(Records, SplitRecordChecksThePrefixAndTheLength) {
  Bytes two = Encode(DataEnd{5});
  const Bytes more = Encode(Header{"a", "b"});
  two.insert(two.end(), more.begin(), more.end());
  const RecordView first = SplitRecord(two, 0).value();
  EXPECT_EQ(first.opcode, 0x0F);
  EXPECT_EQ(first.size(), kDataEndRecordBytes);
  const RecordView second = SplitRecord(two, first.size()).value();
  EXPECT_EQ(second.opcode, 0x01);
  EXPECT_EQ(first.size() + second.size(), two.size());
  EXPECT_EQ(SplitRecord(two, two.size() - 4).status().message(),
            "the record prefix needs 9 bytes, 4 are left");
  Bytes cut(two.begin(), two.end() - 1);
  EXPECT_EQ(SplitRecord(cut, first.size()).status().message(),
            "a Header record of 10 content bytes runs past the end (9 bytes left)");
}

TEST(Records, OpcodeNames) {
  EXPECT_EQ(OpcodeName(Opcode::kChunkIndex), "ChunkIndex");
  EXPECT_EQ(OpcodeName(std::uint8_t{0x0F}), "DataEnd");
  EXPECT_EQ(OpcodeName(std::uint8_t{0x00}), "invalid record 0x00");
  EXPECT_EQ(OpcodeName(std::uint8_t{0x42}), "unknown record 0x42");
  EXPECT_EQ(OpcodeName(std::uint8_t{0x80}), "private record 0x80");
  EXPECT_EQ(Hex32(0xABCu), "0x00000abc");
}

}  // namespace
}  // namespace rover::mcap
