#include "rover/mcap/info.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <tuple>

#include "rover/base/format.hpp"
#include "rover/mcap/writer.hpp"

namespace rover::mcap {

Result<RecordingInfo> Summarize(const Reader& reader) {
  RecordingInfo info;
  info.name = reader.name();
  info.file_size = reader.file_size();
  info.profile = reader.header().profile;
  info.library = reader.header().library;
  info.indexed = reader.has_summary();

  std::map<std::uint16_t, std::uint64_t> counts;
  const std::optional<Statistics>& stats = reader.statistics();
  const bool counted_in_file =
      stats && (!stats->channel_message_counts.empty() || stats->message_count == 0);
  if (counted_in_file) {
    counts = stats->channel_message_counts;
    info.message_count = stats->message_count;
    info.start_time = stats->message_start_time;
    info.end_time = stats->message_end_time;
  } else {
    Statistics counted;
    ROVER_RETURN_IF_ERROR(reader.ForEachMessage({}, [&](const MessageEvent& e) {
      CountMessage(counted, e.message.channel_id, e.message.log_time);
      return Status::Ok();
    }));
    counts = counted.channel_message_counts;
    info.message_count = counted.message_count;
    info.start_time = counted.message_start_time;
    info.end_time = counted.message_end_time;
  }

  for (const auto& [id, channel] : reader.channels()) {
    TopicInfo t;
    t.topic = channel.topic;
    t.channel_id = id;
    t.message_encoding = channel.message_encoding;
    const auto schema = reader.schemas().find(channel.schema_id);
    if (schema != reader.schemas().end()) {
      t.schema_name = schema->second.name;
      t.schema_encoding = schema->second.encoding;
    }
    const auto n = counts.find(id);
    t.message_count = n == counts.end() ? 0 : n->second;
    info.topics.push_back(std::move(t));
  }
  std::sort(info.topics.begin(), info.topics.end(), [](const TopicInfo& a, const TopicInfo& b) {
    return std::tie(a.topic, a.channel_id) < std::tie(b.topic, b.channel_id);
  });

  for (const ChunkIndex& c : reader.chunk_indexes()) {
    ++info.chunk_count;
    ++info.chunks_by_compression[c.compression.empty() ? "none" : c.compression];
    info.chunk_compressed_bytes += c.compressed_size;
    info.chunk_uncompressed_bytes += c.uncompressed_size;
  }
  info.attachment_count = reader.attachment_indexes().size();
  for (const MetadataIndex& m : reader.metadata_indexes()) {
    info.metadata_names.push_back(m.name);
    if (m.name != kRecordingMetadataName) continue;
    ROVER_ASSIGN_OR_RETURN(Metadata notice, reader.ReadMetadata(m));
    const auto truncated = notice.metadata.find(kTruncatedKey);
    if (truncated == notice.metadata.end()) continue;
    auto get = [&](const char* key) {
      const auto it = notice.metadata.find(key);
      return it == notice.metadata.end() ? std::string("?") : it->second;
    };
    std::string text = "by the " + truncated->second + " of " + get(kSizeCapKey) + " bytes";
    const std::string first = get(kFirstDroppedKey);
    if (first != "?") {
      char* end = nullptr;
      const unsigned long long t = std::strtoull(first.c_str(), &end, 10);
      text += ": messages from log time " +
              (end != nullptr && *end == '\0' ? FormatTimestamp(t) + " s" : first) +
              " on were not recorded (" + get(kDroppedKey) + " refused)";
    }
    info.truncation = text;
  }
  return info;
}

Result<RecordingInfo> SummarizeFile(const std::string& path) {
  ReaderOptions options;
  options.verification = Verification::kSummary;
  ROVER_ASSIGN_OR_RETURN(std::unique_ptr<Reader> reader, Reader::Open(path, options));
  return Summarize(*reader);
}

std::string FormatTimestamp(Timestamp t) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%llu.%09llu", static_cast<unsigned long long>(t / 1000000000u),
                static_cast<unsigned long long>(t % 1000000000u));
  return buf;
}

namespace {

std::string Megabytes(std::uint64_t bytes) {
  return FormatNumber(static_cast<double>(bytes) / 1e6, 4) + " MB";
}

std::string Pad(std::string s, std::size_t width) {
  if (s.size() < width) s.append(width - s.size(), ' ');
  return s;
}

}  // namespace

std::string FormatRecordingInfo(const RecordingInfo& info) {
  std::string out;
  auto line = [&](const char* key, const std::string& value) {
    out += Pad(std::string(key) + ":", 14) + value + "\n";
  };
  line("file", info.name + " (" + Megabytes(info.file_size) + ", " +
                   (info.indexed ? "indexed" : "not indexed") + ")");
  line("library", info.library.empty() ? "-" : info.library);
  if (!info.profile.empty()) line("profile", info.profile);
  line("messages", std::to_string(info.message_count) + " on " +
                       std::to_string(info.topics.size()) + " topics");
  if (info.message_count > 0) {
    line("start", FormatTimestamp(info.start_time) + " s");
    line("end", FormatTimestamp(info.end_time) + " s");
    line("duration", FormatTimestamp(info.end_time - info.start_time) + " s");
  }
  if (info.chunk_count > 0) {
    std::string by;
    for (const auto& [name, n] : info.chunks_by_compression) {
      by += (by.empty() ? "" : ", ") + name + " " + std::to_string(n);
    }
    std::string ratio;
    if (info.chunk_uncompressed_bytes > 0) {
      ratio = " (" +
              FormatNumber(100.0 * static_cast<double>(info.chunk_compressed_bytes) /
                               static_cast<double>(info.chunk_uncompressed_bytes),
                           3) +
              " %)";
    }
    line("chunks", std::to_string(info.chunk_count) + " (" + by + "), " +
                       Megabytes(info.chunk_uncompressed_bytes) + " stored in " +
                       Megabytes(info.chunk_compressed_bytes) + ratio);
  }
  if (info.attachment_count > 0) line("attachments", std::to_string(info.attachment_count));
  if (!info.metadata_names.empty()) {
    std::string names;
    for (const std::string& n : info.metadata_names) names += (names.empty() ? "" : ", ") + n;
    line("metadata", names);
  }
  if (info.truncation) line("truncated", *info.truncation);
  if (info.topics.empty()) return out;

  out += "topics:\n";
  std::size_t topic_w = 0;
  std::size_t count_w = 0;
  std::size_t type_w = 0;
  for (const TopicInfo& t : info.topics) {
    topic_w = std::max(topic_w, t.topic.size());
    count_w = std::max(count_w, std::to_string(t.message_count).size());
    type_w = std::max(type_w, t.schema_name.empty() ? 1 : t.schema_name.size());
  }
  for (const TopicInfo& t : info.topics) {
    const std::string count = std::to_string(t.message_count);
    out += "  " + Pad(t.topic, topic_w) + "  " + std::string(count_w - count.size(), ' ') + count +
           " msgs  " + Pad(t.schema_name.empty() ? "-" : t.schema_name, type_w) + "  " +
           t.message_encoding + (t.schema_encoding.empty() ? "" : "/" + t.schema_encoding) + "\n";
  }
  return out;
}

}  // namespace rover::mcap
