#include "rover/mcap/records.hpp"

#include <algorithm>
#include <cstdio>
#include <cstring>

#include "rover/base/check.hpp"
#include "rover/mcap/crc32.hpp"

namespace rover::mcap {

std::string OpcodeName(std::uint8_t opcode) {
  static const char* const kNames[] = {"invalid record 0x00",
                                       "Header",
                                       "Footer",
                                       "Schema",
                                       "Channel",
                                       "Message",
                                       "Chunk",
                                       "MessageIndex",
                                       "ChunkIndex",
                                       "Attachment",
                                       "AttachmentIndex",
                                       "Statistics",
                                       "Metadata",
                                       "MetadataIndex",
                                       "SummaryOffset",
                                       "DataEnd"};
  if (opcode <= 0x0F) return kNames[opcode];
  char buf[32];
  std::snprintf(buf, sizeof buf, "%s record 0x%02x", opcode >= 0x80 ? "private" : "unknown",
                static_cast<unsigned>(opcode));
  return buf;
}

std::string Hex32(std::uint32_t v) {
  char buf[16];
  std::snprintf(buf, sizeof buf, "0x%08x", static_cast<unsigned>(v));
  return buf;
}

namespace {

// ---- little-endian writing ----------------------------------------------------------------------

class Out {
 public:
  Out(Bytes& b, Opcode op) : b_(b) {
    b_.push_back(static_cast<std::uint8_t>(op));
    length_at_ = b_.size();
    U64(0);  // patched by the destructor
  }
  ~Out() {
    const std::uint64_t n = b_.size() - length_at_ - 8;
    for (int i = 0; i < 8; ++i) b_[length_at_ + i] = static_cast<std::uint8_t>(n >> (8 * i));
  }
  Out(const Out&) = delete;
  Out& operator=(const Out&) = delete;

  void U8(std::uint8_t v) { b_.push_back(v); }
  void U16(std::uint16_t v) { Le(v, 2); }
  void U32(std::uint32_t v) { Le(v, 4); }
  void U64(std::uint64_t v) { Le(v, 8); }
  void Raw(ByteSpan s) { b_.insert(b_.end(), s.begin(), s.end()); }
  void Str(std::string_view s) {
    U32(Len32(s.size()));
    Raw(AsBytes(s));
  }
  void Bytes32(ByteSpan s) {
    U32(Len32(s.size()));
    Raw(s);
  }
  void Bytes64(ByteSpan s) {
    U64(s.size());
    Raw(s);
  }
  void Map(const StringMap& m) {
    const std::size_t at = Begin32();
    for (const auto& [k, v] : m) {
      Str(k);
      Str(v);
    }
    End32(at);
  }
  void Map(const std::map<std::uint16_t, std::uint64_t>& m) {
    U32(Len32(m.size() * 10));
    for (const auto& [k, v] : m) {
      U16(k);
      U64(v);
    }
  }
  std::size_t size() const { return b_.size(); }
  /// The bytes appended since `from`.
  ByteSpan Since(std::size_t from) const { return ByteSpan(b_).subspan(from); }

 private:
  static std::uint32_t Len32(std::uint64_t n) {
    ROVER_DEMAND_MSG(n <= 0xFFFFFFFFu, "an MCAP string, map or array exceeds 4 GiB");
    return static_cast<std::uint32_t>(n);
  }
  void Le(std::uint64_t v, int n) {
    for (int i = 0; i < n; ++i) b_.push_back(static_cast<std::uint8_t>(v >> (8 * i)));
  }
  std::size_t Begin32() {
    const std::size_t at = b_.size();
    U32(0);
    return at;
  }
  void End32(std::size_t at) {
    const std::uint32_t n = Len32(b_.size() - at - 4);
    for (int i = 0; i < 4; ++i) b_[at + i] = static_cast<std::uint8_t>(n >> (8 * i));
  }

  Bytes& b_;
  std::size_t length_at_ = 0;
};

// ---- bounds-checked little-endian reading -------------------------------------------------------

class In {
 public:
  explicit In(ByteSpan c) : c_(c) {}

  std::uint64_t left() const { return c_.size() - pos_; }
  std::uint64_t pos() const { return pos_; }

