#pragma once
/// @file
/// Shell-style globs for topic and service names (fault specs, recording topic filters).

#include <string_view>

namespace rover {

/// True when `glob` matches all of `text`: `*` matches any run of characters (including '/',
/// and none), `?` exactly one, every other character itself. Iterative with one backtrack point
/// (the last `*`), so linear in practice.
inline bool GlobMatch(std::string_view glob, std::string_view text) {
  std::size_t g = 0, t = 0, star_g = std::string_view::npos, star_t = 0;
  while (t < text.size()) {
    if (g < glob.size() && (glob[g] == '?' || glob[g] == text[t])) {
      ++g;
      ++t;
    } else if (g < glob.size() && glob[g] == '*') {
      star_g = g++;
      star_t = t;
    } else if (star_g != std::string_view::npos) {
      g = star_g + 1;
      t = ++star_t;
    } else {
      return false;
    }
  }
  while (g < glob.size() && glob[g] == '*') ++g;
  return g == glob.size();
}

}  // namespace rover
