#pragma once
/// @file
/// Which topics a recording or a replay takes: glob patterns to include (none = every topic) and
/// to exclude. A glob matches a whole topic name; `*` matches any run of characters, `/`
/// included (so "ddl/*" is every ddl/ topic and "*" everything), `?` one character, and every
/// other character itself.

#include <string>
#include <string_view>
#include <vector>

#include "rover/base/glob.hpp"
#include "rover/base/status.hpp"

namespace rover::recording {

/// True when `pattern` matches all of `text` (rover/base/glob.hpp).
using rover::GlobMatch;

struct TopicFilter {
  std::vector<std::string> include;  ///< globs; empty = every topic
  std::vector<std::string> exclude;  ///< globs; a topic matching one is dropped

  /// Included and not excluded.
  bool Selects(std::string_view topic) const;
  /// No empty pattern, no whitespace in one (a pattern is a topic name with wildcards).
  Status Validate() const;
  /// "ddl/*, dl/pose (excluding sim/truth)", or "every topic".
  std::string Describe() const;
};

}  // namespace rover::recording
