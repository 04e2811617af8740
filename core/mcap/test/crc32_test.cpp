#include "rover/mcap/crc32.hpp"

#include <gtest/gtest.h>

#include <random>
#include <string_view>
#include <vector>

namespace rover::mcap {
namespace {

std::uint32_t Crc(std::string_view s) {
  return ComputeCrc32({reinterpret_cast<const std::uint8_t*>(s.data()), s.size()});
}

// Bit by bit, straight from the definition: the reference the table version must match.
std::uint32_t BitwiseCrc(const std::vector<std::uint8_t>& data) {
  std::uint32_t c = 0xFFFFFFFFu;
  for (std::uint8_t b : data) {
    c ^= b;
    for (int k = 0; k < 8; ++k) c = (c & 1u) ? (c >> 1) ^ 0xEDB88320u : c >> 1;
  }
  return ~c;
}

TEST(Crc32, KnownVectors) {
  EXPECT_EQ(Crc(""), 0x00000000u);
  EXPECT_EQ(Crc("a"), 0xE8B7BE43u);
  EXPECT_EQ(Crc("123456789"), 0xCBF43926u);  // the CRC-32/ISO-HDLC check value
  EXPECT_EQ(Crc("The quick brown fox jumps over the lazy dog"), 0x414FA339u);
}

TEST(Crc32, TableVersionMatchesTheBitwiseDefinitionAtEveryLength) {
  std::mt19937 rng(3);
  for (std::size_t n = 0; n < 70; ++n) {
    std::vector<std::uint8_t> data(n);
    for (auto& b : data) b = static_cast<std::uint8_t>(rng());
    EXPECT_EQ(ComputeCrc32(data), BitwiseCrc(data)) << "length " << n;
  }
  std::vector<std::uint8_t> big(100003);
  for (auto& b : big) b = static_cast<std::uint8_t>(rng());
  EXPECT_EQ(ComputeCrc32(big), BitwiseCrc(big));
}

TEST(Crc32, PiecesGiveTheSameCrcAsTheWhole) {
  std::mt19937 rng(5);
  std::vector<std::uint8_t> data(5000);
  for (auto& b : data) b = static_cast<std::uint8_t>(rng());
  const std::uint32_t whole = ComputeCrc32(data);
  for (int trial = 0; trial < 50; ++trial) {
    Crc32 crc;
    std::size_t pos = 0;
    while (pos < data.size()) {
      const std::size_t n = std::min<std::size_t>(rng() % 40, data.size() - pos);
      crc.Update(std::span(data).subspan(pos, n));
      pos += n;
    }
    EXPECT_EQ(crc.Value(), whole);
  }
  Crc32 crc;
  crc.Update(data);
  crc.Reset();
  EXPECT_EQ(crc.Value(), 0u);
}

}  // namespace
}  // namespace rover::mcap
