#pragma once
/// @file
/// CRC-32 as MCAP uses it (the ISO-HDLC / zlib CRC: reflected polynomial 0xEDB88320, initial
/// value and final XOR 0xFFFFFFFF), so CRC32("123456789") = 0xCBF43926. Table-driven, eight
/// bytes per step (slicing-by-8).

#include <cstdint>
#include <span>

namespace rover::mcap {

/// A CRC-32 over bytes fed in any number of pieces: Update(a); Update(b) equals Update(a + b).
class Crc32 {
 public:
  /// Adds `bytes` to the checksum.
  void Update(std::span<const std::uint8_t> bytes);
  /// The CRC of all bytes added so far (0 for none).
  std::uint32_t Value() const { return ~state_; }
  void Reset() { state_ = 0xFFFFFFFFu; }

 private:
  std::uint32_t state_ = 0xFFFFFFFFu;
};

/// The CRC-32 of `bytes` in one call.
std::uint32_t ComputeCrc32(std::span<const std::uint8_t> bytes);

}  // namespace rover::mcap
