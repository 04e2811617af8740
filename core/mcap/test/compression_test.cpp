#include "rover/mcap/compression.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string>
#include <vector>

namespace rover::mcap {
namespace {

using Bytes = std::vector<std::uint8_t>;

Bytes Compressible(std::size_t n) {
  Bytes b(n);
  for (std::size_t i = 0; i < n; ++i)
    b[i] = static_cast<std::uint8_t>("rover"[i % 5] + (i / 997) % 3);
  return b;
}

Bytes Random(std::size_t n, std::uint32_t seed) {
  std::mt19937 rng(seed);
  Bytes b(n);
  for (auto& x : b) x = static_cast<std::uint8_t>(rng());
  return b;
}

class EachCompression : public ::testing::TestWithParam<Compression> {};

TEST_P(EachCompression, RoundTripsEmptySmallCompressibleAndRandomData) {
  Compressor c(GetParam(), 0);
  Decompressor d;
  for (const Bytes& in : {Bytes{}, Bytes{42}, Compressible(100000), Random(70000, 1)}) {
    Bytes packed;
    ASSERT_TRUE(c.Compress(in, packed).ok());
    Bytes out;
    const Status s = d.Decompress(CompressionName(GetParam()), packed, in.size(), out);
    ASSERT_TRUE(s.ok()) << s.ToString();
    EXPECT_EQ(out, in);
  }
  const Bytes text = Compressible(100000);
  Bytes packed;
  ASSERT_TRUE(c.Compress(text, packed).ok());
  if (GetParam() != Compression::kNone) {
    EXPECT_LT(packed.size(), text.size() / 5);
  }
}

TEST_P(EachCompression, EveryLevelOfTheRangeWorks) {
  const LevelRange r = CompressionLevels(GetParam());
  const Bytes in = Compressible(20000);
  Decompressor d;
  for (int level : {r.lo, 0, r.hi}) {
    Compressor c(GetParam(), level);
    Bytes packed;
    Bytes out;
    ASSERT_TRUE(c.Compress(in, packed).ok()) << level;
    ASSERT_TRUE(d.Decompress(CompressionName(GetParam()), packed, in.size(), out).ok()) << level;
    EXPECT_EQ(out, in);
  }
}

TEST_P(EachCompression, AWrongUncompressedSizeIsAnError) {
  Compressor c(GetParam(), 0);
  Decompressor d;
  const Bytes in = Compressible(5000);
  Bytes packed;
  ASSERT_TRUE(c.Compress(in, packed).ok());
  Bytes out;
  for (std::uint64_t wrong : {std::uint64_t{4999}, std::uint64_t{5001}, std::uint64_t{0}}) {
    const Status s = d.Decompress(CompressionName(GetParam()), packed, wrong, out);
    EXPECT_FALSE(s.ok()) << wrong;
    EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  }
  // The decompressor is usable again after an error.
  ASSERT_TRUE(d.Decompress(CompressionName(GetParam()), packed, in.size(), out).ok());
  EXPECT_EQ(out, in);
}

class EachCodec : public ::testing::TestWithParam<Compression> {};

TEST_P(EachCodec, TruncatedDataIsAnErrorAtEveryLength) {
  Compressor c(GetParam(), 0);
  Decompressor d;
  const Bytes in = Compressible(3000);
  Bytes packed;
  ASSERT_TRUE(c.Compress(in, packed).ok());
  for (std::size_t n = 0; n < packed.size(); ++n) {
    Bytes out;
    const Bytes cut(packed.begin(), packed.begin() + static_cast<std::ptrdiff_t>(n));
    EXPECT_FALSE(d.Decompress(CompressionName(GetParam()), cut, in.size(), out).ok()) << n;
  }
}

TEST_P(EachCodec, CorruptDataNeverCrashesAndIsOftenCaught) {
  // Frames carry no checksum (the chunk's CRC covers the records), so a flipped byte may decode
  // to other bytes of the right size, which the reader's CRC check then rejects. Here: no crash,
  // and the frame structure itself catches some.
  Compressor c(GetParam(), 0);
  Decompressor d;
  const Bytes in = Compressible(4000);
  Bytes packed;
  ASSERT_TRUE(c.Compress(in, packed).ok());
  int caught = 0;
  for (std::size_t i = 0; i < packed.size(); ++i) {
    Bytes bad = packed;
    bad[i] ^= 0x5A;
    Bytes out;
    if (!d.Decompress(CompressionName(GetParam()), bad, in.size(), out).ok()) ++caught;
  }
  EXPECT_GT(caught, 0);
}

std::string ParamName(const ::testing::TestParamInfo<Compression>& p) {
  const std::string_view n = CompressionName(p.param);
  return n.empty() ? std::string("none") : std::string(n);
}
INSTANTIATE_TEST_SUITE_P(Codecs, EachCompression,
                         ::testing::Values(Compression::kNone, Compression::kZstd,
                                           Compression::kLz4),
                         ParamName);
INSTANTIATE_TEST_SUITE_P(Codecs, EachCodec,
                         ::testing::Values(Compression::kZstd, Compression::kLz4), ParamName);

TEST(Compression, NamesAreTheChunkFieldValues) {
  EXPECT_EQ(CompressionName(Compression::kNone), "");
  EXPECT_EQ(CompressionName(Compression::kZstd), "zstd");
  EXPECT_EQ(CompressionName(Compression::kLz4), "lz4");
}

TEST(Compression, FramesStartWithTheirFormatsMagic) {
  const Bytes in = Compressible(1000);
  Bytes packed;
  Compressor zstd(Compression::kZstd, 0);
  ASSERT_TRUE(zstd.Compress(in, packed).ok());
  EXPECT_EQ(Bytes(packed.begin(), packed.begin() + 4), (Bytes{0x28, 0xB5, 0x2F, 0xFD}));
  Compressor lz4(Compression::kLz4, 0);
  ASSERT_TRUE(lz4.Compress(in, packed).ok());
  EXPECT_EQ(Bytes(packed.begin(), packed.begin() + 4), (Bytes{0x04, 0x22, 0x4D, 0x18}));
}

TEST(Compression, ConcatenatedFramesDecodeAsOne) {
  const Bytes a = Compressible(700);
  const Bytes b = Random(300, 9);
  Bytes whole = a;
  whole.insert(whole.end(), b.begin(), b.end());
  Decompressor d;
  for (Compression kind : {Compression::kZstd, Compression::kLz4}) {
    Compressor c(kind, 0);
    Bytes pa;
    Bytes pb;
    ASSERT_TRUE(c.Compress(a, pa).ok());
    ASSERT_TRUE(c.Compress(b, pb).ok());
    pa.insert(pa.end(), pb.begin(), pb.end());
    Bytes out;
    const Status s = d.Decompress(CompressionName(kind), pa, whole.size(), out);
    ASSERT_TRUE(s.ok()) << s.ToString();
    EXPECT_EQ(out, whole);
  }
}

TEST(Compression, UnknownCompressionIsNamed) {
  Decompressor d;
  Bytes out;
  const Status s = d.Decompress("bz2", Bytes{1, 2, 3}, 3, out);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(s.message(), "unsupported compression 'bz2' (this reader knows '', 'zstd', 'lz4')");
}

TEST(Compression, UncompressedRecordsMustHaveTheStatedSize) {
  Decompressor d;
  Bytes out;
  const Status s = d.Decompress("", Bytes{1, 2, 3}, 4, out);
  EXPECT_EQ(s.message(), "decompressed to 3 bytes, the chunk says 4");
}

}  // namespace
}  // namespace rover::mcap
