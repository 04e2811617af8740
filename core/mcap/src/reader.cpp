#include "rover/mcap/reader.hpp"

#include <algorithm>
#include <cstring>
#include <set>
#include <tuple>
#include <utility>

#include "rover/base/check.hpp"
#include "rover/mcap/crc32.hpp"

namespace rover::mcap {

struct Reader::LooseMessage {
  Timestamp log_time = 0;
  std::uint64_t offset = 0;  ///< of the Message record
  std::uint64_t length = 0;  ///< whole record
  std::uint16_t channel_id = 0;
};

struct Reader::Loaded {
  Bytes storage;
  ByteSpan records;  ///< the decompressed records (in storage)
  std::vector<std::pair<Timestamp, std::uint64_t>> entries;  ///< (log time, offset in records)
};

namespace {

constexpr std::uint64_t kWindowBytes = 4u << 20;

std::string Num(std::uint64_t v) { return std::to_string(v); }

/// Sequential views of a source's bytes through a read-ahead window.
class Window {
 public:
  Window(const Source& source, std::uint64_t end) : source_(source), end_(end) {}

  /// A view of [offset, offset + n), valid until the next call. Preconditions: inside end.
  Status View(std::uint64_t offset, std::uint64_t n, ByteSpan& out) {
    ROVER_DEMAND(offset <= end_ && n <= end_ - offset);
    if (offset >= start_ && offset - start_ + n <= buffer_.size()) {
      out = ByteSpan(buffer_).subspan(offset - start_, n);
      return Status::Ok();
    }
    if (n > kWindowBytes) {
      big_.resize(n);
      ROVER_RETURN_IF_ERROR(source_.Read(offset, big_));
      out = big_;
      return Status::Ok();
    }
    buffer_.resize(std::min(kWindowBytes, end_ - offset));
    ROVER_RETURN_IF_ERROR(source_.Read(offset, buffer_));
    start_ = offset;
    out = ByteSpan(buffer_).first(n);
    return Status::Ok();
  }

