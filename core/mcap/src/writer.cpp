#include "rover/mcap/writer.hpp"

#include <algorithm>
#include <limits>
#include <utility>

#include "rover/base/check.hpp"
#include "rover/base/range_check.hpp"
#include "rover/mcap/crc32.hpp"

namespace rover::mcap {
namespace {

constexpr std::uint64_t kMinSizeCap = 4096;
constexpr std::uint64_t kMaxChunkBytes = std::uint64_t{1} << 30;
constexpr std::size_t kMaxIds = 65535;
/// Summary groups this writer may write (Schema, Channel, Statistics, ChunkIndex,
/// AttachmentIndex, MetadataIndex), each with one Summary Offset record.
constexpr std::uint64_t kSummaryGroups = 6;

/// The notice Close() writes when the cap cut the recording.
Metadata TruncationNotice(std::uint64_t cap, Timestamp first_dropped, std::uint64_t dropped) {
  Metadata m;
  m.name = kRecordingMetadataName;
  m.metadata[kTruncatedKey] = "size_cap";
  m.metadata[kSizeCapKey] = std::to_string(cap);
  m.metadata[kFirstDroppedKey] = std::to_string(first_dropped);
  m.metadata[kDroppedKey] = std::to_string(dropped);
  return m;
}

/// The notice's largest possible record and index sizes (every number at 20 digits).
std::uint64_t TruncationNoticeReserve() {
  const auto max = std::numeric_limits<std::uint64_t>::max();
  const Metadata m = TruncationNotice(max, max, max);
  return RecordSize(m) + RecordSize(MetadataIndex{0, 0, m.name});
}

}  // namespace

// ---- options ------------------------------------------------------------------------------------

Status WriterOptions::Validate() const {
  const LevelRange r = CompressionLevels(compression);
  ROVER_RETURN_IF_ERROR(CheckIntRange("compression_level", compression_level, r.lo, r.hi));
  ROVER_RETURN_IF_ERROR(CheckIntRange(
      "chunk_bytes",
      static_cast<long long>(std::min<std::uint64_t>(chunk_bytes, kMaxChunkBytes + 1)), 1,
      static_cast<long long>(kMaxChunkBytes)));
  if (size_cap_bytes != 0 && size_cap_bytes < kMinSizeCap) {
    return InvalidArgument("size_cap_bytes = " + std::to_string(size_cap_bytes) +
                           " is below the smallest cap, " + std::to_string(kMinSizeCap) +
                           " (0 means no cap)");
  }
  return Status::Ok();
}

void WriterOptions::BindParams(ParamBinder<WriterOptions>& b) {
  b.BindEnum(
      "compression", &WriterOptions::compression,
      {{"none", Compression::kNone}, {"zstd", Compression::kZstd}, {"lz4", Compression::kLz4}},
      "chunk compression");
  b.Bind("compression_level", &WriterOptions::compression_level, "",
         "0 = the library's default; zstd -7..22, lz4 0..12");
  b.Bind("chunk_bytes", &WriterOptions::chunk_bytes, "bytes",
         "a chunk is closed when its uncompressed records reach this size")
      .Range(1, static_cast<double>(kMaxChunkBytes));
  b.Bind("size_cap_bytes", &WriterOptions::size_cap_bytes, "bytes",
         "the file never grows past this size; 0 = no cap")
      .Min(0);
}

// ---- writer -------------------------------------------------------------------------------------

Result<std::unique_ptr<Writer>> Writer::Create(const std::string& path,
                                               const WriterOptions& options) {
  ROVER_RETURN_IF_ERROR(options.Validate().WithPrefix(path + ": writer options"));
  ROVER_ASSIGN_OR_RETURN(std::unique_ptr<FileSink> sink, FileSink::Create(path));
  return Create(std::move(sink), options);
}

Result<std::unique_ptr<Writer>> Writer::Create(std::unique_ptr<Sink> sink,
                                               const WriterOptions& options) {
  ROVER_DEMAND(sink != nullptr);
  ROVER_RETURN_IF_ERROR(options.Validate().WithPrefix(sink->name() + ": writer options"));
  std::unique_ptr<Writer> w(new Writer(std::move(sink), options));
  ROVER_RETURN_IF_ERROR(w->Start());
  return w;
}

Writer::Writer(std::unique_ptr<Sink> sink, const WriterOptions& options)
    : sink_(std::move(sink)),
      options_(options),
      compressor_(options.chunked ? options.compression : Compression::kNone,
                  options.chunked ? options.compression_level : 0) {}

Writer::~Writer() {
  if (!closed_) (void)Close();
}

Status Writer::Start() {
  Bytes b(kMagic.begin(), kMagic.end());
  AppendRecord(b, Header{options_.profile, options_.library});
  const std::uint64_t empty = b.size() + ProjectedSize({});
  if (options_.size_cap_bytes != 0 && empty > options_.size_cap_bytes) {
    closed_ = true;
    (void)sink_->Close();
    return InvalidArgument(
        sink_->name() + ": size_cap_bytes = " + std::to_string(options_.size_cap_bytes) +
        " is smaller than an empty recording (" + std::to_string(empty) + " bytes)");
  }
  return Emit(b);
}

Status Writer::Emit(ByteSpan bytes) {
  if (!failed_.ok()) return failed_;
  Status s = sink_->Write(bytes);
  if (!s.ok()) {
    failed_ = s;
    return s;
  }
  if (data_open_) data_crc_.Update(bytes);
  offset_ += bytes.size();
  stats_.bytes_written = offset_;
  return Status::Ok();
}

Status Writer::CheckWritable() const {
  if (closed_) return FailedPrecondition(sink_->name() + ": the writer is closed");
  return failed_;
}

std::uint64_t Writer::ProjectedSize(const Extra& extra) const {
  std::uint64_t n = offset_ + extra.data_bytes;
  const std::string_view compression = CompressionName(compressor_.compression());
  std::uint64_t summary = schema_bytes_ + channel_bytes_ + index_bytes_ + extra.summary_bytes +
                          StatisticsRecordSize(channels_.size()) +
                          kSummaryGroups * kSummaryOffsetRecordBytes;
  if (options_.chunked && (!chunk_.empty() || extra.chunk_bytes > 0)) {
    std::uint64_t index_bytes = chunk_index_bytes_;
    std::uint64_t indexed_channels = chunk_index_.size();
    if (extra.message_channel) {
      if (chunk_index_.contains(*extra.message_channel)) {
        index_bytes += 16;
      } else {
        index_bytes += MessageIndexRecordSize(1);
        ++indexed_channels;
      }
    }
    // Stored compressed only when that is smaller, so the uncompressed size bounds the chunk.
    n += ChunkRecordSize(chunk_.size() + extra.chunk_bytes, compression) + index_bytes;
    summary += ChunkIndexRecordSize(indexed_channels, compression);
  }
  if (options_.size_cap_bytes != 0) n += TruncationNoticeReserve();
  n += kDataEndRecordBytes;
  if (options_.summary) n += summary;
  return n + kFooterRecordBytes + kMagic.size();
}

Status Writer::Admit(const Extra& extra, const std::string& what) {
  if (options_.size_cap_bytes == 0 || ProjectedSize(extra) <= options_.size_cap_bytes) {
    return Status::Ok();
  }
  if (!chunk_.empty()) {
    ROVER_RETURN_IF_ERROR(FlushChunk());  // its real, compressed size may leave room
    if (ProjectedSize(extra) <= options_.size_cap_bytes) return Status::Ok();
  }
  return OutOfRange(sink_->name() + ": size cap of " + std::to_string(options_.size_cap_bytes) +
                    " bytes reached: " + what + " not written");
}

Status Writer::AddDefinition(const Bytes& record, std::uint64_t summary_extra,
                             const std::string& what) {
  Extra e;
  (options_.chunked ? e.chunk_bytes : e.data_bytes) = record.size();
  e.summary_bytes = record.size() + summary_extra;  // the summary repeats every definition
  const Status admitted = Admit(e, what);
  // A definition refused by the cap ends the recording: its messages could not follow.
  if (admitted.code() == StatusCode::kOutOfRange) capped_ = true;
  ROVER_RETURN_IF_ERROR(admitted);
  if (options_.chunked) {
    chunk_.insert(chunk_.end(), record.begin(), record.end());
    return Status::Ok();
  }
  return Emit(record);
}

Result<std::uint16_t> Writer::AddSchema(const std::string& name, const std::string& encoding,
                                        ByteSpan data) {
  ROVER_RETURN_IF_ERROR(CheckWritable());
  Schema s{0, name, encoding, Bytes(data.begin(), data.end())};
  for (const Schema& known : schemas_) {
    if (known.name == s.name && known.encoding == s.encoding && known.data == s.data) {
      return known.id;
    }
  }
  if (schemas_.size() >= kMaxIds) {
    return InvalidArgument(sink_->name() + ": schema '" + name +
                           "': all 65535 schema ids are used");
  }
  s.id = static_cast<std::uint16_t>(schemas_.size() + 1);
  Bytes record;
  AppendRecord(record, s);
  ROVER_RETURN_IF_ERROR(AddDefinition(record, 0, "schema '" + name + "'"));
  schema_bytes_ += record.size();
  schemas_.push_back(std::move(s));
  return schemas_.back().id;
}

Result<std::uint16_t> Writer::AddChannel(const std::string& topic,
                                         const std::string& message_encoding,
                                         std::uint16_t schema_id, const StringMap& metadata) {
  ROVER_RETURN_IF_ERROR(CheckWritable());
  if (schema_id > schemas_.size()) {
    return InvalidArgument(sink_->name() + ": channel '" + topic + "': unknown schema id " +
                           std::to_string(schema_id));
  }
  Channel c{0, schema_id, topic, message_encoding, metadata};
  for (const Channel& known : channels_) {
    if (known.schema_id == c.schema_id && known.topic == c.topic &&
        known.message_encoding == c.message_encoding && known.metadata == c.metadata) {
      return known.id;
    }
  }
  if (channels_.size() >= kMaxIds) {
    return InvalidArgument(sink_->name() + ": channel '" + topic +
                           "': all 65535 channel ids are used");
  }
  c.id = static_cast<std::uint16_t>(channels_.size() + 1);
  Bytes record;
  AppendRecord(record, c);
  // 10 more summary bytes: the channel's entry in the Statistics' channel counts.
  ROVER_RETURN_IF_ERROR(AddDefinition(record, 10, "channel '" + topic + "'"));
  channel_bytes_ += record.size();
  statistics_.channel_message_counts[c.id] = 0;
  channels_.push_back(std::move(c));
  return channels_.back().id;
}

Status Writer::WriteMessage(const MessageView& m) {
  ROVER_RETURN_IF_ERROR(CheckWritable());
  if (m.channel_id == 0 || m.channel_id > channels_.size()) {
    return InvalidArgument(sink_->name() + ": message on unknown channel " +
                           std::to_string(m.channel_id));
  }
  const Channel& channel = channels_[m.channel_id - 1];
  const std::uint64_t size = MessageRecordSize(m.data.size());
  if (capped_) {
    ++stats_.dropped_messages;
    return OutOfRange(sink_->name() + ": size cap of " + std::to_string(options_.size_cap_bytes) +
                      " bytes reached earlier: message on '" + channel.topic + "' not written");
  }
  Extra e;
  if (options_.chunked) {
    e.chunk_bytes = size;
    e.message_channel = m.channel_id;
  } else {
    e.data_bytes = size;
  }
  Status admitted =
      Admit(e, "message on '" + channel.topic + "' at log time " + std::to_string(m.log_time));
  if (admitted.code() == StatusCode::kOutOfRange) {
    capped_ = true;
    first_dropped_ = m.log_time;
    ++stats_.dropped_messages;
  }
  ROVER_RETURN_IF_ERROR(admitted);

  if (options_.chunked) {
    MessageIndex& index = chunk_index_[m.channel_id];
    if (index.records.empty()) {
      index.channel_id = m.channel_id;
      chunk_index_bytes_ += MessageIndexRecordSize(0);
    }
    index.records.emplace_back(m.log_time, chunk_.size());
    chunk_index_bytes_ += 16;
    AppendRecord(chunk_, m);
    if (!chunk_has_messages_) {
      chunk_start_ = chunk_end_ = m.log_time;
      chunk_has_messages_ = true;
    }
    chunk_start_ = std::min(chunk_start_, m.log_time);
    chunk_end_ = std::max(chunk_end_, m.log_time);
  } else {
    scratch_.clear();
    AppendRecord(scratch_, m);
    ROVER_RETURN_IF_ERROR(Emit(scratch_));
  }

  CountMessage(statistics_, m.channel_id, m.log_time);
  ++stats_.messages;

  if (options_.chunked && chunk_.size() >= options_.chunk_bytes) return FlushChunk();
  return Status::Ok();
}

Status Writer::FlushChunk() {
  if (chunk_.empty()) return Status::Ok();
  ChunkView view;
  view.message_start_time = chunk_has_messages_ ? chunk_start_ : 0;
  view.message_end_time = chunk_has_messages_ ? chunk_end_ : 0;
  view.uncompressed_size = chunk_.size();
  view.uncompressed_crc = ComputeCrc32(chunk_);
  ByteSpan records = chunk_;
  if (compressor_.compression() != Compression::kNone) {
    Status s = compressor_.Compress(chunk_, compressed_);
    if (!s.ok()) {
      failed_ = s.WithPrefix(sink_->name());
      return failed_;
    }
    // Incompressible data (e.g. already-compressed images) is stored as it is.
    if (compressed_.size() < chunk_.size()) {
      view.compression = std::string(CompressionName(compressor_.compression()));
      records = compressed_;
    }
  }

  // The record's prefix and fixed fields, then the records themselves without another copy.
  ChunkIndex index;
  index.chunk_start_offset = offset_;
  scratch_.clear();
  AppendRecord(scratch_, view);  // with empty records: patch both lengths
  const std::uint64_t content = scratch_.size() - kRecordPrefixBytes + records.size();
  for (int i = 0; i < 8; ++i) {
    scratch_[1 + i] = static_cast<std::uint8_t>(content >> (8 * i));
    scratch_[scratch_.size() - 8 + i] = static_cast<std::uint8_t>(records.size() >> (8 * i));
  }
  ROVER_RETURN_IF_ERROR(Emit(scratch_));
  ROVER_RETURN_IF_ERROR(Emit(records));
  index.chunk_length = offset_ - index.chunk_start_offset;

  const std::uint64_t index_start = offset_;
  for (const auto& [channel, message_index] : chunk_index_) {
    index.message_index_offsets[channel] = offset_;
    scratch_.clear();
    AppendRecord(scratch_, message_index);
    ROVER_RETURN_IF_ERROR(Emit(scratch_));
  }
  index.message_index_length = offset_ - index_start;
  index.message_start_time = view.message_start_time;
  index.message_end_time = view.message_end_time;
  index.compression = view.compression;
  index.compressed_size = records.size();
  index.uncompressed_size = view.uncompressed_size;
  index_bytes_ += ChunkIndexRecordSize(index.message_index_offsets.size(), index.compression);
  chunk_indexes_.push_back(std::move(index));

  ++statistics_.chunk_count;
  ++stats_.chunks;
  stats_.uncompressed_chunk_bytes += view.uncompressed_size;
  stats_.compressed_chunk_bytes += records.size();
  chunk_.clear();
  chunk_index_.clear();
  chunk_index_bytes_ = 0;
  chunk_has_messages_ = false;
  return Status::Ok();
}

Status Writer::WriteMetadata(const Metadata& metadata) {
  ROVER_RETURN_IF_ERROR(CheckWritable());
  MetadataIndex index{0, RecordSize(metadata), metadata.name};
  Extra e;
  e.data_bytes = index.length;
  e.summary_bytes = RecordSize(index);
  ROVER_RETURN_IF_ERROR(Admit(e, "metadata '" + metadata.name + "'"));
  index.offset = offset_;
  scratch_.clear();
  AppendRecord(scratch_, metadata);
  ROVER_RETURN_IF_ERROR(Emit(scratch_));
  index_bytes_ += RecordSize(index);
  metadata_indexes_.push_back(std::move(index));
  ++statistics_.metadata_count;
  return Status::Ok();
}

Status Writer::WriteAttachment(const Attachment& attachment) {
  ROVER_RETURN_IF_ERROR(CheckWritable());
  Bytes record;
  AppendRecord(record, attachment);
  AttachmentIndex index{0,
                        record.size(),
                        attachment.log_time,
                        attachment.create_time,
                        attachment.data.size(),
                        attachment.name,
                        attachment.media_type};
  Extra e;
  e.data_bytes = record.size();
  e.summary_bytes = RecordSize(index);
  ROVER_RETURN_IF_ERROR(Admit(e, "attachment '" + attachment.name + "'"));
  index.offset = offset_;
  ROVER_RETURN_IF_ERROR(Emit(record));
  index_bytes_ += RecordSize(index);
  attachment_indexes_.push_back(std::move(index));
  ++statistics_.attachment_count;
  return Status::Ok();
}

Status Writer::Close() {
  if (closed_) return close_status_;
  Status s = failed_;
  if (s.ok()) s = FlushChunk();
  if (s.ok() && capped_) {
    // Within the reserve ProjectedSize kept for it: the cap check would refuse nothing here.
    const Metadata notice =
        TruncationNotice(options_.size_cap_bytes, first_dropped_, stats_.dropped_messages);
    MetadataIndex index{offset_, RecordSize(notice), notice.name};
    scratch_.clear();
    AppendRecord(scratch_, notice);
    s = Emit(scratch_);
    index_bytes_ += RecordSize(index);
    metadata_indexes_.push_back(std::move(index));
    ++statistics_.metadata_count;
  }
  if (s.ok()) s = WriteSummaryAndFooter();
  closed_ = true;
  // After a failure the file stays without its footer: readers reject it as incomplete.
  const Status closed = sink_->Close();
  if (s.ok()) s = closed;
  if (s.ok() && options_.size_cap_bytes != 0) {
    ROVER_DEMAND_MSG(offset_ <= options_.size_cap_bytes, "the size cap arithmetic is wrong");
  }
  close_status_ = s;
  return s;
}

Status Writer::WriteSummaryAndFooter() {
  Bytes b;
  AppendRecord(b, DataEnd{data_crc_.Value()});
  data_open_ = false;
  ROVER_RETURN_IF_ERROR(Emit(b));

  Footer footer;
  Bytes summary;
  if (options_.summary) {
    footer.summary_start = offset_;
    std::vector<SummaryOffset> groups;
    auto group = [&](Opcode op, auto&& append_all) {
      const std::size_t from = summary.size();
      append_all();
      if (summary.size() > from) {
        groups.push_back(
            {static_cast<std::uint8_t>(op), footer.summary_start + from, summary.size() - from});
      }
    };
    group(Opcode::kSchema, [&] {
      for (const Schema& s : schemas_) AppendRecord(summary, s);
    });
    group(Opcode::kChannel, [&] {
      for (const Channel& c : channels_) AppendRecord(summary, c);
    });
    group(Opcode::kStatistics, [&] {
      Statistics st = statistics_;
      st.schema_count = static_cast<std::uint16_t>(schemas_.size());
      st.channel_count = static_cast<std::uint32_t>(channels_.size());
      AppendRecord(summary, st);
    });
    group(Opcode::kChunkIndex, [&] {
      for (const ChunkIndex& c : chunk_indexes_) AppendRecord(summary, c);
    });
    group(Opcode::kAttachmentIndex, [&] {
      for (const AttachmentIndex& a : attachment_indexes_) AppendRecord(summary, a);
    });
    group(Opcode::kMetadataIndex, [&] {
      for (const MetadataIndex& m : metadata_indexes_) AppendRecord(summary, m);
    });
    footer.summary_offset_start = footer.summary_start + summary.size();
    for (const SummaryOffset& g : groups) AppendRecord(summary, g);

    // The summary CRC covers the summary and the footer up to its summary_offset_start field.
    Bytes prefix;
    AppendRecord(prefix, footer);
    Crc32 crc;
    crc.Update(summary);
    crc.Update(ByteSpan(prefix).first(kFooterRecordBytes - 4));
    footer.summary_crc = crc.Value();
  }
  summary.reserve(summary.size() + kFooterRecordBytes + kMagic.size());
  AppendRecord(summary, footer);
  summary.insert(summary.end(), kMagic.begin(), kMagic.end());
  return Emit(summary);
}

}  // namespace rover::mcap
