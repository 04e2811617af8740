#pragma once
/// @file
/// Chunk compression: zstd (a zstd frame, libzstd) and lz4 (an LZ4 *frame*, lz4frame.h, as the
/// MCAP registry's "lz4" means), or none. A compressor keeps its library context between chunks.

#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "rover/base/status.hpp"

namespace rover::mcap {

enum class Compression { kNone, kZstd, kLz4 };

/// The value of the Chunk record's `compression` field: "", "zstd" or "lz4".
std::string_view CompressionName(Compression compression);

/// Levels a compressor accepts; 0 always means the library's default (zstd 3, lz4 fast).
struct LevelRange {
  int lo = 0;
  int hi = 0;
};
LevelRange CompressionLevels(Compression compression);

/// Compresses whole chunks. Not thread-safe; one per writer.
class Compressor {
 public:
  /// Preconditions: `level` is inside CompressionLevels(compression) (options are validated).
  Compressor(Compression compression, int level);
  ~Compressor();
  Compressor(const Compressor&) = delete;
  Compressor& operator=(const Compressor&) = delete;

  Compression compression() const { return compression_; }
  /// Replaces `out` with the compressed form of `in` (a copy for kNone). Fails (kInternal) only
  /// if the library does.
  Status Compress(std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out);

 private:
  struct Contexts;
  Compression compression_;
  int level_;
  std::unique_ptr<Contexts> contexts_;
};

/// Decompresses chunk records. Not thread-safe; one per reader.
class Decompressor {
 public:
  Decompressor();
  ~Decompressor();
  Decompressor(const Decompressor&) = delete;
  Decompressor& operator=(const Decompressor&) = delete;

  /// Replaces `out` with the decompression of `in`, which must give exactly `uncompressed_size`
  /// bytes. `compression` is the Chunk field ("", "zstd", "lz4"). Errors (kInvalidArgument) say
  /// what is wrong: "unsupported compression 'bz2' (this reader knows '', 'zstd', 'lz4')",
  /// "zstd: Unknown frame descriptor", "lz4 data ends before its frame does",
  /// "decompressed to 100 bytes, the chunk says 120".
  Status Decompress(std::string_view compression, std::span<const std::uint8_t> in,
                    std::uint64_t uncompressed_size, std::vector<std::uint8_t>& out);

 private:
  struct Contexts;
  std::unique_ptr<Contexts> contexts_;
};

}  // namespace rover::mcap