 private:
  const Source& source_;
  std::uint64_t end_;
  std::uint64_t start_ = 0;
  Bytes buffer_;
  Bytes big_;
};

std::uint64_t LoadLe(ByteSpan b, std::size_t at, int n) {
  std::uint64_t v = 0;
  for (int i = 0; i < n; ++i) v |= std::uint64_t{b[at + i]} << (8 * i);
  return v;
}

bool IsSummaryRecord(std::uint8_t op) {
  return op == static_cast<std::uint8_t>(Opcode::kChunkIndex) ||
         op == static_cast<std::uint8_t>(Opcode::kAttachmentIndex) ||
         op == static_cast<std::uint8_t>(Opcode::kMetadataIndex) ||
         op == static_cast<std::uint8_t>(Opcode::kStatistics) ||
         op == static_cast<std::uint8_t>(Opcode::kSummaryOffset);
}

bool IsKnown(std::uint8_t op) { return op >= 0x01 && op <= 0x0F; }

}  // namespace

// ---- construction -------------------------------------------------------------------------------

Reader::Reader(std::unique_ptr<Source> source, const ReaderOptions& options)
    : source_(std::move(source)), options_(options) {}

Reader::~Reader() = default;

const std::string& Reader::name() const { return source_->name(); }
std::uint64_t Reader::file_size() const { return source_->size(); }

Result<std::unique_ptr<Reader>> Reader::Open(const std::string& path,
                                             const ReaderOptions& options) {
  ROVER_ASSIGN_OR_RETURN(std::unique_ptr<FileSource> source, FileSource::Open(path));
  return Open(std::move(source), options);
}

Result<std::unique_ptr<Reader>> Reader::Open(std::unique_ptr<Source> source,
                                             const ReaderOptions& options) {
  ROVER_DEMAND(source != nullptr);
  std::unique_ptr<Reader> r(new Reader(std::move(source), options));
  ROVER_RETURN_IF_ERROR(r->Init());
  return r;
}

Status Reader::Error(Opcode op, std::uint64_t offset, const std::string& message) const {
  return InvalidArgument(name() + ": " + OpcodeName(op) + " record at offset " + Num(offset) +
                         ": " + message);
}

Status Reader::Error(std::uint64_t offset, const std::string& message) const {
  return InvalidArgument(name() + ": offset " + Num(offset) + ": " + message);
}

Status Reader::Init() {
  ROVER_RETURN_IF_ERROR(ReadHeaderAndFooter());
  if (has_summary()) ROVER_RETURN_IF_ERROR(ReadSummary());

  if (!has_summary()) {
    ROVER_RETURN_IF_ERROR(Scan(/*scan_mode=*/true));  // decompresses and checks every chunk
  } else if (options_.verification != Verification::kSummary) {
    ROVER_RETURN_IF_ERROR(Scan(false));
  } else if (chunk_indexes_.empty() && (!statistics_ || statistics_->message_count > 0)) {
    // Messages outside chunks are found only by walking the data section.
    ROVER_RETURN_IF_ERROR(Scan(false));
  }
  const bool full = options_.verification == Verification::kFull;
  const bool no_data_crc = options_.verification == Verification::kDataSection && has_summary() &&
                           data_section_crc_ == 0;
  if (full || no_data_crc) ROVER_RETURN_IF_ERROR(Verify(/*data_crc=*/false));  // Scan did it
  return Status::Ok();
}

// ---- header and footer --------------------------------------------------------------------------

Status Reader::ReadHeaderAndFooter() {
  const std::uint64_t size = source_->size();
  if (size < kMagic.size()) {
    return Error(0, "not an MCAP file: " + Num(size) + " bytes are too few for the magic");
  }
  std::array<std::uint8_t, 8> magic{};
  ROVER_RETURN_IF_ERROR(source_->Read(0, magic));
  if (!std::equal(magic.begin(), magic.begin() + 5, kMagic.begin())) {
    return Error(0, "not an MCAP file (the first bytes are not the MCAP magic)");
  }
  if (magic != kMagic) {
    return Error(0, "MCAP major version '" + std::string(1, static_cast<char>(magic[5])) +
                        "' is not supported (this reader knows version '0')");
  }
  constexpr std::uint64_t kHeaderAt = kMagic.size();
  if (size < kHeaderAt + kRecordPrefixBytes) {
    return Error(kHeaderAt, "the file ends before the Header record (the file is truncated)");
  }
  std::array<std::uint8_t, kRecordPrefixBytes> prefix{};
  ROVER_RETURN_IF_ERROR(source_->Read(kHeaderAt, prefix));
  if (prefix[0] != static_cast<std::uint8_t>(Opcode::kHeader)) {
    return Error(kHeaderAt, "expected the Header record, found " + OpcodeName(prefix[0]));
  }
  const std::uint64_t length = LoadLe(prefix, 1, 8);
  if (length > size - kHeaderAt - kRecordPrefixBytes || length > options_.max_record_bytes) {
    return Error(Opcode::kHeader, kHeaderAt,
                 "length " + Num(length) + " runs past the end of the file (" + Num(size) +
                     " bytes; the file is truncated or corrupt)");
  }
  Bytes content(length);
  ROVER_RETURN_IF_ERROR(source_->Read(kHeaderAt + kRecordPrefixBytes, content));
  Result<Header> header = ParseHeader(content);
  if (!header.ok()) return Error(Opcode::kHeader, kHeaderAt, header.status().message());
  header_ = std::move(header).value();
  header_end_ = kHeaderAt + kRecordPrefixBytes + length;

  const std::uint64_t tail = kFooterRecordBytes + kMagic.size();
  if (size < header_end_ + tail) {
    return Error(header_end_,
                 "no Footer record and trailing magic after the Header (the file "
                 "of " +
                     Num(size) + " bytes is truncated or was not closed)");
  }
  footer_offset_ = size - tail;
  Bytes footer(tail);
  ROVER_RETURN_IF_ERROR(source_->Read(footer_offset_, footer));
  const bool magic_ok = std::equal(kMagic.begin(), kMagic.end(), footer.end() - kMagic.size());
  const bool footer_ok = footer[0] == static_cast<std::uint8_t>(Opcode::kFooter) &&
                         LoadLe(footer, 1, 8) == kFooterRecordBytes - kRecordPrefixBytes;
  if (!magic_ok || !footer_ok) {
    return Error(footer_offset_,
                 "no Footer record and trailing magic at the end (the file is "
                 "truncated or was not closed)");
  }
  Result<Footer> parsed =
      ParseFooter(ByteSpan(footer).subspan(kRecordPrefixBytes, kFooterRecordBytes - 9));
  ROVER_DEMAND(parsed.ok());  // fixed size, checked above
  footer_ = parsed.value();
  if (footer_.summary_start == 0 && footer_.summary_offset_start != 0) {
    return Error(Opcode::kFooter, footer_offset_,
                 "summary_offset_start " + Num(footer_.summary_offset_start) +
                     " without a summary (summary_start is 0)");
  }
  if (footer_.summary_start != 0 && (footer_.summary_start < header_end_ + kDataEndRecordBytes ||
                                     footer_.summary_start > footer_offset_)) {
    return Error(Opcode::kFooter, footer_offset_,
                 "summary_start " + Num(footer_.summary_start) + " is outside [" +
                     Num(header_end_ + kDataEndRecordBytes) + ", " + Num(footer_offset_) + "]");
  }
  return Status::Ok();
}

// ---- summary ------------------------------------------------------------------------------------

Status Reader::ReadSummary() {
  const std::uint64_t start = footer_.summary_start;
  data_end_offset_ = start - kDataEndRecordBytes;
  if (footer_offset_ - start > options_.max_record_bytes) {
    return Error(Opcode::kFooter, footer_offset_,
                 "a summary of " + Num(footer_offset_ - start) +
                     " bytes exceeds the reader's limit of " + Num(options_.max_record_bytes) +
                     " bytes");
  }
  // DataEnd, the summary, and the footer up to its crc field (which the summary CRC covers).
  Bytes bytes(footer_offset_ + (kFooterRecordBytes - 4) - data_end_offset_);
  ROVER_RETURN_IF_ERROR(source_->Read(data_end_offset_, bytes));
  const ByteSpan all(bytes);
  if (all[0] != static_cast<std::uint8_t>(Opcode::kDataEnd) ||
      LoadLe(all, 1, 8) != kDataEndRecordBytes - kRecordPrefixBytes) {
    return Error(data_end_offset_, "expected the DataEnd record right before the summary at " +
                                       Num(start) + ", found " + OpcodeName(all[0]));
  }
  data_section_crc_ = static_cast<std::uint32_t>(LoadLe(all, kRecordPrefixBytes, 4));

  const ByteSpan covered = all.subspan(kDataEndRecordBytes);
  if (footer_.summary_crc != 0) {
    const std::uint32_t actual = ComputeCrc32(covered);
    if (actual != footer_.summary_crc) {
      return Error(Opcode::kFooter, footer_offset_,
                   "summary_crc " + Hex32(footer_.summary_crc) + " does not match the summary's " +
                       Hex32(actual) + " (the summary section is corrupt)");
    }
  }

  const ByteSpan summary = covered.first(footer_offset_ - start);
  const std::uint64_t offsets_at =
      footer_.summary_offset_start != 0 ? footer_.summary_offset_start : footer_offset_;
  if (offsets_at < start || offsets_at > footer_offset_) {
    return Error(Opcode::kFooter, footer_offset_,
                 "summary_offset_start " + Num(offsets_at) + " is outside the summary [" +
                     Num(start) + ", " + Num(footer_offset_) + "]");
  }
  std::map<std::uint64_t, std::uint8_t> record_at;  // file offset -> opcode
  std::vector<std::pair<std::uint64_t, SummaryOffset>> summary_offsets;
  std::vector<std::pair<std::uint64_t, Channel>> channels;
  std::uint64_t pos = 0;
  while (pos < summary.size()) {
    const std::uint64_t at = start + pos;
    Result<RecordView> rec = SplitRecord(summary, pos);
    if (!rec.ok()) {
      return Error(at, "summary section: " + rec.status().message() + " (the summary is corrupt)");
    }
    const std::uint8_t op = rec->opcode;
    const ByteSpan c = rec->content;
    record_at[at] = op;
    if (at >= offsets_at && op != static_cast<std::uint8_t>(Opcode::kSummaryOffset)) {
      return Error(at, OpcodeName(op) + " record after summary_offset_start " + Num(offsets_at) +
                           " (only SummaryOffset records may follow it)");
    }
    auto fail = [&](const Status& s) { return Error(static_cast<Opcode>(op), at, s.message()); };
    switch (static_cast<Opcode>(op)) {
      case Opcode::kSchema: {
        Result<Schema> s = ParseSchema(c);
        if (!s.ok()) return fail(s.status());
        ROVER_RETURN_IF_ERROR(LearnSchema(std::move(s).value(), Opcode::kSchema, at));
        break;
      }
      case Opcode::kChannel: {
        Result<Channel> ch = ParseChannel(c);
        if (!ch.ok()) return fail(ch.status());
        channels.emplace_back(at, std::move(ch).value());  // schemas may follow
        break;
      }
      case Opcode::kChunkIndex: {
        Result<ChunkIndex> ci = ParseChunkIndex(c);
        if (!ci.ok()) return fail(ci.status());
        const ChunkIndex& x = ci.value();
        const std::uint64_t end = x.chunk_start_offset + x.chunk_length;
        if (x.chunk_start_offset < header_end_ || x.chunk_length < kRecordPrefixBytes ||
            end < x.chunk_start_offset || end > data_end_offset_ ||
            x.message_index_length > data_end_offset_ - end) {
          return fail(InvalidArgument("the chunk [" + Num(x.chunk_start_offset) + ", +" +
                                      Num(x.chunk_length) + ") and its message indexes (" +
                                      Num(x.message_index_length) +
                                      " bytes) are not inside the data section [" +
                                      Num(header_end_) + ", " + Num(data_end_offset_) + ")"));
        }
        for (const auto& [channel, offset] : x.message_index_offsets) {
          if (offset < end || offset >= end + x.message_index_length) {
            return fail(InvalidArgument("the message index of channel " + Num(channel) + " at " +
                                        Num(offset) + " is not after the chunk"));
          }
        }
        if (x.uncompressed_size > options_.max_record_bytes) {
          return fail(InvalidArgument("uncompressed_size " + Num(x.uncompressed_size) +
                                      " exceeds the reader's limit of " +
                                      Num(options_.max_record_bytes) + " bytes"));
        }
        chunk_indexes_.push_back(std::move(ci).value());
        break;
      }
      case Opcode::kAttachmentIndex:
      case Opcode::kMetadataIndex: {
        std::uint64_t offset = 0;
        std::uint64_t length = 0;
        if (op == static_cast<std::uint8_t>(Opcode::kAttachmentIndex)) {
          Result<AttachmentIndex> ai = ParseAttachmentIndex(c);
          if (!ai.ok()) return fail(ai.status());
          offset = ai->offset;
          length = ai->length;
          attachment_indexes_.push_back(std::move(ai).value());
        } else {
          Result<MetadataIndex> mi = ParseMetadataIndex(c);
          if (!mi.ok()) return fail(mi.status());
          offset = mi->offset;
          length = mi->length;
          metadata_indexes_.push_back(std::move(mi).value());
        }
        if (offset < header_end_ || length < kRecordPrefixBytes || offset + length < offset ||
            offset + length > data_end_offset_) {
          return fail(InvalidArgument("the record [" + Num(offset) + ", +" + Num(length) +
                                      ") is not inside the data section [" + Num(header_end_) +
                                      ", " + Num(data_end_offset_) + ")"));
        }
        break;
      }
      case Opcode::kStatistics: {
        if (statistics_) return fail(InvalidArgument("a second Statistics record"));
        Result<Statistics> st = ParseStatistics(c);
        if (!st.ok()) return fail(st.status());
        statistics_ = std::move(st).value();
        break;
      }
      case Opcode::kSummaryOffset: {
        Result<SummaryOffset> so = ParseSummaryOffset(c);
        if (!so.ok()) return fail(so.status());
        summary_offsets.emplace_back(at, so.value());
        break;
      }
      default:
        if (IsKnown(op)) {
          return Error(static_cast<Opcode>(op), at, "not allowed in the summary section");
        }
        break;  // private or future records: skipped
    }
    pos += rec->size();
  }
  if (footer_.summary_offset_start != 0 && !record_at.contains(offsets_at) &&
      offsets_at != footer_offset_) {
    return Error(Opcode::kFooter, footer_offset_,
                 "summary_offset_start " + Num(offsets_at) + " is not at a record");
  }
  for (auto& [at, channel] : channels) {
    ROVER_RETURN_IF_ERROR(LearnChannel(std::move(channel), Opcode::kChannel, at));
  }
  for (const auto& [at, so] : summary_offsets) {
    const auto first = record_at.find(so.group_start);
    if (so.group_start < start ||
        so.group_length > offsets_at - std::min(so.group_start, offsets_at) ||
        first == record_at.end() || first->second != so.group_opcode) {
      return Error(Opcode::kSummaryOffset, at,
                   "the group of " + OpcodeName(so.group_opcode) + " records at " +
                       Num(so.group_start) + " (+" + Num(so.group_length) +
                       " bytes) does not match the summary");
    }
  }
  std::sort(chunk_indexes_.begin(), chunk_indexes_.end(), [](const auto& a, const auto& b) {
    return a.chunk_start_offset < b.chunk_start_offset;
  });
  for (std::size_t i = 1; i < chunk_indexes_.size(); ++i) {
    const ChunkIndex& a = chunk_indexes_[i - 1];
    if (a.chunk_start_offset + a.chunk_length > chunk_indexes_[i].chunk_start_offset) {
      return Error(Opcode::kChunkIndex, start,
                   "the chunks at " + Num(a.chunk_start_offset) + " and " +
                       Num(chunk_indexes_[i].chunk_start_offset) + " overlap in the file");
    }
  }
  std::sort(metadata_indexes_.begin(), metadata_indexes_.end(),
            [](const auto& a, const auto& b) { return a.offset < b.offset; });
  std::sort(attachment_indexes_.begin(), attachment_indexes_.end(),
            [](const auto& a, const auto& b) { return a.offset < b.offset; });
  return Status::Ok();
}

// ---- definitions --------------------------------------------------------------------------------

Status Reader::CheckSchema(const Schema& s, Opcode where, std::uint64_t offset) const {
  if (s.id == 0) return Status::Ok();  // invalid id: ignored, as the specification says
  const auto it = schemas_.find(s.id);
  if (it != schemas_.end() && it->second != s) {
    return Error(where, offset,
                 "schema " + Num(s.id) + " ('" + s.name +
                     "') differs from its earlier definition ('" + it->second.name + "')");
  }
  return Status::Ok();
}

Status Reader::CheckChannel(const Channel& c, Opcode where, std::uint64_t offset) const {
  const auto it = channels_.find(c.id);
  if (it == channels_.end()) {
    return Error(where, offset,
                 "channel " + Num(c.id) + " ('" + c.topic + "') is missing from the summary");
  }
  if (it->second != c) {
    return Error(where, offset,
                 "channel " + Num(c.id) + " ('" + c.topic +
                     "') differs from its earlier definition ('" + it->second.topic + "')");
  }
  return Status::Ok();
}

Status Reader::LearnSchema(Schema s, Opcode where, std::uint64_t offset) {
  ROVER_RETURN_IF_ERROR(CheckSchema(s, where, offset));
  if (s.id != 0) schemas_.emplace(s.id, std::move(s));
  return Status::Ok();
}

Status Reader::LearnChannel(Channel c, Opcode where, std::uint64_t offset) {
  if (c.schema_id != 0 && !schemas_.contains(c.schema_id)) {
    return Error(where, offset,
                 "channel " + Num(c.id) + " ('" + c.topic + "') uses schema " + Num(c.schema_id) +
                     ", which is not defined before it");
  }
  if (channels_.contains(c.id)) return CheckChannel(c, where, offset);
  channels_.emplace(c.id, std::move(c));
  return Status::Ok();
}

// ---- records and chunks -------------------------------------------------------------------------

Status Reader::ReadRecordAt(std::uint64_t offset, std::uint64_t length, Opcode expected,
                            Bytes& buffer, ByteSpan& content) const {
  if (length < kRecordPrefixBytes || length - kRecordPrefixBytes > options_.max_record_bytes) {
    return Error(expected, offset, "the index gives it an impossible length " + Num(length));
  }
  buffer.resize(length);
  ROVER_RETURN_IF_ERROR(source_->Read(offset, buffer));
  if (buffer[0] != static_cast<std::uint8_t>(expected)) {
    return Error(offset, "the index points at a " + OpcodeName(expected) + " record, found " +
                             OpcodeName(buffer[0]));
  }
  if (LoadLe(buffer, 1, 8) != length - kRecordPrefixBytes) {
    return Error(expected, offset,
                 "content length " + Num(LoadLe(buffer, 1, 8)) + " does not match the index's " +
                     Num(length - kRecordPrefixBytes));
  }
  content = ByteSpan(buffer).subspan(kRecordPrefixBytes);
  return Status::Ok();
}

Status Reader::DecompressChunk(const ChunkView& chunk, std::uint64_t offset, Bytes& out) const {
  if (chunk.uncompressed_size > options_.max_record_bytes) {
    return Error(Opcode::kChunk, offset,
                 "uncompressed_size " + Num(chunk.uncompressed_size) +
                     " exceeds the reader's limit of " + Num(options_.max_record_bytes) + " bytes");
  }
  Status s =
      decompressor_.Decompress(chunk.compression, chunk.records, chunk.uncompressed_size, out);
  if (!s.ok()) return Error(Opcode::kChunk, offset, s.message() + " (the chunk is corrupt)");
  if (chunk.uncompressed_crc != 0) {
    const std::uint32_t actual = ComputeCrc32(out);
    if (actual != chunk.uncompressed_crc) {
      return Error(Opcode::kChunk, offset,
                   "uncompressed_crc " + Hex32(chunk.uncompressed_crc) +
                       " does not match the records' " + Hex32(actual) + " (the chunk is corrupt)");
    }
  }
  return Status::Ok();
}

Status Reader::WalkChunk(ByteSpan records, const ChunkView& chunk, std::uint64_t offset,
                         const ChunkVisitor& visitor) const {
  std::uint64_t pos = 0;
  while (pos < records.size()) {
    auto fail = [&](const std::string& what) {
      return Error(Opcode::kChunk, offset,
                   "its record at offset " + Num(pos) + " of the decompressed records: " + what);
    };
    Result<RecordView> rec = SplitRecord(records, pos);
    if (!rec.ok()) return fail(rec.status().message());
    const std::uint8_t op = rec->opcode;
    switch (static_cast<Opcode>(op)) {
      case Opcode::kSchema: {
        Result<Schema> s = ParseSchema(rec->content);
        if (!s.ok()) return fail("Schema: " + s.status().message());
        ROVER_RETURN_IF_ERROR(visitor.schema ? visitor.schema(std::move(s).value(), pos)
                                             : CheckSchema(s.value(), Opcode::kChunk, offset));
        break;
      }
      case Opcode::kChannel: {
        Result<Channel> c = ParseChannel(rec->content);
        if (!c.ok()) return fail("Channel: " + c.status().message());
        ROVER_RETURN_IF_ERROR(visitor.channel ? visitor.channel(std::move(c).value(), pos)
                                              : CheckChannel(c.value(), Opcode::kChunk, offset));
        break;
      }
      case Opcode::kMessage: {
        Result<MessageView> m = ParseMessage(rec->content);
        if (!m.ok()) return fail("Message: " + m.status().message());
        if (!channels_.contains(m->channel_id)) {
          return fail("Message on channel " + Num(m->channel_id) +
                      ", which is not defined before it");
        }
        if (m->log_time < chunk.message_start_time || m->log_time > chunk.message_end_time) {
          return fail("Message log_time " + Num(m->log_time) + " is outside the chunk's [" +
                      Num(chunk.message_start_time) + ", " + Num(chunk.message_end_time) + "]");
        }
        if (visitor.message) ROVER_RETURN_IF_ERROR(visitor.message(m.value(), pos));
        break;
      }
      case Opcode::kMetadata:
        break;  // not expected in a chunk, but harmless
      default:
        if (IsKnown(op)) return fail(OpcodeName(op) + " record is not allowed inside a chunk");
        break;  // private or future records: skipped
    }
    pos += rec->size();
  }
  return Status::Ok();
}

Status Reader::LoadChunk(const ChunkIndex& index,
                         const std::function<bool(const MessageView&)>& keep, Loaded& out) const {
  const std::uint64_t at = index.chunk_start_offset;
  Bytes buffer;
  ByteSpan content;
  ROVER_RETURN_IF_ERROR(ReadRecordAt(at, index.chunk_length, Opcode::kChunk, buffer, content));
  Result<ChunkView> chunk = ParseChunk(content);
  if (!chunk.ok()) return Error(Opcode::kChunk, at, chunk.status().message());
  const ChunkView& c = chunk.value();
  if (c.message_start_time != index.message_start_time ||
      c.message_end_time != index.message_end_time || c.records.size() != index.compressed_size ||
      c.uncompressed_size != index.uncompressed_size || c.compression != index.compression) {
    return Error(Opcode::kChunk, at, "its times, sizes or compression differ from its ChunkIndex");
  }
  if (c.compression.empty()) {
    // Stored uncompressed: keep the read buffer instead of copying the records.
    if (c.uncompressed_size != c.records.size()) {
      return Error(Opcode::kChunk, at,
                   "uncompressed records of " + Num(c.records.size()) +
                       " bytes, but uncompressed_size says " + Num(c.uncompressed_size));
    }
    if (c.uncompressed_crc != 0 && ComputeCrc32(c.records) != c.uncompressed_crc) {
      return Error(Opcode::kChunk, at,
                   "uncompressed_crc " + Hex32(c.uncompressed_crc) +
                       " does not match the records' " + Hex32(ComputeCrc32(c.records)) +
                       " (the chunk is corrupt)");
    }
    const std::size_t from = static_cast<std::size_t>(c.records.data() - buffer.data());
    out.storage = std::move(buffer);
    out.records = ByteSpan(out.storage).subspan(from, c.uncompressed_size);
  } else {
    ROVER_RETURN_IF_ERROR(DecompressChunk(c, at, out.storage));
    out.records = out.storage;
  }
  out.entries.clear();
  ChunkVisitor visitor;
  visitor.message = [&](const MessageView& m, std::uint64_t pos) {
    if (!keep || keep(m)) out.entries.emplace_back(m.log_time, pos);
    return Status::Ok();
  };
  ROVER_RETURN_IF_ERROR(WalkChunk(out.records, c, at, visitor));
  std::sort(out.entries.begin(), out.entries.end());
  return Status::Ok();
}

// ---- the data section ---------------------------------------------------------------------------

Status Reader::Scan(bool scan_mode) {
  const std::uint64_t end = has_summary() ? footer_.summary_start : footer_offset_;
  Window window(*source_, end);
  Crc32 crc;
  {
    Bytes head(header_end_);
    ROVER_RETURN_IF_ERROR(source_->Read(0, head));
    crc.Update(head);
  }
  Statistics counted;
  std::set<std::uint64_t> attachments_seen;
  std::set<std::uint64_t> metadata_seen;
  std::size_t chunks_seen = 0;
  ChunkIndex* last_chunk = nullptr;  // scan mode: collects the message indexes that follow it
  Bytes decompressed;

  std::uint64_t pos = header_end_;
  while (true) {
    const char* before = has_summary() ? "the summary" : "the footer";
    if (end - pos < kRecordPrefixBytes) {
      return Error(pos, "the data section ends without a DataEnd record (" + Num(end - pos) +
                            " bytes before " + before + " at " + Num(end) +
                            "; the file is truncated or corrupt)");
    }
    ByteSpan view;
    ROVER_RETURN_IF_ERROR(window.View(pos, kRecordPrefixBytes, view));
    std::array<std::uint8_t, kRecordPrefixBytes> prefix{};
    std::copy(view.begin(), view.end(), prefix.begin());
    const std::uint8_t op = prefix[0];
    const std::uint64_t length = LoadLe(prefix, 1, 8);
    if (length > end - pos - kRecordPrefixBytes) {
      return Error(static_cast<Opcode>(op), pos,
                   "length " + Num(length) + " runs past the end of the data section at " +
                       Num(end) + " (the file is truncated or corrupt)");
    }
    if (length > options_.max_record_bytes) {
      return Error(static_cast<Opcode>(op), pos,
                   "length " + Num(length) + " exceeds the reader's limit of " +
                       Num(options_.max_record_bytes) + " bytes");
    }
    if (op == static_cast<std::uint8_t>(Opcode::kDataEnd)) {
      ByteSpan content;
      ROVER_RETURN_IF_ERROR(window.View(pos + kRecordPrefixBytes, length, content));
      Result<DataEnd> de = ParseDataEnd(content);
      if (!de.ok()) return Error(Opcode::kDataEnd, pos, de.status().message());
      if (has_summary() && pos != data_end_offset_) {
        return Error(Opcode::kDataEnd, pos,
                     "the data section ends here, but the footer puts the summary at " +
                         Num(footer_.summary_start));
      }
      if (!has_summary() && pos + kRecordPrefixBytes + length != footer_offset_) {
        return Error(Opcode::kDataEnd, pos,
                     Num(footer_offset_ - pos - kRecordPrefixBytes - length) +
                         " bytes follow it before the Footer, but the footer says the file has no "
                         "summary");
      }
      if (de->data_section_crc != 0 && de->data_section_crc != crc.Value()) {
        return Error(Opcode::kDataEnd, pos,
                     "data_section_crc " + Hex32(de->data_section_crc) +
                         " does not match the data section's " + Hex32(crc.Value()) +
                         " (the file is corrupt)");
      }
      data_end_offset_ = pos;
      data_section_crc_ = de->data_section_crc;
      break;
    }
    crc.Update(prefix);
    ByteSpan c;
    ROVER_RETURN_IF_ERROR(window.View(pos + kRecordPrefixBytes, length, c));
    crc.Update(c);
    auto fail = [&](const Status& s) { return Error(static_cast<Opcode>(op), pos, s.message()); };
    if (op != static_cast<std::uint8_t>(Opcode::kMessageIndex)) last_chunk = nullptr;

    switch (static_cast<Opcode>(op)) {
      case Opcode::kHeader:
      case Opcode::kFooter:
        return Error(static_cast<Opcode>(op), pos, "not allowed in the data section");
      case Opcode::kSchema: {
        Result<Schema> s = ParseSchema(c);
        if (!s.ok()) return fail(s.status());
        ROVER_RETURN_IF_ERROR(LearnSchema(std::move(s).value(), Opcode::kSchema, pos));
        break;
      }
      case Opcode::kChannel: {
        Result<Channel> ch = ParseChannel(c);
        if (!ch.ok()) return fail(ch.status());
        ROVER_RETURN_IF_ERROR(LearnChannel(std::move(ch).value(), Opcode::kChannel, pos));
        break;
      }
      case Opcode::kMessage: {
        Result<MessageView> m = ParseMessage(c);
        if (!m.ok()) return fail(m.status());
        if (!channels_.contains(m->channel_id)) {
          return fail(InvalidArgument("channel " + Num(m->channel_id) +
                                      " is not defined before the message"));
        }
        loose_.push_back({m->log_time, pos, kRecordPrefixBytes + length, m->channel_id});
        CountMessage(counted, m->channel_id, m->log_time);
        break;
      }
      case Opcode::kChunk: {
        Result<ChunkView> chunk = ParseChunk(c);
        if (!chunk.ok()) return fail(chunk.status());
        const ChunkView& v = chunk.value();
        ++chunks_seen;
        if (!scan_mode) {
          const auto it = std::lower_bound(
              chunk_indexes_.begin(), chunk_indexes_.end(), pos,
              [](const ChunkIndex& x, std::uint64_t o) { return x.chunk_start_offset < o; });
          if (it == chunk_indexes_.end() || it->chunk_start_offset != pos) {
            return fail(InvalidArgument("no ChunkIndex in the summary points at this chunk"));
          }
          if (it->chunk_length != kRecordPrefixBytes + length ||
              it->message_start_time != v.message_start_time ||
              it->message_end_time != v.message_end_time || it->compression != v.compression ||
              it->compressed_size != v.records.size() ||
              it->uncompressed_size != v.uncompressed_size) {
            return fail(InvalidArgument(
                "its length, times, sizes or compression differ from its ChunkIndex"));
          }
          break;
        }
        ROVER_RETURN_IF_ERROR(DecompressChunk(v, pos, decompressed));
        ChunkIndex index;
        index.message_start_time = v.message_start_time;
        index.message_end_time = v.message_end_time;
        index.chunk_start_offset = pos;
        index.chunk_length = kRecordPrefixBytes + length;
        index.compression = v.compression;
        index.compressed_size = v.records.size();
        index.uncompressed_size = v.uncompressed_size;
        ChunkVisitor visitor;
        visitor.schema = [&](Schema s, std::uint64_t) {
          return LearnSchema(std::move(s), Opcode::kChunk, pos);
        };
        visitor.channel = [&](Channel ch, std::uint64_t) {
          return LearnChannel(std::move(ch), Opcode::kChunk, pos);
        };
        visitor.message = [&](const MessageView& m, std::uint64_t) {
          CountMessage(counted, m.channel_id, m.log_time);
          return Status::Ok();
        };
        ROVER_RETURN_IF_ERROR(WalkChunk(decompressed, v, pos, visitor));
        chunk_indexes_.push_back(std::move(index));
        last_chunk = &chunk_indexes_.back();
        break;
      }
      case Opcode::kMessageIndex: {
        Result<MessageIndex> mi = ParseMessageIndex(c);
        if (!mi.ok()) return fail(mi.status());
        if (last_chunk != nullptr) {
          last_chunk->message_index_offsets[mi->channel_id] = pos;
          last_chunk->message_index_length += kRecordPrefixBytes + length;
        }
        break;
      }
      case Opcode::kAttachment: {
        Result<Attachment> a = ParseAttachment(c);  // checks its CRC
        if (!a.ok()) return fail(a.status());
        attachments_seen.insert(pos);
        if (scan_mode) {
          attachment_indexes_.push_back({pos, kRecordPrefixBytes + length, a->log_time,
                                         a->create_time, a->data.size(), a->name, a->media_type});
        }
        break;
      }
      case Opcode::kMetadata: {
        Result<Metadata> m = ParseMetadata(c);
        if (!m.ok()) return fail(m.status());
        metadata_seen.insert(pos);
        if (scan_mode) metadata_indexes_.push_back({pos, kRecordPrefixBytes + length, m->name});
        break;
      }
      default:
        if (IsSummaryRecord(op)) {
          return Error(static_cast<Opcode>(op), pos,
                       "a summary record is not allowed in the data section");
        }
        break;  // private or future records: skipped
    }
    pos += kRecordPrefixBytes + length;
  }

  if (scan_mode) {
    counted.schema_count = static_cast<std::uint16_t>(schemas_.size());
    counted.channel_count = static_cast<std::uint32_t>(channels_.size());
    counted.attachment_count = static_cast<std::uint32_t>(attachment_indexes_.size());
    counted.metadata_count = static_cast<std::uint32_t>(metadata_indexes_.size());
    counted.chunk_count = static_cast<std::uint32_t>(chunk_indexes_.size());
    for (const auto& [id, channel] : channels_) counted.channel_message_counts.try_emplace(id, 0);
    statistics_ = std::move(counted);
  } else {
    if (chunks_seen != chunk_indexes_.size()) {
      return Error(footer_.summary_start, "the summary indexes " + Num(chunk_indexes_.size()) +
                                              " chunks, the data section holds " +
                                              Num(chunks_seen));
    }
    for (const AttachmentIndex& a : attachment_indexes_) {
      if (!attachments_seen.contains(a.offset)) {
        return Error(Opcode::kAttachmentIndex, footer_.summary_start,
                     "no Attachment record at offset " + Num(a.offset));
      }
    }
    for (const MetadataIndex& m : metadata_indexes_) {
      if (!metadata_seen.contains(m.offset)) {
        return Error(Opcode::kMetadataIndex, footer_.summary_start,
                     "no Metadata record at offset " + Num(m.offset));
      }
    }
  }
  std::sort(loose_.begin(), loose_.end(), [](const LooseMessage& a, const LooseMessage& b) {
    return std::tie(a.log_time, a.offset) < std::tie(b.log_time, b.offset);
  });
  return Status::Ok();
}

Status Reader::Verify(bool data_crc) const {
  if (data_crc && data_section_crc_ != 0) {
    Crc32 crc;
    Bytes block;
    for (std::uint64_t pos = 0; pos < data_end_offset_;) {
      block.resize(std::min(kWindowBytes, data_end_offset_ - pos));
      ROVER_RETURN_IF_ERROR(source_->Read(pos, block));
      crc.Update(block);
      pos += block.size();
    }
    if (crc.Value() != data_section_crc_) {
      return Error(Opcode::kDataEnd, data_end_offset_,
                   "data_section_crc " + Hex32(data_section_crc_) +
                       " does not match the data section's " + Hex32(crc.Value()) +
                       " (the file is corrupt)");
    }
  }

  Statistics counted;

  for (const ChunkIndex& index : chunk_indexes_) {
    Loaded loaded;
    std::map<std::uint16_t, std::vector<std::pair<Timestamp, std::uint64_t>>> actual;
    ROVER_RETURN_IF_ERROR(LoadChunk(
        index,
        [&](const MessageView& m) {
          CountMessage(counted, m.channel_id, m.log_time);
          return true;
        },
        loaded));
    for (const auto& [t, offset] : loaded.entries) {
      const std::uint16_t channel =
          static_cast<std::uint16_t>(LoadLe(loaded.records, offset + 9, 2));
      actual[channel].emplace_back(t, offset);
    }
    if (index.message_index_length == 0) continue;  // written without message indexes
    const std::uint64_t at = index.chunk_start_offset + index.chunk_length;
    Bytes bytes(index.message_index_length);
    ROVER_RETURN_IF_ERROR(source_->Read(at, bytes));
    std::set<std::uint16_t> indexed;
    for (std::uint64_t pos = 0; pos < bytes.size();) {
      Result<RecordView> rec = SplitRecord(bytes, pos);
      if (!rec.ok()) return Error(at + pos, "message index: " + rec.status().message());
      if (rec->opcode != static_cast<std::uint8_t>(Opcode::kMessageIndex)) {
        return Error(at + pos, "expected a MessageIndex record after the chunk at " +
                                   Num(index.chunk_start_offset) + ", found " +
                                   OpcodeName(rec->opcode));
      }
      Result<MessageIndex> mi = ParseMessageIndex(rec->content);
      if (!mi.ok()) return Error(Opcode::kMessageIndex, at + pos, mi.status().message());
      std::vector<std::pair<Timestamp, std::uint64_t>> entries = mi->records;
      std::sort(entries.begin(), entries.end());
      if (entries != actual[mi->channel_id]) {
        return Error(Opcode::kMessageIndex, at + pos,
                     "its " + Num(entries.size()) + " entries for channel " + Num(mi->channel_id) +
                         " do not match the " + Num(actual[mi->channel_id].size()) +
                         " messages of the chunk at " + Num(index.chunk_start_offset));
      }
      const auto named = index.message_index_offsets.find(mi->channel_id);
      if (!index.message_index_offsets.empty() &&
          (named == index.message_index_offsets.end() || named->second != at + pos)) {
        return Error(Opcode::kMessageIndex, at + pos,
                     "the ChunkIndex of the chunk at " + Num(index.chunk_start_offset) +
                         " does not point at this index of channel " + Num(mi->channel_id));
      }
      indexed.insert(mi->channel_id);
      pos += rec->size();
    }
    for (const auto& [channel, entries] : actual) {
      if (!indexed.contains(channel)) {
        return Error(Opcode::kChunk, index.chunk_start_offset,
                     Num(entries.size()) + " messages on channel " + Num(channel) +
                         " have no MessageIndex record after the chunk");
      }
    }
  }
  for (const LooseMessage& m : loose_) CountMessage(counted, m.channel_id, m.log_time);
  for (const AttachmentIndex& a : attachment_indexes_) {
    ROVER_RETURN_IF_ERROR(ReadAttachment(a).status());
  }

  if (statistics_) {
    const Statistics& s = *statistics_;
    std::string wrong;
    if (s.message_count != counted.message_count) {
      wrong = "message_count " + Num(s.message_count) + ", the file holds " +
              Num(counted.message_count) + " messages";
    } else if (s.message_count > 0 && (s.message_start_time != counted.message_start_time ||
                                       s.message_end_time != counted.message_end_time)) {
      wrong = "message times [" + Num(s.message_start_time) + ", " + Num(s.message_end_time) +
              "], the messages span [" + Num(counted.message_start_time) + ", " +
              Num(counted.message_end_time) + "]";
    } else if (s.chunk_count != chunk_indexes_.size()) {
      wrong = "chunk_count " + Num(s.chunk_count) + ", the file holds " +
              Num(chunk_indexes_.size()) + " chunks";
    } else if (s.attachment_count != attachment_indexes_.size()) {
      wrong = "attachment_count " + Num(s.attachment_count) + ", the file indexes " +
              Num(attachment_indexes_.size());
    } else if (s.metadata_count != metadata_indexes_.size()) {
      wrong = "metadata_count " + Num(s.metadata_count) + ", the file indexes " +
              Num(metadata_indexes_.size());
    } else {
      for (const auto& [channel, n] : s.channel_message_counts) {
        const auto it = counted.channel_message_counts.find(channel);
        const std::uint64_t have = it == counted.channel_message_counts.end() ? 0 : it->second;
        if (have != n) {
          wrong = "channel " + Num(channel) + " has " + Num(n) + " messages, the file holds " +
                  Num(have);
          break;
        }
      }
    }
    if (!wrong.empty()) {
      return Error(Opcode::kStatistics, footer_.summary_start,
                   wrong + " (the statistics disagree with the data)");
    }
  }
  return Status::Ok();
}

// ---- metadata and attachments -------------------------------------------------------------------

Result<Metadata> Reader::ReadMetadata(const MetadataIndex& index) const {
  Bytes buffer;
  ByteSpan content;
  ROVER_RETURN_IF_ERROR(
      ReadRecordAt(index.offset, index.length, Opcode::kMetadata, buffer, content));
  Result<Metadata> m = ParseMetadata(content);
  if (!m.ok()) return Error(Opcode::kMetadata, index.offset, m.status().message());
  if (m->name != index.name) {
    return Error(Opcode::kMetadata, index.offset,
                 "name '" + m->name + "' differs from its index's '" + index.name + "'");
  }
  return m;
}

Result<std::vector<Metadata>> Reader::ReadAllMetadata() const {
  std::vector<Metadata> all;
  for (const MetadataIndex& index : metadata_indexes_) {
    ROVER_ASSIGN_OR_RETURN(Metadata m, ReadMetadata(index));
    all.push_back(std::move(m));
  }
  return all;
}

Result<Attachment> Reader::ReadAttachment(const AttachmentIndex& index) const {
  Bytes buffer;
  ByteSpan content;
  ROVER_RETURN_IF_ERROR(
      ReadRecordAt(index.offset, index.length, Opcode::kAttachment, buffer, content));
  Result<Attachment> a = ParseAttachment(content);
  if (!a.ok()) return Error(Opcode::kAttachment, index.offset, a.status().message());
  if (a->name != index.name || a->data.size() != index.data_size) {
    return Error(Opcode::kAttachment, index.offset,
                 "name or size differs from its AttachmentIndex");
  }
  return a;
}

// ---- messages -----------------------------------------------------------------------------------

struct MessageCursor::State {
  const Reader* reader = nullptr;
  MessageFilter filter;
  std::vector<char> keep_channel;  ///< by channel id

