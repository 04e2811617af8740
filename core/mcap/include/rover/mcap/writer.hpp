#pragma once
/// @file
/// The MCAP writer: schemas, channels and messages into compressed, indexed chunks, then a
/// summary (Schema, Channel, Statistics, ChunkIndex, AttachmentIndex, MetadataIndex groups, each
/// located by a SummaryOffset record) and the Footer with the summary's CRC. See README.md.
///
///   ROVER_ASSIGN_OR_RETURN(auto w, mcap::Writer::Create("run.mcap", options));
///   ROVER_ASSIGN_OR_RETURN(auto schema, w->AddSchema("rover::dl::PoseEstimate", "omgidl", idl));
///   ROVER_ASSIGN_OR_RETURN(auto channel, w->AddChannel("dl/pose", "cdr", schema));
///   Status s = w->WriteMessage({channel, seq, log_time, publish_time, cdr_bytes});
///   if (s.code() == StatusCode::kOutOfRange) { /* the size cap: stop recording */ }
///   ROVER_RETURN_IF_ERROR(w->Close());
///
/// Errors are sticky: after a sink failure (disk full) every call returns that error and Close()
/// leaves the file without its footer, so no reader takes it for complete. The size cap is not
/// an error of the file: once a message would push the closed file past `size_cap_bytes`, that
/// message and all later ones are refused (kOutOfRange), and Close() writes a valid file that
/// says it was cut (Metadata "rover_recording", truncated = "size_cap").

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/param_binder.hpp"
#include "rover/base/status.hpp"
#include "rover/mcap/compression.hpp"
#include "rover/mcap/crc32.hpp"
#include "rover/mcap/io.hpp"
#include "rover/mcap/records.hpp"

namespace rover::mcap {

/// The Metadata record this library writes about the recording itself, and its keys.
inline constexpr const char* kRecordingMetadataName = "rover_recording";
inline constexpr const char* kTruncatedKey = "truncated";  ///< "size_cap" when cut
inline constexpr const char* kSizeCapKey = "size_cap_bytes";
inline constexpr const char* kFirstDroppedKey = "first_dropped_log_time";  ///< ns
inline constexpr const char* kDroppedKey = "dropped_messages";

/// Well-known encodings this stack writes (the MCAP registry's names).
inline constexpr const char* kMessageEncodingCdr = "cdr";
inline constexpr const char* kSchemaEncodingOmgIdl = "omgidl";

struct WriterOptions {
  /// Header.profile. "" (no well-known profile): "ros2" would promise ros2msg/ros2idl schemas
  /// and QoS metadata that CDR over plain DDS with OMG IDL schemas does not have.
  std::string profile;
  /// Header.library.
  std::string library = "rover_mcap 1";
  Compression compression = Compression::kZstd;
  /// 0: the library's default; else inside CompressionLevels(compression).
  int compression_level = 0;
  /// A chunk is closed once its uncompressed records reach this many bytes [bytes]. A message
  /// larger than this gets a chunk of its own.
  std::uint64_t chunk_bytes = 4u << 20;
  /// The closed file never exceeds this many bytes; 0 = no cap [bytes].
  std::uint64_t size_cap_bytes = 0;
  /// false writes Schema, Channel and Message records straight into the data section (no
  /// chunks, no compression, no message or chunk indexes): for tests and simple tools.
  bool chunked = true;
  /// false ends the file with DataEnd and a Footer of zeros (no summary): for tests.
  bool summary = true;

  /// size_cap_bytes 0 or >= 4096; chunk_bytes in [1, 1 GiB]; compression_level in range.
  Status Validate() const;
  /// Parameters: compression (none|zstd|lz4), compression_level, chunk_bytes, size_cap_bytes.
  static void BindParams(ParamBinder<WriterOptions>& b);
};

/// What the writer has done so far.
struct WriterStats {
  std::uint64_t bytes_written = 0;  ///< handed to the sink (the file offset)
  std::uint64_t messages = 0;
  std::uint64_t chunks = 0;
  std::uint64_t uncompressed_chunk_bytes = 0;  ///< records of all closed chunks, uncompressed
  std::uint64_t compressed_chunk_bytes = 0;    ///< and as stored
  std::uint64_t dropped_messages = 0;          ///< refused after the size cap was reached
};

class Writer {
 public:
  /// Creates (truncates) `path` and writes the magic and Header.
  static Result<std::unique_ptr<Writer>> Create(const std::string& path,
                                                const WriterOptions& options);
  static Result<std::unique_ptr<Writer>> Create(std::unique_ptr<Sink> sink,
                                                const WriterOptions& options);
  /// Closes the file if Close() was not called; its status is then lost (call Close()).
  ~Writer();
  Writer(const Writer&) = delete;
  Writer& operator=(const Writer&) = delete;