  Status U8(const char* field, std::uint8_t& v) { return Fixed(field, v); }
  Status U16(const char* field, std::uint16_t& v) { return Fixed(field, v); }
  Status U32(const char* field, std::uint32_t& v) { return Fixed(field, v); }
  Status U64(const char* field, std::uint64_t& v) { return Fixed(field, v); }
  Status Span(const char* field, std::uint64_t n, const char* what, ByteSpan& v) {
    if (n > left()) {
      return InvalidArgument(Field(field) + "a " + what + " of " + std::to_string(n) +
                             " bytes runs past the end of the record (" + std::to_string(left()) +
                             " bytes left)");
    }
    v = c_.subspan(pos_, n);
    pos_ += n;
    return Status::Ok();
  }
  Status Str(const char* field, std::string& v) {
    std::uint32_t n = 0;
    ROVER_RETURN_IF_ERROR(U32(field, n));
    ByteSpan s;
    ROVER_RETURN_IF_ERROR(Span(field, n, "string", s));
    v.assign(reinterpret_cast<const char*>(s.data()), s.size());
    return Status::Ok();
  }
  Status Bytes32(const char* field, Bytes& v) {
    std::uint32_t n = 0;
    ROVER_RETURN_IF_ERROR(U32(field, n));
    ByteSpan s;
    ROVER_RETURN_IF_ERROR(Span(field, n, "byte string", s));
    v.assign(s.begin(), s.end());
    return Status::Ok();
  }
  Status Span64(const char* field, ByteSpan& v) {
    std::uint64_t n = 0;
    ROVER_RETURN_IF_ERROR(U64(field, n));
    return Span(field, n, "byte string", v);
  }
  /// The uint32-length-prefixed body of a map or array.
  Status Body32(const char* field, const char* what, In& body) {
    std::uint32_t n = 0;
    ROVER_RETURN_IF_ERROR(U32(field, n));
    ByteSpan s;
    ROVER_RETURN_IF_ERROR(Span(field, n, what, s));
    body = In(s);
    return Status::Ok();
  }
  Status Map(const char* field, StringMap& m) {
    In body(ByteSpan{});
    ROVER_RETURN_IF_ERROR(Body32(field, "map", body));
    m.clear();
    while (body.left() > 0) {
      std::string k;
      std::string v;
      Status s = body.Str("key", k);
      if (s.ok()) s = body.Str("value", v);
      if (!s.ok())
        return InvalidArgument(Field(field) + "entry " + std::to_string(m.size()) + ": " +
                               s.message());
      m[std::move(k)] = std::move(v);
    }
    return Status::Ok();
  }
  Status Map(const char* field, std::map<std::uint16_t, std::uint64_t>& m) {
    In body(ByteSpan{});
    ROVER_RETURN_IF_ERROR(Body32(field, "map", body));
    if (body.left() % 10 != 0) {
      return InvalidArgument(Field(field) + "a map of (uint16, uint64) entries has " +
                             std::to_string(body.left()) + " bytes, not a multiple of 10");
    }
    m.clear();
    while (body.left() > 0) {
      std::uint16_t k = 0;
      std::uint64_t v = 0;
      ROVER_DEMAND(body.U16("key", k).ok() && body.U64("value", v).ok());
      m[k] = v;
    }
    return Status::Ok();
  }
  Status Pairs(const char* field, std::vector<std::pair<Timestamp, std::uint64_t>>& v) {
    In body(ByteSpan{});
    ROVER_RETURN_IF_ERROR(Body32(field, "array", body));
    if (body.left() % 16 != 0) {
      return InvalidArgument(Field(field) + "an array of (timestamp, uint64) entries has " +
                             std::to_string(body.left()) + " bytes, not a multiple of 16");
    }
    v.clear();
    v.reserve(body.left() / 16);
    while (body.left() > 0) {
      std::uint64_t t = 0;
      std::uint64_t o = 0;
      ROVER_DEMAND(body.U64("log_time", t).ok() && body.U64("offset", o).ok());
      v.emplace_back(t, o);
    }
    return Status::Ok();
  }
  ByteSpan Rest() {
    ByteSpan r = c_.subspan(pos_);
    pos_ = c_.size();
    return r;
  }