  struct Stream {
    const ChunkIndex* chunk = nullptr;  ///< null: the messages outside chunks
    bool loaded = false;
    std::shared_ptr<Reader::Loaded> data;
    std::vector<std::size_t> loose;  ///< indexes into reader->loose_
    std::size_t next = 0;
  };
  std::vector<Stream> streams;
  std::vector<std::size_t> heap;         ///< min-heap of stream indexes by Key
  std::shared_ptr<Reader::Loaded> hold;  ///< keeps the last message's bytes alive
  Bytes loose_buffer;
  Status error;
  bool done = false;

  /// (log time, container offset, offset inside): file order among equal times.
  using Key = std::tuple<Timestamp, std::uint64_t, std::uint64_t>;
  Key KeyOf(const Stream& s) const {
    if (s.chunk == nullptr) {
      const auto& m = reader->loose_[s.loose[s.next]];
      return {m.log_time, m.offset, 0};
    }
    if (!s.loaded) return {s.chunk->message_start_time, s.chunk->chunk_start_offset, 0};
    const auto& e = s.data->entries[s.next];
    return {e.first, s.chunk->chunk_start_offset, e.second};
  }
  bool Later(std::size_t a, std::size_t b) const { return KeyOf(streams[a]) > KeyOf(streams[b]); }
  void Push(std::size_t i) {
    heap.push_back(i);
    std::push_heap(heap.begin(), heap.end(), [this](auto a, auto b) { return Later(a, b); });
  }
  std::size_t Pop() {
    std::pop_heap(heap.begin(), heap.end(), [this](auto a, auto b) { return Later(a, b); });
    const std::size_t i = heap.back();
    heap.pop_back();
    return i;
  }
  bool Keep(const MessageView& m) const {
    return keep_channel[m.channel_id] != 0 && m.log_time >= filter.start_time &&
           m.log_time <= filter.end_time;
  }
};

MessageCursor::MessageCursor(std::unique_ptr<State> state) : state_(std::move(state)) {}
MessageCursor::MessageCursor(MessageCursor&&) noexcept = default;
MessageCursor& MessageCursor::operator=(MessageCursor&&) noexcept = default;
MessageCursor::~MessageCursor() = default;

Result<MessageCursor> Reader::Messages(const MessageFilter& filter) const {
  auto state = std::make_unique<MessageCursor::State>();
  state->reader = this;
  state->filter = filter;
  state->keep_channel.assign(65536, 0);
  for (const auto& [id, channel] : channels_) {
    const bool topic_ok =
        filter.topics.empty() ||
        std::find(filter.topics.begin(), filter.topics.end(), channel.topic) != filter.topics.end();
    state->keep_channel[id] = topic_ok && (!filter.channel || filter.channel(channel)) ? 1 : 0;
  }
  for (const ChunkIndex& c : chunk_indexes_) {
    if (c.message_end_time < filter.start_time || c.message_start_time > filter.end_time) continue;
    if (!c.message_index_offsets.empty()) {
      bool any = false;
      for (const auto& [id, offset] : c.message_index_offsets) any = any || state->keep_channel[id];
      if (!any) continue;
    }
    MessageCursor::State::Stream s;
    s.chunk = &c;
    state->streams.push_back(std::move(s));
  }
  MessageCursor::State::Stream loose;
  for (std::size_t i = 0; i < loose_.size(); ++i) {
    const LooseMessage& m = loose_[i];
    if (state->keep_channel[m.channel_id] && m.log_time >= filter.start_time &&
        m.log_time <= filter.end_time) {
      loose.loose.push_back(i);
    }
  }
  if (!loose.loose.empty()) {
    loose.loaded = true;
    state->streams.push_back(std::move(loose));
  }
  for (std::size_t i = 0; i < state->streams.size(); ++i) state->Push(i);
  return MessageCursor(std::move(state));
}

Result<std::optional<MessageEvent>> MessageCursor::Next() {
  State& st = *state_;
  if (!st.error.ok()) return st.error;
  const Reader& r = *st.reader;
  while (!st.done) {
    if (st.heap.empty()) {
      st.done = true;
      st.hold.reset();
      break;
    }
    const std::size_t i = st.Pop();
    State::Stream& s = st.streams[i];
    if (!s.loaded) {
      s.data = std::make_shared<Reader::Loaded>();
      Status loaded = r.LoadChunk(
          *s.chunk, [&st](const MessageView& m) { return st.Keep(m); }, *s.data);
      if (!loaded.ok()) {
        st.error = loaded;
        return loaded;
      }
      s.loaded = true;
      if (!s.data->entries.empty()) st.Push(i);
      continue;
    }

    MessageEvent event;
    if (s.chunk != nullptr) {
      const std::uint64_t offset = s.data->entries[s.next].second;
      Result<RecordView> rec = SplitRecord(s.data->records, offset);
      ROVER_DEMAND(rec.ok());  // the chunk walk checked every record
      Result<MessageView> m = ParseMessage(rec->content);
      ROVER_DEMAND(m.ok());
      event.message = m.value();
      st.hold = s.data;
    } else {
      const Reader::LooseMessage& lm = r.loose_[s.loose[s.next]];
      ByteSpan content;
      Status read =
          r.ReadRecordAt(lm.offset, lm.length, Opcode::kMessage, st.loose_buffer, content);
      Result<MessageView> m = read.ok() ? ParseMessage(content) : Result<MessageView>(read);
      if (read.ok() && !m.ok()) read = r.Error(Opcode::kMessage, lm.offset, m.status().message());
      if (read.ok() && (m->log_time != lm.log_time || m->channel_id != lm.channel_id)) {
        read = r.Error(Opcode::kMessage, lm.offset, "changed since the file was opened");
      }
      if (!read.ok()) {
        st.error = read;
        return read;
      }
      event.message = m.value();
      st.hold.reset();
    }
    ++s.next;
    const std::size_t remaining = s.chunk != nullptr ? s.data->entries.size() : s.loose.size();
    if (s.next < remaining) {
      st.Push(i);
    } else if (s.chunk != nullptr) {
      s.data.reset();  // `hold` keeps it until the next call
    }
    const auto channel = r.channels_.find(event.message.channel_id);
    ROVER_DEMAND(channel != r.channels_.end());  // checked when the chunk was walked
    event.channel = &channel->second;
    const auto schema = r.schemas_.find(channel->second.schema_id);
    event.schema = schema == r.schemas_.end() ? nullptr : &schema->second;
    return std::optional<MessageEvent>(event);
  }
  return std::optional<MessageEvent>();
}

Status Reader::ForEachMessage(const MessageFilter& filter,
                              const std::function<Status(const MessageEvent&)>& f) const {
  ROVER_ASSIGN_OR_RETURN(MessageCursor cursor, Messages(filter));
  while (true) {
    ROVER_ASSIGN_OR_RETURN(std::optional<MessageEvent> event, cursor.Next());
    if (!event) return Status::Ok();
    ROVER_RETURN_IF_ERROR(f(*event));
  }
}

}  // namespace rover::mcap
