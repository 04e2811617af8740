#pragma once
/// @file
/// What a recording takes and how it is written, as the compose file (`x-rover.record`), the
/// scenario file (`record`) and `roverctl record` give it:
///
///   record:                  # or `record: false` (off) / `record: true` (all defaults)
///     path: run.mcap         # the file (compose: default <state>/<project>/recording.mcap;
///                            # scenario: inside the run folder, default run.mcap)
///     topics: ["ddl/*", "dl/*"]   # globs to include; default every catalog topic
///     exclude: ["hw/camera_frame"]  # globs to leave out
///     size_cap_mb: 500       # the file never grows past this [MB = 10^6 bytes]; 0 = no cap
///     compression: zstd      # zstd | lz4 | none (chunk compression)
///
/// Errors name the file, line and key ("s.yaml:14: record.compression: 'gzip' is not one of:
/// zstd, lz4, none").

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

#include "rover/base/status.hpp"
#include "rover/base/yaml_check.hpp"
#include "rover/mcap/writer.hpp"
#include "rover/recording/topic_filter.hpp"

namespace rover::recording {

struct RecordOptions {
  bool enabled = true;
  std::string path;  ///< "" = the caller's default
  TopicFilter topics;
  double size_cap_mb = 0;  ///< [MB] 0 = none; else at least 0.01 (the writer's 4096 bytes)
  mcap::Compression compression = mcap::Compression::kZstd;

  /// The topic patterns, and the cap 0 or in [0.01, 10^6] MB.
  Status Validate() const;
  /// The MCAP writer's options for these (chunk size and level at their defaults).
  mcap::WriterOptions WriterOptions() const;
};

/// "zstd", "lz4" or "none" (anything else is InvalidArgument naming the choices).
Result<mcap::Compression> ParseCompression(std::string_view name);
/// "zstd", "lz4", "none".
std::string CompressionText(mcap::Compression compression);

/// Parses a `record` node: a boolean, or a map of the keys above. `where` is the key path used
/// in messages ("record", "x-rover.record"). `defaults` are the values of absent keys. With
/// `known_topics` (the topic catalog's names) a pattern that matches none of them is an error
/// ("s.yaml:9: record.exclude: 'hw/camera_frames' matches no topic (did you mean
/// 'hw/camera_frame'?)").
Result<RecordOptions> ParseRecordOptions(const YAML::Node& node, const std::string& where,
                                         const yaml::FileErrors& err,
                                         const RecordOptions& defaults = {},
                                         const std::vector<std::string>& known_topics = {});

}  // namespace rover::recording
