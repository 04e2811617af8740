#include "rover/recording/cdr.hpp"

#include <gtest/gtest.h>

namespace rover::recording {
namespace {

using Bytes = std::vector<std::uint8_t>;

TEST(Cdr, ClockRoundTripInXcdr1LittleEndian) {
  ClockSample c;
  c.header.stamp_ns = 1'500'000'000;
  c.header.frame_id = "sim";
  c.header.seq = 7;
  c.sim_time_ns = 1'500'000'000;
  c.real_time_factor = 2.5;
  c.paused = true;
  const Bytes b = WriteClockSample(c);
  // Header 00 01 (CDR_LE); stamp at payload 0; frame length 4 at 8; "sim\0" at 12; seq at 16;
  // sim_time_ns aligned to 8 at 24; rtf at 32; paused at 40; the empty `written` sequence's
  // length aligned to 4 at 44; 48 payload bytes, no padding.
  ASSERT_EQ(b.size(), 4u + 48u);
  EXPECT_EQ(b[0], 0x00);
  EXPECT_EQ(b[1], 0x01);
  EXPECT_EQ(b[3], 0);  // padding bytes the option field announces
  EXPECT_EQ(b[4 + 44], 0);  // written: empty
  EXPECT_EQ(b[4 + 8], 4);
  EXPECT_EQ(b[4 + 12], 's');
  EXPECT_EQ(b[4 + 16], 7);
  EXPECT_EQ(b[4 + 40], 1);
  auto back = ReadClockSample(b);
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->header.stamp_ns, c.header.stamp_ns);
  EXPECT_EQ(back->header.frame_id, "sim");
  EXPECT_EQ(back->header.seq, 7u);
  EXPECT_EQ(back->sim_time_ns, c.sim_time_ns);
  EXPECT_EQ(back->real_time_factor, 2.5);
  EXPECT_TRUE(back->paused);
}

TEST(Cdr, BigEndianAndXcdr2Alignment) {
  // XCDR1 big-endian header: stamp 0x0102, frame "ab", seq 9.
  Bytes be = {0x00, 0x00, 0x00, 0x00, 0, 0, 0, 0, 0, 0, 0x01, 0x02, 0, 0, 0, 3, 'a', 'b', 0, 0,
              0, 0, 0, 9};
  auto h = ReadSampleHeader(be);
  ASSERT_TRUE(h.ok()) << h.status().message();
  EXPECT_EQ(h->stamp_ns, 0x0102);
  EXPECT_EQ(h->frame_id, "ab");
  EXPECT_EQ(h->seq, 9u);
  // XCDR2 little-endian clock: after seq (ends at payload 16+4=20 with frame "x\0\0"?) the
  // int64 aligns to 4, not 8.
  Bytes x2 = {0x00, 0x07, 0x00, 0x00,
              5, 0, 0, 0, 0, 0, 0, 0,    // stamp 5
              2, 0, 0, 0, 'x', 0, 0, 0,  // frame "x" + pad to 4
              1, 0, 0, 0,                // seq at 16
              6, 0, 0, 0, 0, 0, 0, 0,    // sim_time_ns at 20 (XCDR2: 4-aligned)
              0, 0, 0, 0, 0, 0, 0xf0, 0x3f,  // 1.0
              0};
  auto c = ReadClockSample(x2);
  ASSERT_TRUE(c.ok()) << c.status().message();
  EXPECT_EQ(c->sim_time_ns, 6);
  EXPECT_EQ(c->real_time_factor, 1.0);
  EXPECT_FALSE(c->paused);
}

TEST(Cdr, Uint16AndOctetSequences) {
  // XCDR1 little-endian: uint32 1, uint16 300 at 4, pad to 8, sequence<octet> {7, 8, 9}.
  const Bytes b = {0x00, 0x01, 0x00, 0x00, 1, 0, 0, 0, 0x2c, 0x01, 0, 0, 3, 0, 0, 0, 7, 8, 9};
  auto r = CdrReader::Open(b);
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(*r->Uint32("a"), 1u);
  EXPECT_EQ(*r->Uint16("b"), 300u);
  const auto o = r->Octets("c");
  ASSERT_TRUE(o.ok()) << o.status().message();
  ASSERT_EQ(o->size(), 3u);
  EXPECT_EQ((*o)[2], 9);
  // A sequence longer than the sample is named.
  const Bytes short_seq = {0x00, 0x01, 0x00, 0x00, 9, 0, 0, 0, 1, 2};
  auto s = CdrReader::Open(short_seq);
  EXPECT_NE(s->Octets("image").status().message().find("'image'"), std::string::npos);
}

TEST(Cdr, MalformedSamplesNameWhatIsWrong) {
  EXPECT_NE(ReadSampleHeader(Bytes{0, 1}).status().message().find("shorter than its 4-byte"),
            std::string::npos);
  EXPECT_NE(ReadSampleHeader(Bytes{0, 3, 0, 0, 1, 2, 3, 4}).status().message().find(
                "encapsulation 0x0003 (not plain CDR"),
            std::string::npos);
  const Bytes truncated = {0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 4, 0};
  EXPECT_NE(ReadSampleHeader(truncated).status().message().find("'header.frame_id'"),
            std::string::npos)
      << ReadSampleHeader(truncated).status().message();
  Bytes long_frame = {0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 40, 0, 0, 0};
  long_frame.resize(long_frame.size() + 44, 'a');
  EXPECT_NE(ReadSampleHeader(long_frame).status().message().find("exceeds its bound of 31"),
            std::string::npos);
  Bytes no_nul = {0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0, 2, 0, 0, 0, 'a', 'b', 0, 0, 1, 0, 0, 0};
  EXPECT_NE(ReadSampleHeader(no_nul).status().message().find("not NUL-terminated"),
            std::string::npos);
  ClockSample c;
  Bytes bad_bool = WriteClockSample(c);
  bad_bool[4 + 40] = 2;
  EXPECT_NE(ReadClockSample(bad_bool).status().message().find("boolean byte 2"), std::string::npos);
}

}  // namespace
}  // namespace rover::recording
