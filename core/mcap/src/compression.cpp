#include "rover/mcap/compression.hpp"

#include <lz4frame.h>
#include <zstd.h>
#include <zstd_errors.h>

#include <string>

#include "rover/base/check.hpp"

namespace rover::mcap {

std::string_view CompressionName(Compression compression) {
  switch (compression) {
    case Compression::kNone:
      return "";
    case Compression::kZstd:
      return "zstd";
    case Compression::kLz4:
      return "lz4";
  }
  ROVER_UNREACHABLE();
}

LevelRange CompressionLevels(Compression compression) {
  switch (compression) {
    case Compression::kNone:
      return {0, 0};
    case Compression::kZstd:
      return {-7, ZSTD_maxCLevel()};
    case Compression::kLz4:
      return {0, 12};  // LZ4HC_CLEVEL_MAX; 1..2 are the fast mode too, 3.. high compression
  }
  ROVER_UNREACHABLE();
}

// ---- compression --------------------------------------------------------------------------------

struct Compressor::Contexts {
  ZSTD_CCtx* zstd = nullptr;
  ~Contexts() { ZSTD_freeCCtx(zstd); }
};

Compressor::Compressor(Compression compression, int level)
    : compression_(compression), level_(level), contexts_(std::make_unique<Contexts>()) {
  const LevelRange r = CompressionLevels(compression);
  ROVER_DEMAND_MSG(level >= r.lo && level <= r.hi, "compression level outside its range");
  if (compression == Compression::kZstd) {
    contexts_->zstd = ZSTD_createCCtx();
    ROVER_DEMAND(contexts_->zstd != nullptr);
    if (level_ == 0) level_ = ZSTD_CLEVEL_DEFAULT;
  }
}

Compressor::~Compressor() = default;

Status Compressor::Compress(std::span<const std::uint8_t> in, std::vector<std::uint8_t>& out) {
  switch (compression_) {
    case Compression::kNone:
      out.assign(in.begin(), in.end());
      return Status::Ok();
    case Compression::kZstd: {
      out.resize(ZSTD_compressBound(in.size()));
      const std::size_t n =
          ZSTD_compressCCtx(contexts_->zstd, out.data(), out.size(), in.data(), in.size(), level_);
      if (ZSTD_isError(n)) return Internal(std::string("zstd: ") + ZSTD_getErrorName(n));
      out.resize(n);
      return Status::Ok();
    }
    case Compression::kLz4: {
      LZ4F_preferences_t prefs{};
      prefs.frameInfo.contentSize = in.size();
      prefs.compressionLevel = level_;
      out.resize(LZ4F_compressFrameBound(in.size(), &prefs));
      const std::size_t n =
          LZ4F_compressFrame(out.data(), out.size(), in.data(), in.size(), &prefs);
      if (LZ4F_isError(n)) return Internal(std::string("lz4: ") + LZ4F_getErrorName(n));
      out.resize(n);
      return Status::Ok();
    }
  }
  ROVER_UNREACHABLE();
}

// ---- decompression ------------------------------------------------------------------------------

struct Decompressor::Contexts {
  ZSTD_DCtx* zstd = nullptr;
  LZ4F_dctx* lz4 = nullptr;
  ~Contexts() {
    ZSTD_freeDCtx(zstd);
    if (lz4 != nullptr) LZ4F_freeDecompressionContext(lz4);
  }
};

Decompressor::Decompressor() : contexts_(std::make_unique<Contexts>()) {}
Decompressor::~Decompressor() = default;

namespace {

Status SizeMismatch(std::uint64_t got, std::uint64_t want) {
  return InvalidArgument("decompressed to " + std::to_string(got) + " bytes, the chunk says " +
                         std::to_string(want));
}

}  // namespace

Status Decompressor::Decompress(std::string_view compression, std::span<const std::uint8_t> in,
                                std::uint64_t uncompressed_size, std::vector<std::uint8_t>& out) {
  if (compression.empty()) {
    if (in.size() != uncompressed_size) return SizeMismatch(in.size(), uncompressed_size);
    out.assign(in.begin(), in.end());
    return Status::Ok();
  }
  const bool zstd = compression == "zstd";
  const bool lz4 = compression == "lz4";
  if (!zstd && !lz4) {
    return InvalidArgument("unsupported compression '" + std::string(compression) +
                           "' (this reader knows '', 'zstd', 'lz4')");
  }
  out.resize(uncompressed_size);
  if (in.empty() && uncompressed_size == 0) return Status::Ok();
  // A non-null destination even for an empty output, which both libraries require.
  std::uint8_t dummy = 0;
  std::uint8_t* dst = out.empty() ? &dummy : out.data();

  if (zstd) {
    if (contexts_->zstd == nullptr) contexts_->zstd = ZSTD_createDCtx();
    ROVER_DEMAND(contexts_->zstd != nullptr);
    const std::size_t n =
        ZSTD_decompressDCtx(contexts_->zstd, dst, out.size(), in.data(), in.size());
    if (ZSTD_isError(n)) {
      if (ZSTD_getErrorCode(n) == ZSTD_error_dstSize_tooSmall) {
        return InvalidArgument("zstd data decompresses to more than the chunk's " +
                               std::to_string(uncompressed_size) + " bytes");
      }
      return InvalidArgument(std::string("zstd: ") + ZSTD_getErrorName(n));
    }
    if (n != uncompressed_size) return SizeMismatch(n, uncompressed_size);
    return Status::Ok();
  }

  if (contexts_->lz4 == nullptr) {
    const std::size_t r = LZ4F_createDecompressionContext(&contexts_->lz4, LZ4F_VERSION);
    ROVER_DEMAND(!LZ4F_isError(r));
  } else {
    LZ4F_resetDecompressionContext(contexts_->lz4);
  }
  std::size_t src_pos = 0;
  std::size_t dst_pos = 0;
  while (true) {
    std::size_t src_n = in.size() - src_pos;
    std::size_t dst_n = out.size() - dst_pos;
    const std::size_t r = LZ4F_decompress(contexts_->lz4, dst + dst_pos, &dst_n,
                                          in.data() + src_pos, &src_n, nullptr);
    if (LZ4F_isError(r)) {
      LZ4F_resetDecompressionContext(contexts_->lz4);
      return InvalidArgument(std::string("lz4: ") + LZ4F_getErrorName(r));
    }
    src_pos += src_n;
    dst_pos += dst_n;
    if (r == 0 && src_pos == in.size()) break;  // the last frame ended with the input
    if (src_n == 0 && dst_n == 0) {
      LZ4F_resetDecompressionContext(contexts_->lz4);
      if (src_pos == in.size()) return InvalidArgument("lz4 data ends before its frame does");
      return InvalidArgument("lz4 data decompresses to more than the chunk's " +
                             std::to_string(uncompressed_size) + " bytes");
    }
  }
  if (dst_pos != uncompressed_size) return SizeMismatch(dst_pos, uncompressed_size);
  return Status::Ok();
}

}  // namespace rover::mcap