 private:
  static std::string Field(const char* field) { return std::string("field '") + field + "': "; }
  template <class T>
  Status Fixed(const char* field, T& v) {
    if (left() < sizeof(T)) {
      return InvalidArgument(Field(field) + "needs " + std::to_string(sizeof(T)) + " bytes, " +
                             std::to_string(left()) + " are left in the record");
    }
    std::uint64_t x = 0;
    for (std::size_t i = 0; i < sizeof(T); ++i) x |= std::uint64_t{c_[pos_ + i]} << (8 * i);
    v = static_cast<T>(x);
    pos_ += sizeof(T);
    return Status::Ok();
  }

  ByteSpan c_;
  std::uint64_t pos_ = 0;
};

std::uint64_t StrSize(std::string_view s) { return 4 + s.size(); }
std::uint64_t MapSize(const StringMap& m) {
  std::uint64_t n = 4;
  for (const auto& [k, v] : m) n += StrSize(k) + StrSize(v);
  return n;
}

}  // namespace

void CountMessage(Statistics& s, std::uint16_t channel, Timestamp log_time) {
  if (s.message_count == 0) s.message_start_time = s.message_end_time = log_time;
  s.message_start_time = std::min(s.message_start_time, log_time);
  s.message_end_time = std::max(s.message_end_time, log_time);
  ++s.message_count;
  ++s.channel_message_counts[channel];
}

// ---- writing ------------------------------------------------------------------------------------

void AppendRecord(Bytes& out, const Header& r) {
  Out o(out, Opcode::kHeader);
  o.Str(r.profile);
  o.Str(r.library);
}

void AppendRecord(Bytes& out, const Footer& r) {
  Out o(out, Opcode::kFooter);
  o.U64(r.summary_start);
  o.U64(r.summary_offset_start);
  o.U32(r.summary_crc);
}

void AppendRecord(Bytes& out, const Schema& r) {
  Out o(out, Opcode::kSchema);
  o.U16(r.id);
  o.Str(r.name);
  o.Str(r.encoding);
  o.Bytes32(r.data);
}

void AppendRecord(Bytes& out, const Channel& r) {
  Out o(out, Opcode::kChannel);
  o.U16(r.id);
  o.U16(r.schema_id);
  o.Str(r.topic);
  o.Str(r.message_encoding);
  o.Map(r.metadata);
}

void AppendRecord(Bytes& out, const MessageView& r) {
  Out o(out, Opcode::kMessage);
  o.U16(r.channel_id);
  o.U32(r.sequence);
  o.U64(r.log_time);
  o.U64(r.publish_time);
  o.Raw(r.data);
}

void AppendRecord(Bytes& out, const ChunkView& r) {
  Out o(out, Opcode::kChunk);
  o.U64(r.message_start_time);
  o.U64(r.message_end_time);
  o.U64(r.uncompressed_size);
  o.U32(r.uncompressed_crc);
  o.Str(r.compression);
  o.Bytes64(r.records);
}

void AppendRecord(Bytes& out, const MessageIndex& r) {
  Out o(out, Opcode::kMessageIndex);
  o.U16(r.channel_id);
  ROVER_DEMAND(r.records.size() <= 0xFFFFFFFFu / 16);
  o.U32(static_cast<std::uint32_t>(r.records.size() * 16));
  for (const auto& [t, off] : r.records) {
    o.U64(t);
    o.U64(off);
  }
}

void AppendRecord(Bytes& out, const ChunkIndex& r) {
  Out o(out, Opcode::kChunkIndex);
  o.U64(r.message_start_time);
  o.U64(r.message_end_time);
  o.U64(r.chunk_start_offset);
  o.U64(r.chunk_length);
  o.Map(r.message_index_offsets);
  o.U64(r.message_index_length);
  o.Str(r.compression);
  o.U64(r.compressed_size);
  o.U64(r.uncompressed_size);
}

void AppendRecord(Bytes& out, const Attachment& r) {
  Out o(out, Opcode::kAttachment);
  const std::size_t from = o.size();
  o.U64(r.log_time);
  o.U64(r.create_time);
  o.Str(r.name);
  o.Str(r.media_type);
  o.Bytes64(r.data);
  o.U32(ComputeCrc32(o.Since(from)));
}

void AppendRecord(Bytes& out, const AttachmentIndex& r) {
  Out o(out, Opcode::kAttachmentIndex);
  o.U64(r.offset);
  o.U64(r.length);
  o.U64(r.log_time);
  o.U64(r.create_time);
  o.U64(r.data_size);
  o.Str(r.name);
  o.Str(r.media_type);
}

void AppendRecord(Bytes& out, const Statistics& r) {
  Out o(out, Opcode::kStatistics);
  o.U64(r.message_count);
  o.U16(r.schema_count);
  o.U32(r.channel_count);
  o.U32(r.attachment_count);
  o.U32(r.metadata_count);
  o.U32(r.chunk_count);
  o.U64(r.message_start_time);
  o.U64(r.message_end_time);
  o.Map(r.channel_message_counts);
}

void AppendRecord(Bytes& out, const Metadata& r) {
  Out o(out, Opcode::kMetadata);
  o.Str(r.name);
  o.Map(r.metadata);
}

void AppendRecord(Bytes& out, const MetadataIndex& r) {
  Out o(out, Opcode::kMetadataIndex);
  o.U64(r.offset);
  o.U64(r.length);
  o.Str(r.name);
}

void AppendRecord(Bytes& out, const SummaryOffset& r) {
  Out o(out, Opcode::kSummaryOffset);
  o.U8(r.group_opcode);
  o.U64(r.group_start);
  o.U64(r.group_length);
}

void AppendRecord(Bytes& out, const DataEnd& r) {
  Out o(out, Opcode::kDataEnd);
  o.U32(r.data_section_crc);
}

std::uint64_t RecordSize(const Schema& r) {
  return kRecordPrefixBytes + 2 + StrSize(r.name) + StrSize(r.encoding) + 4 + r.data.size();
}
std::uint64_t RecordSize(const Channel& r) {
  return kRecordPrefixBytes + 2 + 2 + StrSize(r.topic) + StrSize(r.message_encoding) +
         MapSize(r.metadata);
}
std::uint64_t RecordSize(const Metadata& r) {
  return kRecordPrefixBytes + StrSize(r.name) + MapSize(r.metadata);
}
std::uint64_t RecordSize(const MetadataIndex& r) {
  return kRecordPrefixBytes + 8 + 8 + StrSize(r.name);
}
std::uint64_t RecordSize(const AttachmentIndex& r) {
  return kRecordPrefixBytes + 5 * 8 + StrSize(r.name) + StrSize(r.media_type);
}
std::uint64_t MessageRecordSize(std::uint64_t data_bytes) {
  return kRecordPrefixBytes + kMessageHeaderBytes + data_bytes;
}
std::uint64_t ChunkRecordSize(std::uint64_t records_bytes, std::string_view compression) {
  return kRecordPrefixBytes + 8 + 8 + 8 + 4 + StrSize(compression) + 8 + records_bytes;
}
std::uint64_t MessageIndexRecordSize(std::uint64_t entries) {
  return kRecordPrefixBytes + 2 + 4 + 16 * entries;
}
std::uint64_t ChunkIndexRecordSize(std::uint64_t channels, std::string_view compression) {
  return kRecordPrefixBytes + 4 * 8 + 4 + 10 * channels + 8 + StrSize(compression) + 8 + 8;
}
std::uint64_t StatisticsRecordSize(std::uint64_t channels) {
  return kRecordPrefixBytes + 8 + 2 + 4 * 4 + 8 + 8 + 4 + 10 * channels;
}

// ---- reading ------------------------------------------------------------------------------------

Result<RecordView> SplitRecord(ByteSpan bytes, std::uint64_t pos) {
  ROVER_DEMAND(pos <= bytes.size());
  const std::uint64_t left = bytes.size() - pos;
  if (left < kRecordPrefixBytes) {
    return InvalidArgument("the record prefix needs 9 bytes, " + std::to_string(left) +
                           " are left");
  }
  RecordView r;
  r.opcode = bytes[pos];
  std::uint64_t n = 0;
  for (int i = 0; i < 8; ++i) n |= std::uint64_t{bytes[pos + 1 + i]} << (8 * i);
  if (n > left - kRecordPrefixBytes) {
    return InvalidArgument("a " + OpcodeName(r.opcode) + " record of " + std::to_string(n) +
                           " content bytes runs past the end (" +
                           std::to_string(left - kRecordPrefixBytes) + " bytes left)");
  }
  r.content = bytes.subspan(pos + kRecordPrefixBytes, n);
  return r;
}

Result<Header> ParseHeader(ByteSpan content) {
  In in(content);
  Header r;
  ROVER_RETURN_IF_ERROR(in.Str("profile", r.profile));
  ROVER_RETURN_IF_ERROR(in.Str("library", r.library));
  return r;
}

Result<Footer> ParseFooter(ByteSpan content) {
  In in(content);
  Footer r;
  ROVER_RETURN_IF_ERROR(in.U64("summary_start", r.summary_start));
  ROVER_RETURN_IF_ERROR(in.U64("summary_offset_start", r.summary_offset_start));
  ROVER_RETURN_IF_ERROR(in.U32("summary_crc", r.summary_crc));
  return r;
}

Result<Schema> ParseSchema(ByteSpan content) {
  In in(content);
  Schema r;
  ROVER_RETURN_IF_ERROR(in.U16("id", r.id));
  ROVER_RETURN_IF_ERROR(in.Str("name", r.name));
  ROVER_RETURN_IF_ERROR(in.Str("encoding", r.encoding));
  ROVER_RETURN_IF_ERROR(in.Bytes32("data", r.data));
  return r;
}

Result<Channel> ParseChannel(ByteSpan content) {
  In in(content);
  Channel r;
  ROVER_RETURN_IF_ERROR(in.U16("id", r.id));
  ROVER_RETURN_IF_ERROR(in.U16("schema_id", r.schema_id));
  ROVER_RETURN_IF_ERROR(in.Str("topic", r.topic));
  ROVER_RETURN_IF_ERROR(in.Str("message_encoding", r.message_encoding));
  ROVER_RETURN_IF_ERROR(in.Map("metadata", r.metadata));
  return r;
}

Result<MessageView> ParseMessage(ByteSpan content) {
  In in(content);
  MessageView r;
  ROVER_RETURN_IF_ERROR(in.U16("channel_id", r.channel_id));
  ROVER_RETURN_IF_ERROR(in.U32("sequence", r.sequence));
  ROVER_RETURN_IF_ERROR(in.U64("log_time", r.log_time));
  ROVER_RETURN_IF_ERROR(in.U64("publish_time", r.publish_time));
  r.data = in.Rest();
  return r;
}

Result<ChunkView> ParseChunk(ByteSpan content) {
  In in(content);
  ChunkView r;
  ROVER_RETURN_IF_ERROR(in.U64("message_start_time", r.message_start_time));
  ROVER_RETURN_IF_ERROR(in.U64("message_end_time", r.message_end_time));
  ROVER_RETURN_IF_ERROR(in.U64("uncompressed_size", r.uncompressed_size));
  ROVER_RETURN_IF_ERROR(in.U32("uncompressed_crc", r.uncompressed_crc));
  ROVER_RETURN_IF_ERROR(in.Str("compression", r.compression));
  ROVER_RETURN_IF_ERROR(in.Span64("records", r.records));
  if (r.message_start_time > r.message_end_time) {
    return InvalidArgument("message_start_time " + std::to_string(r.message_start_time) +
                           " is after message_end_time " + std::to_string(r.message_end_time));
  }
  return r;
}

Result<MessageIndex> ParseMessageIndex(ByteSpan content) {
  In in(content);
  MessageIndex r;
  ROVER_RETURN_IF_ERROR(in.U16("channel_id", r.channel_id));
  ROVER_RETURN_IF_ERROR(in.Pairs("records", r.records));
  return r;
}

Result<ChunkIndex> ParseChunkIndex(ByteSpan content) {
  In in(content);
  ChunkIndex r;
  ROVER_RETURN_IF_ERROR(in.U64("message_start_time", r.message_start_time));
  ROVER_RETURN_IF_ERROR(in.U64("message_end_time", r.message_end_time));
  ROVER_RETURN_IF_ERROR(in.U64("chunk_start_offset", r.chunk_start_offset));
  ROVER_RETURN_IF_ERROR(in.U64("chunk_length", r.chunk_length));
  ROVER_RETURN_IF_ERROR(in.Map("message_index_offsets", r.message_index_offsets));
  ROVER_RETURN_IF_ERROR(in.U64("message_index_length", r.message_index_length));
  ROVER_RETURN_IF_ERROR(in.Str("compression", r.compression));
  ROVER_RETURN_IF_ERROR(in.U64("compressed_size", r.compressed_size));
  ROVER_RETURN_IF_ERROR(in.U64("uncompressed_size", r.uncompressed_size));
  if (r.message_start_time > r.message_end_time) {
    return InvalidArgument("message_start_time " + std::to_string(r.message_start_time) +
                           " is after message_end_time " + std::to_string(r.message_end_time));
  }
  return r;
}

Result<Attachment> ParseAttachment(ByteSpan content) {
  In in(content);
  Attachment r;
  ROVER_RETURN_IF_ERROR(in.U64("log_time", r.log_time));
  ROVER_RETURN_IF_ERROR(in.U64("create_time", r.create_time));
  ROVER_RETURN_IF_ERROR(in.Str("name", r.name));
  ROVER_RETURN_IF_ERROR(in.Str("media_type", r.media_type));
  ByteSpan data;
  ROVER_RETURN_IF_ERROR(in.Span64("data", data));
  const std::uint64_t covered = in.pos();
  std::uint32_t crc = 0;
  ROVER_RETURN_IF_ERROR(in.U32("crc", crc));
  if (crc != 0) {
    const std::uint32_t actual = ComputeCrc32(content.first(covered));
    if (actual != crc) {
      return InvalidArgument("crc " + Hex32(crc) + " does not match the content's " +
                             Hex32(actual) + " (the attachment is corrupt)");
    }
  }
  r.data.assign(data.begin(), data.end());
  return r;
}

Result<AttachmentIndex> ParseAttachmentIndex(ByteSpan content) {
  In in(content);
  AttachmentIndex r;
  ROVER_RETURN_IF_ERROR(in.U64("offset", r.offset));
  ROVER_RETURN_IF_ERROR(in.U64("length", r.length));
  ROVER_RETURN_IF_ERROR(in.U64("log_time", r.log_time));
  ROVER_RETURN_IF_ERROR(in.U64("create_time", r.create_time));
  ROVER_RETURN_IF_ERROR(in.U64("data_size", r.data_size));
  ROVER_RETURN_IF_ERROR(in.Str("name", r.name));
  ROVER_RETURN_IF_ERROR(in.Str("media_type", r.media_type));
  return r;
}

Result<Statistics> ParseStatistics(ByteSpan content) {
  In in(content);
  Statistics r;
  ROVER_RETURN_IF_ERROR(in.U64("message_count", r.message_count));
  ROVER_RETURN_IF_ERROR(in.U16("schema_count", r.schema_count));
  ROVER_RETURN_IF_ERROR(in.U32("channel_count", r.channel_count));
  ROVER_RETURN_IF_ERROR(in.U32("attachment_count", r.attachment_count));
  ROVER_RETURN_IF_ERROR(in.U32("metadata_count", r.metadata_count));
  ROVER_RETURN_IF_ERROR(in.U32("chunk_count", r.chunk_count));
  ROVER_RETURN_IF_ERROR(in.U64("message_start_time", r.message_start_time));
  ROVER_RETURN_IF_ERROR(in.U64("message_end_time", r.message_end_time));
  ROVER_RETURN_IF_ERROR(in.Map("channel_message_counts", r.channel_message_counts));
  return r;
}

Result<Metadata> ParseMetadata(ByteSpan content) {
  In in(content);
  Metadata r;
  ROVER_RETURN_IF_ERROR(in.Str("name", r.name));
  ROVER_RETURN_IF_ERROR(in.Map("metadata", r.metadata));
  return r;
}

Result<MetadataIndex> ParseMetadataIndex(ByteSpan content) {
  In in(content);
  MetadataIndex r;
  ROVER_RETURN_IF_ERROR(in.U64("offset", r.offset));
  ROVER_RETURN_IF_ERROR(in.U64("length", r.length));
  ROVER_RETURN_IF_ERROR(in.Str("name", r.name));
  return r;
}

Result<SummaryOffset> ParseSummaryOffset(ByteSpan content) {
  In in(content);
  SummaryOffset r;
  ROVER_RETURN_IF_ERROR(in.U8("group_opcode", r.group_opcode));
  ROVER_RETURN_IF_ERROR(in.U64("group_start", r.group_start));
  ROVER_RETURN_IF_ERROR(in.U64("group_length", r.group_length));
  return r;
}

Result<DataEnd> ParseDataEnd(ByteSpan content) {
  In in(content);
  DataEnd r;
  ROVER_RETURN_IF_ERROR(in.U32("data_section_crc", r.data_section_crc));
  return r;
}

}  // namespace rover::mcap
