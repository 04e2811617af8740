#pragma once
/// @file
/// The records of the MCAP format, version 0 (the magic's version byte '0'), their byte layout
/// and parsing. https://mcap.dev/spec is the reference; this header names each field as it does.
///
/// Layout rules: every record is <opcode:uint8><content length:uint64><content>; integers are
/// little-endian; a String is <uint32 byte length><UTF-8 bytes>; a Map or Array is <uint32 byte
/// length of the entries><entries>; a Timestamp is a uint64 of nanoseconds since an epoch the
/// writer chooses (this stack: the run clock, rover/base/time.hpp).
///
/// Records whose payload may be large are *views* (MessageView, ChunkView): their bytes belong
/// to the caller (writing) or to the buffer they were parsed from (reading). All others own
/// their fields.
///
/// Parsing takes the record *content* (after opcode and length) and ignores bytes after the
/// last known field, as the specification asks of readers (records may grow new fields). Errors
/// (kInvalidArgument) name the field, e.g. "field 'topic': a string of 4000 bytes runs past the
/// end of the record (12 bytes left)"; callers prefix the record and its offset.

#include <array>
#include <cstdint>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rover/base/status.hpp"

namespace rover::mcap {

/// Nanoseconds since the writer's epoch.
using Timestamp = std::uint64_t;
using Bytes = std::vector<std::uint8_t>;
using ByteSpan = std::span<const std::uint8_t>;
/// Map<string, string>; std::map keeps the serialized order deterministic (sorted by key).
using StringMap = std::map<std::string, std::string>;

/// The bytes of a string, for schema data given as text.
inline ByteSpan AsBytes(std::string_view s) {
  return {reinterpret_cast<const std::uint8_t*>(s.data()), s.size()};
}

/// 0x89 'M' 'C' 'A' 'P' '0' '\r' '\n': begins and ends every file.
inline constexpr std::array<std::uint8_t, 8> kMagic = {0x89, 'M', 'C', 'A', 'P', '0', '\r', '\n'};
/// Opcode and content length before every record's content.
inline constexpr std::uint64_t kRecordPrefixBytes = 9;
/// A whole Footer record (prefix + summary_start + summary_offset_start + summary_crc).
inline constexpr std::uint64_t kFooterRecordBytes = kRecordPrefixBytes + 20;
/// A whole DataEnd record (prefix + data_section_crc).
inline constexpr std::uint64_t kDataEndRecordBytes = kRecordPrefixBytes + 4;
/// The fixed part of a Message record's content before its data.
inline constexpr std::uint64_t kMessageHeaderBytes = 2 + 4 + 8 + 8;

enum class Opcode : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

/// "Header", "Message", ..., "DataEnd"; "private record 0x80".."0xff"; "unknown record 0x42"
/// (reserved for future versions); "invalid record 0x00".
std::string OpcodeName(std::uint8_t opcode);
inline std::string OpcodeName(Opcode op) { return OpcodeName(static_cast<std::uint8_t>(op)); }

struct Header {
  std::string profile;  ///< "" here: no well-known profile fits CDR over DDS with OMG IDL schemas
  std::string library;
  bool operator==(const Header&) const = default;
};

struct Footer {
  std::uint64_t summary_start = 0;         ///< 0: no summary section
  std::uint64_t summary_offset_start = 0;  ///< 0: no Summary Offset records
  std::uint32_t summary_crc = 0;           ///< 0: not available
  bool operator==(const Footer&) const = default;
};

struct Schema {
  std::uint16_t id = 0;  ///< 1..65535; 0 is invalid
  std::string name;      ///< omgidl: the scoped type name, "rover::dl::PoseEstimate"
  std::string encoding;  ///< "omgidl" here; "" = no schema
  Bytes data;            ///< omgidl: one self-contained IDL text without directives
  bool operator==(const Schema&) const = default;
};

struct Channel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;  ///< 0: no schema
  std::string topic;
  std::string message_encoding;  ///< "cdr" here (XCDR with its 4-byte encapsulation header)
  StringMap metadata;
  bool operator==(const Channel&) const = default;
};

