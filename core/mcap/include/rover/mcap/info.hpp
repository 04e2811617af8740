#pragma once
/// @file
/// What a recording holds, for `roverctl info FILE`: topics with their types and message
/// counts, the log-time span, chunking and compression, metadata, and whether a size cap cut
/// the recording. Uses the summary; counts messages only when the file has no statistics.

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/mcap/reader.hpp"

namespace rover::mcap {

struct TopicInfo {
  std::string topic;
  std::uint16_t channel_id = 0;
  std::string schema_name;       ///< "" when the channel has no schema
  std::string schema_encoding;   ///< "omgidl", ...
  std::string message_encoding;  ///< "cdr", ...
  std::uint64_t message_count = 0;
};

struct RecordingInfo {
  std::string name;
  std::uint64_t file_size = 0;
  std::string profile;
  std::string library;
  bool indexed = false;  ///< the file has a summary section
  std::uint64_t message_count = 0;
  Timestamp start_time = 0;  ///< earliest log time; 0 when there are no messages
  Timestamp end_time = 0;
  std::vector<TopicInfo> topics;  ///< sorted by topic, then channel id
  std::uint64_t chunk_count = 0;
  std::map<std::string, std::uint64_t> chunks_by_compression;  ///< "none", "zstd", "lz4"
  std::uint64_t chunk_compressed_bytes = 0;
  std::uint64_t chunk_uncompressed_bytes = 0;
  std::uint64_t attachment_count = 0;
  std::vector<std::string> metadata_names;  ///< in file order
  /// Set when the writer's size cap cut the recording: what the notice says.
  std::optional<std::string> truncation;
};

/// The information of an open reader. Counts come from the Statistics record; without one
/// (or without per-channel counts) every message is read and counted.
Result<RecordingInfo> Summarize(const Reader& reader);
/// Opens `path` checking only the summary (Verification::kSummary) and summarizes it.
Result<RecordingInfo> SummarizeFile(const std::string& path);

/// "12.500000000" (seconds.nanoseconds of a log time or duration).
std::string FormatTimestamp(Timestamp t);

/// The text `roverctl info` prints: a few "key: value" lines, then one line per topic.
std::string FormatRecordingInfo(const RecordingInfo& info);

}  // namespace rover::mcap
