#pragma once
/// @file
/// The MCAP reader: opens a file through its summary (the fast path) or, when the file has
/// none, by scanning every record; checks every CRC it meets; iterates messages in log-time
/// order across chunks, overlapping ones included. See README.md.
///
///   ROVER_ASSIGN_OR_RETURN(auto r, mcap::Reader::Open("run.mcap"));
///   for (const auto& [id, channel] : r->channels()) ...
///   ROVER_ASSIGN_OR_RETURN(auto cursor, r->Messages());
///   while (true) {
///     ROVER_ASSIGN_OR_RETURN(auto event, cursor.Next());
///     if (!event) break;
///     Use(event->channel->topic, event->message.log_time, event->message.data);
///   }
///
/// Every error names the file, the byte offset and the record, e.g.
///   "run.mcap: Chunk record at offset 4107: uncompressed_crc 0x8a1c... does not match the
///    records' 0x1f00... (the chunk is corrupt)"
///   "run.mcap: no Footer record and trailing magic at offset 91223 (the file is truncated or
///    was not closed)"
/// and a file that fails is never half-returned: Open fails, or a cursor's Next fails and keeps
/// failing. A Reader and its cursors are not thread-safe (they share one decompressor).

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/mcap/compression.hpp"
#include "rover/mcap/io.hpp"
#include "rover/mcap/records.hpp"

namespace rover::mcap {

/// How much Open checks before it returns.
enum class Verification {
  /// Header, Footer and the summary (its CRC and structure): reads a few kilobytes. For `info`.
  kSummary,
  /// Also every record of the data section in sequence: framing, the data-section CRC of the
  /// DataEnd record, attachment CRCs, and that chunks and indexes agree. Reads the whole file
  /// once without decompressing. When the file has no data-section CRC (0), every chunk is
  /// decompressed and its CRC checked instead, so that a corrupt file fails here either way.
  kDataSection,
  /// Also decompresses every chunk, checks its CRC, its records and its Message Index records,
  /// and the Statistics against the messages counted.
  kFull,
};

struct ReaderOptions {
  Verification verification = Verification::kDataSection;
  /// Largest record or uncompressed chunk accepted (guards memory against a corrupt length).
  std::uint64_t max_record_bytes = std::uint64_t{1} << 30;
};

/// Which messages a cursor yields.
struct MessageFilter {
  /// Topics to include exactly; empty = every topic.
  std::vector<std::string> topics;
  /// Further channels to drop (e.g. a glob); null = keep all that `topics` kept.
  std::function<bool(const Channel&)> channel;
  Timestamp start_time = 0;            ///< inclusive
  Timestamp end_time = ~Timestamp{0};  ///< inclusive
};

/// One message with its channel and schema (null when the channel has none). `message.data`
/// and the pointers stay valid until the cursor's next Next() call and while the reader lives.
struct MessageEvent {
  const Channel* channel = nullptr;
  const Schema* schema = nullptr;
  MessageView message;
};

class Reader;

/// Messages in log-time order; among equal log times, in file order.
class MessageCursor {
 public:
  MessageCursor(MessageCursor&&) noexcept;
  MessageCursor& operator=(MessageCursor&&) noexcept;
  ~MessageCursor();

  /// The next message, or nullopt after the last. An error is final: it is returned again.
  Result<std::optional<MessageEvent>> Next();

 private:
  friend class Reader;
  struct State;
  explicit MessageCursor(std::unique_ptr<State> state);
  std::unique_ptr<State> state_;
};

class Reader {
 public:
  static Result<std::unique_ptr<Reader>> Open(const std::string& path,
                                              const ReaderOptions& options = {});
  static Result<std::unique_ptr<Reader>> Open(std::unique_ptr<Source> source,
                                              const ReaderOptions& options = {});
  ~Reader();
  Reader(const Reader&) = delete;
  Reader& operator=(const Reader&) = delete;

  const std::string& name() const;
  std::uint64_t file_size() const;
  const Header& header() const { return header_; }
  const Footer& footer() const { return footer_; }
  /// True when the file has a summary section (its indexes were read, not rebuilt by a scan).
  bool has_summary() const { return footer_.summary_start != 0; }

  const std::map<std::uint16_t, Schema>& schemas() const { return schemas_; }
  const std::map<std::uint16_t, Channel>& channels() const { return channels_; }
  /// From the summary; when the file has none, counted by the scan. nullopt when the summary
  /// has no Statistics record.
  const std::optional<Statistics>& statistics() const { return statistics_; }
  /// From the summary, or rebuilt by the scan (message_index_offsets from the Message Index
  /// records found after each chunk). Sorted by chunk_start_offset.
  const std::vector<ChunkIndex>& chunk_indexes() const { return chunk_indexes_; }
  const std::vector<AttachmentIndex>& attachment_indexes() const { return attachment_indexes_; }
  const std::vector<MetadataIndex>& metadata_indexes() const { return metadata_indexes_; }
  /// The file offset of the DataEnd record.
  std::uint64_t data_end_offset() const { return data_end_offset_; }