struct MessageView {
  std::uint16_t channel_id = 0;
  std::uint32_t sequence = 0;
  Timestamp log_time = 0;
  Timestamp publish_time = 0;  ///< set to log_time when unknown
  ByteSpan data;
};

struct ChunkView {
  Timestamp message_start_time = 0;  ///< earliest log_time inside, 0 if no messages
  Timestamp message_end_time = 0;    ///< latest log_time inside, 0 if no messages
  std::uint64_t uncompressed_size = 0;
  std::uint32_t uncompressed_crc = 0;  ///< CRC-32 of the uncompressed records; 0 = not available
  std::string compression;             ///< "", "zstd", "lz4"
  ByteSpan records;                    ///< compressed records
};

struct MessageIndex {
  std::uint16_t channel_id = 0;
  /// (log_time, offset of the Message record in the uncompressed chunk records).
  std::vector<std::pair<Timestamp, std::uint64_t>> records;
  bool operator==(const MessageIndex&) const = default;
};

struct ChunkIndex {
  Timestamp message_start_time = 0;
  Timestamp message_end_time = 0;
  std::uint64_t chunk_start_offset = 0;  ///< file offset of the Chunk record
  std::uint64_t chunk_length = 0;        ///< whole record, prefix included
  /// channel id -> file offset of its Message Index record after the chunk (empty: no index).
  std::map<std::uint16_t, std::uint64_t> message_index_offsets;
  std::uint64_t message_index_length = 0;  ///< all Message Index records after the chunk
  std::string compression;
  std::uint64_t compressed_size = 0;  ///< size of the Chunk's records field
  std::uint64_t uncompressed_size = 0;
  bool operator==(const ChunkIndex&) const = default;
};

struct Attachment {
  Timestamp log_time = 0;
  Timestamp create_time = 0;  ///< 0 when unknown
  std::string name;
  std::string media_type;  ///< e.g. "text/plain", "application/x-yaml"
  Bytes data;
  bool operator==(const Attachment&) const = default;
};

struct AttachmentIndex {
  std::uint64_t offset = 0;  ///< file offset of the Attachment record
  std::uint64_t length = 0;  ///< whole record, prefix included
  Timestamp log_time = 0;
  Timestamp create_time = 0;
  std::uint64_t data_size = 0;
  std::string name;
  std::string media_type;
  bool operator==(const AttachmentIndex&) const = default;
};

struct Statistics {
  std::uint64_t message_count = 0;
  std::uint16_t schema_count = 0;
  std::uint32_t channel_count = 0;
  std::uint32_t attachment_count = 0;
  std::uint32_t metadata_count = 0;
  std::uint32_t chunk_count = 0;
  Timestamp message_start_time = 0;  ///< 0 if no messages
  Timestamp message_end_time = 0;
  std::map<std::uint16_t, std::uint64_t> channel_message_counts;  ///< empty: not available
  bool operator==(const Statistics&) const = default;
};

/// Adds one message of `channel` at `log_time` to the message count, the channel's count and
/// the time span.
void CountMessage(Statistics& s, std::uint16_t channel, Timestamp log_time);

struct Metadata {
  std::string name;
  StringMap metadata;
  bool operator==(const Metadata&) const = default;
};

struct MetadataIndex {
  std::uint64_t offset = 0;  ///< file offset of the Metadata record
  std::uint64_t length = 0;  ///< whole record, prefix included
  std::string name;
  bool operator==(const MetadataIndex&) const = default;
};

struct SummaryOffset {
  std::uint8_t group_opcode = 0;
  std::uint64_t group_start = 0;   ///< file offset of the group's first record
  std::uint64_t group_length = 0;  ///< bytes of the whole group
  bool operator==(const SummaryOffset&) const = default;
};

struct DataEnd {
  std::uint32_t data_section_crc = 0;  ///< CRC-32 of the file from byte 0 up to this record
  bool operator==(const DataEnd&) const = default;
};

// ---- writing: each appends one whole record (opcode, length, content) to `out` ------------------

