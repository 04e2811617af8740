#include "rover/recording/record_options.hpp"

#include <algorithm>

#include "rover/base/params.hpp"

namespace rover::recording {

Status RecordOptions::Validate() const {
  ROVER_RETURN_IF_ERROR(topics.Validate());
  if (size_cap_mb != 0 && !(size_cap_mb >= 0.01 && size_cap_mb <= 1e6)) {
    return InvalidArgument("size_cap_mb: " + std::to_string(size_cap_mb) +
                           " is not 0 (no cap) or in [0.01, 1000000] MB");
  }
  return Status::Ok();
}

mcap::WriterOptions RecordOptions::WriterOptions() const {
  mcap::WriterOptions o;
  o.compression = compression;
  o.size_cap_bytes = static_cast<std::uint64_t>(size_cap_mb * 1e6);
  return o;
}

Result<mcap::Compression> ParseCompression(std::string_view name) {
  if (name == "zstd") return mcap::Compression::kZstd;
  if (name == "lz4") return mcap::Compression::kLz4;
  if (name == "none") return mcap::Compression::kNone;
  return InvalidArgument("compression '" + std::string(name) + "' is not one of: zstd, lz4, none");
}

std::string CompressionText(mcap::Compression compression) {
  switch (compression) {
    case mcap::Compression::kZstd: return "zstd";
    case mcap::Compression::kLz4: return "lz4";
    case mcap::Compression::kNone: return "none";
  }
  return "?";
}

namespace {
Result<std::vector<std::string>> Patterns(const YAML::Node& n, const std::string& key,
                                          const yaml::FileErrors& err,
                                          const std::vector<std::string>& known) {
  std::vector<std::string> out;
  if (n.IsScalar()) {
    out.push_back(n.Scalar());
  } else if (n.IsSequence()) {
    for (const auto& item : n) {
      if (!item.IsScalar()) return err.At(item, key + ": each entry is a topic pattern");
      out.push_back(item.Scalar());
    }
  } else {
    return err.At(n, key + ": expected a topic pattern or a list of them");
  }
  TopicFilter check;
  check.include = out;
  if (Status s = check.Validate(); !s.ok()) {
    return err.At(n, key + ": " + s.message().substr(s.message().find(": ") + 2));
  }
  if (!known.empty()) {
    for (const auto& g : out) {
      const bool any = std::any_of(known.begin(), known.end(),
                                   [&](const std::string& t) { return GlobMatch(g, t); });
      if (!any) {
        return err.At(n, key + ": '" + g + "' matches no topic" + DidYouMean(g, known) +
                             " (docs/topics.md lists them)");
      }
    }
  }
  return out;
}
}  // namespace

Result<RecordOptions> ParseRecordOptions(const YAML::Node& node, const std::string& where,
                                         const yaml::FileErrors& err, const RecordOptions& defaults,
                                         const std::vector<std::string>& known_topics) {
  RecordOptions o = defaults;
  if (node.IsScalar()) {
    const std::string v = node.Scalar();
    if (v == "true" || v == "yes" || v == "on") {
      o.enabled = true;
      return o;
    }
    if (v == "false" || v == "no" || v == "off") {
      o.enabled = false;
      return o;
    }
    return err.At(node, where + ": expected true, false or a map of record settings, got '" +
                            v + "'");
  }
  if (!node.IsMap()) return err.At(node, where + ": expected true, false or a map");
  ROVER_RETURN_IF_ERROR(yaml::CheckKeys(
      node, where, {"path", "topics", "exclude", "size_cap_mb", "compression"}, err));
  o.enabled = true;
  if (const auto p = node["path"]) {
    if (!p.IsScalar() || p.Scalar().empty()) return err.At(p, where + ".path: expected a file name");
    o.path = p.Scalar();
  }
  if (const auto t = node["topics"]) {
    ROVER_ASSIGN_OR_RETURN(o.topics.include, Patterns(t, where + ".topics", err, known_topics));
  }
  if (const auto x = node["exclude"]) {
    ROVER_ASSIGN_OR_RETURN(o.topics.exclude, Patterns(x, where + ".exclude", err, known_topics));
  }
  bool has_cap = false;
  double cap = 0;
  ROVER_RETURN_IF_ERROR(yaml::OptionalNumber(node, "size_cap_mb", where, 0, 1e6, err, &cap, &has_cap));
  if (has_cap) {
    if (cap != 0 && cap < 0.01) {
      return err.At(node["size_cap_mb"], where + ".size_cap_mb: " + yaml::ScalarText(node["size_cap_mb"]) +
                                             " is below 0.01 MB (0 means no cap)");
    }
    o.size_cap_mb = cap;
  }
  if (const auto c = node["compression"]) {
    ROVER_ASSIGN_OR_RETURN(const std::string name,
                           yaml::OneOf(c, where + ".compression", {"zstd", "lz4", "none"}, err));
    ROVER_ASSIGN_OR_RETURN(o.compression, ParseCompression(name));
  }
  return o;
}

}  // namespace rover::recording
