#include "rover/mcap/io.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <string>
#include <vector>

#include "mcap_test_util.hpp"

namespace rover::mcap {
namespace {

TEST(FileSinkAndSource, WriteThenReadBackAcrossTheBuffer) {
  const std::string dir = testing::MakeTempDir("mcap-io");
  const std::string path = dir + "/a.bin";
  std::vector<std::uint8_t> expected;
  {
    auto sink = FileSink::Create(path);
    ASSERT_TRUE(sink.ok()) << sink.status().ToString();
    // Small pieces (buffered), one piece larger than the buffer (written through), small again.
    for (int i = 0; i < 1000; ++i) {
      const std::vector<std::uint8_t> piece(37, static_cast<std::uint8_t>(i));
      ASSERT_TRUE((*sink)->Write(piece).ok());
      expected.insert(expected.end(), piece.begin(), piece.end());
    }
    const std::vector<std::uint8_t> big(3 << 20, 0xAB);
    ASSERT_TRUE((*sink)->Write(big).ok());
    expected.insert(expected.end(), big.begin(), big.end());
    ASSERT_TRUE((*sink)->Write(std::vector<std::uint8_t>{1, 2, 3}).ok());
    expected.insert(expected.end(), {1, 2, 3});
    ASSERT_TRUE((*sink)->Close().ok());
    EXPECT_EQ((*sink)->Close().code(), StatusCode::kFailedPrecondition);
  }
  auto source = FileSource::Open(path);
  ASSERT_TRUE(source.ok());
  ASSERT_EQ((*source)->size(), expected.size());
  std::vector<std::uint8_t> got(expected.size());
  ASSERT_TRUE((*source)->Read(0, got).ok());
  EXPECT_EQ(got, expected);
  std::vector<std::uint8_t> tail(10);
  const Status past = (*source)->Read(expected.size() - 5, tail);
  EXPECT_EQ(past.message(), path + ": read of 10 bytes at offset " +
                                std::to_string(expected.size() - 5) + " failed: the file ends at " +
                                std::to_string(expected.size()));
  std::remove(path.c_str());
}

TEST(FileSinkAndSource, ErrorsNameThePathAndTheReason) {
  const auto sink = FileSink::Create("/nonexistent-dir/x.mcap");
  ASSERT_FALSE(sink.ok());
  EXPECT_EQ(sink.status().code(), StatusCode::kUnavailable);
  EXPECT_EQ(sink.status().message(),
            "/nonexistent-dir/x.mcap: cannot create: No such file or directory");
  const auto source = FileSource::Open("/nonexistent-dir/x.mcap");
  EXPECT_EQ(source.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(source.status().message(),
            "/nonexistent-dir/x.mcap: cannot open: No such file or directory");
  EXPECT_EQ(FileSource::Open("/").status().code(), StatusCode::kInvalidArgument);
}

TEST(FileSinkAndSource, AFullDiskIsReportedWithTheOffset) {
  // /dev/full refuses every write with ENOSPC, like a full file system.
  auto sink = FileSink::Create("/dev/full");
  if (!sink.ok()) GTEST_SKIP() << "no /dev/full here: " << sink.status().ToString();
  ASSERT_TRUE((*sink)->Write(std::vector<std::uint8_t>(100, 1)).ok());  // still buffered
  const Status s = (*sink)->Close();
  EXPECT_EQ(s.code(), StatusCode::kUnavailable);
  EXPECT_EQ(s.message(),
            "/dev/full: write of 100 bytes at offset 0 failed: No space left on device");
}

TEST(BufferSinkAndSource, HoldBytesInMemory) {
  std::vector<std::uint8_t> bytes;
  BufferSink sink(&bytes, "mem");
  ASSERT_TRUE(sink.Write(std::vector<std::uint8_t>{1, 2, 3, 4}).ok());
  ASSERT_TRUE(sink.Close().ok());
  EXPECT_EQ(sink.name(), "mem");
  BufferSource source(bytes, "mem");
  std::vector<std::uint8_t> two(2);
  ASSERT_TRUE(source.Read(2, two).ok());
  EXPECT_EQ(two, (std::vector<std::uint8_t>{3, 4}));
  std::vector<std::uint8_t> none;
  EXPECT_TRUE(source.Read(4, none).ok());
  EXPECT_EQ(source.Read(3, two).message(),
            "mem: read of 2 bytes at offset 3 failed: the data ends at 4");
}

}  // namespace
}  // namespace rover::mcap