void AppendRecord(Bytes& out, const Header& r);
void AppendRecord(Bytes& out, const Footer& r);
void AppendRecord(Bytes& out, const Schema& r);
void AppendRecord(Bytes& out, const Channel& r);
void AppendRecord(Bytes& out, const MessageView& r);
void AppendRecord(Bytes& out, const ChunkView& r);
void AppendRecord(Bytes& out, const MessageIndex& r);
void AppendRecord(Bytes& out, const ChunkIndex& r);
/// Computes and writes the record's crc (over every field before it).
void AppendRecord(Bytes& out, const Attachment& r);
void AppendRecord(Bytes& out, const AttachmentIndex& r);
void AppendRecord(Bytes& out, const Statistics& r);
void AppendRecord(Bytes& out, const Metadata& r);
void AppendRecord(Bytes& out, const MetadataIndex& r);
void AppendRecord(Bytes& out, const SummaryOffset& r);
void AppendRecord(Bytes& out, const DataEnd& r);

/// Sizes of whole records without building them (the writer's size-cap arithmetic).
std::uint64_t RecordSize(const Schema& r);
std::uint64_t RecordSize(const Channel& r);
std::uint64_t RecordSize(const Metadata& r);
std::uint64_t RecordSize(const MetadataIndex& r);
std::uint64_t RecordSize(const AttachmentIndex& r);
/// A Message record with `data_bytes` of data.
std::uint64_t MessageRecordSize(std::uint64_t data_bytes);
/// A Chunk record with `records_bytes` of (compressed) records and the given compression name.
std::uint64_t ChunkRecordSize(std::uint64_t records_bytes, std::string_view compression);
/// A Message Index record of `entries` entries.
std::uint64_t MessageIndexRecordSize(std::uint64_t entries);
/// A Chunk Index record naming `channels` message indexes.
std::uint64_t ChunkIndexRecordSize(std::uint64_t channels, std::string_view compression);
/// A Statistics record counting `channels` channels.
std::uint64_t StatisticsRecordSize(std::uint64_t channels);
inline constexpr std::uint64_t kSummaryOffsetRecordBytes = kRecordPrefixBytes + 1 + 8 + 8;

// ---- reading ------------------------------------------------------------------------------------

/// The opcode and content of one record.
struct RecordView {
  std::uint8_t opcode = 0;
  ByteSpan content;
  /// Prefix + content.
  std::uint64_t size() const { return kRecordPrefixBytes + content.size(); }
};

/// The record that starts at `bytes[pos]`. Errors: "the record prefix needs 9 bytes, 4 are
/// left" and "a Chunk record of 5000 bytes runs past the end (300 bytes left)".
Result<RecordView> SplitRecord(ByteSpan bytes, std::uint64_t pos);

Result<Header> ParseHeader(ByteSpan content);
Result<Footer> ParseFooter(ByteSpan content);
Result<Schema> ParseSchema(ByteSpan content);
Result<Channel> ParseChannel(ByteSpan content);
/// The view's data points into `content`.
Result<MessageView> ParseMessage(ByteSpan content);
/// The view's records point into `content`.
Result<ChunkView> ParseChunk(ByteSpan content);
Result<MessageIndex> ParseMessageIndex(ByteSpan content);
Result<ChunkIndex> ParseChunkIndex(ByteSpan content);
/// Also checks the record's crc when it is not 0: "crc 0x... does not match the content's 0x...".
Result<Attachment> ParseAttachment(ByteSpan content);
Result<AttachmentIndex> ParseAttachmentIndex(ByteSpan content);
Result<Statistics> ParseStatistics(ByteSpan content);
Result<Metadata> ParseMetadata(ByteSpan content);
Result<MetadataIndex> ParseMetadataIndex(ByteSpan content);
Result<SummaryOffset> ParseSummaryOffset(ByteSpan content);
Result<DataEnd> ParseDataEnd(ByteSpan content);

/// "0x1a2b3c4d".
std::string Hex32(std::uint32_t v);

}  // namespace rover::mcap