  /// A schema (ids from 1); an identical schema added again returns the first one's id.
  Result<std::uint16_t> AddSchema(const std::string& name, const std::string& encoding,
                                  ByteSpan data);
  /// A channel (ids from 1) on `schema_id` (0 = none; else an id AddSchema returned). An
  /// identical channel added again returns the first one's id. The Schema and Channel records go
  /// into the data stream now (inside the open chunk), so they precede every message using them.
  Result<std::uint16_t> AddChannel(const std::string& topic, const std::string& message_encoding,
                                   std::uint16_t schema_id, const StringMap& metadata = {});
  /// One message; `data` is copied. kInvalidArgument for an unknown channel; kOutOfRange once
  /// the size cap is reached (capped() is then true and stays so).
  Status WriteMessage(const MessageView& message);
  /// A Metadata record in the data section, indexed in the summary. Refused (kOutOfRange) only if
  /// it does not fit under the size cap.
  Status WriteMetadata(const Metadata& metadata);
  /// An Attachment record (never inside a chunk), indexed in the summary. As WriteMetadata.
  Status WriteAttachment(const Attachment& attachment);
  /// Writes the last chunk, DataEnd, the summary and the Footer, and closes the sink. Returns the
  /// first error the writer met, if any. A second call returns the same status.
  Status Close();

  bool capped() const { return capped_; }
  const WriterStats& stats() const { return stats_; }
  const std::string& name() const { return sink_->name(); }

 private:
  Writer(std::unique_ptr<Sink> sink, const WriterOptions& options);
  Status Start();
  /// Writes bytes to the sink (and the data CRC while the data section is open).
  Status Emit(ByteSpan bytes);
  /// Appends a whole Schema or Channel record to the open chunk (or the data section) if it
  /// fits under the cap, with `summary_extra` more summary bytes than its copy there.
  Status AddDefinition(const Bytes& record, std::uint64_t summary_extra, const std::string& what);
  Status FlushChunk();
  /// What an operation adds, for the size-cap arithmetic.
  struct Extra {
    std::uint64_t chunk_bytes = 0;                 ///< records into the open chunk
    std::optional<std::uint16_t> message_channel;  ///< a message of this channel among them
    std::uint64_t data_bytes = 0;                  ///< records straight into the data section
    std::uint64_t summary_bytes = 0;               ///< records into the summary
  };
  /// The size of the file if it were closed after `extra` (an upper bound: the open chunk is
  /// counted uncompressed, the truncation notice and every summary group are reserved).
  std::uint64_t ProjectedSize(const Extra& extra) const;
  /// Ok if `extra` fits under the cap, flushing the open chunk first if that makes it fit;
  /// kOutOfRange if it does not fit; the sink's error if the flush fails.
  Status Admit(const Extra& extra, const std::string& what);
  Status CapStatus(const std::string& what) const;
  Status CheckWritable() const;
  Status WriteSummaryAndFooter();

  std::unique_ptr<Sink> sink_;
  WriterOptions options_;
  Compressor compressor_;
  Status failed_;  ///< the first sink or library error (sticky)
  bool closed_ = false;
  Status close_status_;
  bool capped_ = false;
  Timestamp first_dropped_ = 0;

  std::uint64_t offset_ = 0;  ///< bytes written
  Crc32 data_crc_;
  bool data_open_ = true;

  std::vector<Schema> schemas_;     ///< id = index + 1
  std::vector<Channel> channels_;   ///< id = index + 1
  std::uint64_t schema_bytes_ = 0;  ///< their records' sizes (repeated in the summary)
  std::uint64_t channel_bytes_ = 0;

  // The open chunk.
  Bytes chunk_;
  Timestamp chunk_start_ = 0;
  Timestamp chunk_end_ = 0;
  bool chunk_has_messages_ = false;
  std::map<std::uint16_t, MessageIndex> chunk_index_;  ///< per channel, this chunk
  std::uint64_t chunk_index_bytes_ = 0;                ///< Message Index records it will need
  Bytes compressed_;
  Bytes scratch_;

  std::vector<ChunkIndex> chunk_indexes_;
  std::vector<AttachmentIndex> attachment_indexes_;
  std::vector<MetadataIndex> metadata_indexes_;
  std::uint64_t index_bytes_ = 0;  ///< their records' sizes
  Statistics statistics_;
  WriterStats stats_;
};

}  // namespace rover::mcap