  Result<Metadata> ReadMetadata(const MetadataIndex& index) const;
  /// Every Metadata record, in file order.
  Result<std::vector<Metadata>> ReadAllMetadata() const;
  /// Checks the attachment's CRC.
  Result<Attachment> ReadAttachment(const AttachmentIndex& index) const;

  /// A cursor over the messages `filter` selects. The reader must outlive it.
  Result<MessageCursor> Messages(const MessageFilter& filter = {}) const;
  /// Calls `f` for each message in order; stops at the first error (its own or `f`'s).
  Status ForEachMessage(const MessageFilter& filter,
                        const std::function<Status(const MessageEvent&)>& f) const;

  /// The kFull checks on an open reader (if Open did less), data-section CRC included.
  Status VerifyFull() const { return Verify(true); }

 private:
  friend class MessageCursor;
  friend struct MessageCursor::State;
  struct LooseMessage;
  struct Loaded;
  /// What a walk over a chunk's records does with each kind; a null definition callback checks
  /// the definition against the known ones instead.
  struct ChunkVisitor {
    std::function<Status(Schema, std::uint64_t)> schema;
    std::function<Status(Channel, std::uint64_t)> channel;
    std::function<Status(const MessageView&, std::uint64_t)> message;
  };

  Reader(std::unique_ptr<Source> source, const ReaderOptions& options);
  Status Init();
  Status ReadHeaderAndFooter();
  Status ReadSummary();
  /// Walks the data section record by record. `scan_mode` (no summary): builds every index and
  /// the statistics, decompressing chunks to find their definitions. Otherwise checks the data
  /// section against the summary without decompressing.
  Status Scan(bool scan_mode);
  /// The kFull checks; `data_crc`: also the data-section CRC.
  Status Verify(bool data_crc) const;

  /// Reads the whole record at `offset` and checks its opcode and length.
  Status ReadRecordAt(std::uint64_t offset, std::uint64_t length, Opcode expected, Bytes& buffer,
                      ByteSpan& content) const;
  /// Decompresses a Chunk record's records (checking sizes and the CRC) into `out`.
  Status DecompressChunk(const ChunkView& chunk, std::uint64_t offset, Bytes& out) const;
  /// Walks a chunk's decompressed records: definitions, then messages (channel known, log
  /// time inside the chunk's range); other records are skipped or refused.
  Status WalkChunk(ByteSpan records, const ChunkView& chunk, std::uint64_t offset,
                   const ChunkVisitor& visitor) const;
  Status LearnSchema(Schema s, Opcode where, std::uint64_t offset);
  Status LearnChannel(Channel c, Opcode where, std::uint64_t offset);
  Status CheckSchema(const Schema& s, Opcode where, std::uint64_t offset) const;
  Status CheckChannel(const Channel& c, Opcode where, std::uint64_t offset) const;
  /// Loads a chunk for a cursor: the messages `keep` selects, sorted by (log time, offset).
  Status LoadChunk(const ChunkIndex& chunk, const std::function<bool(const MessageView&)>& keep,
                   Loaded& out) const;
  /// "<file>: <Opcode> record at offset N: <message>".
  Status Error(Opcode op, std::uint64_t offset, const std::string& message) const;
  /// "<file>: offset N: <message>".
  Status Error(std::uint64_t offset, const std::string& message) const;

  std::unique_ptr<Source> source_;
  ReaderOptions options_;
  mutable Decompressor decompressor_;

  Header header_;
  Footer footer_;
  std::uint64_t header_end_ = 0;     ///< first byte after the Header record
  std::uint64_t footer_offset_ = 0;  ///< the Footer record
  std::uint64_t data_end_offset_ = 0;
  std::uint32_t data_section_crc_ = 0;

  std::map<std::uint16_t, Schema> schemas_;
  std::map<std::uint16_t, Channel> channels_;
  std::optional<Statistics> statistics_;
  std::vector<ChunkIndex> chunk_indexes_;  ///< sorted by chunk_start_offset
  std::vector<AttachmentIndex> attachment_indexes_;
  std::vector<MetadataIndex> metadata_indexes_;
  std::vector<LooseMessage> loose_;  ///< messages outside chunks, sorted by (log time, offset)
};

}  // namespace rover::mcap
