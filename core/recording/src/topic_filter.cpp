#include "rover/recording/topic_filter.hpp"

#include <cctype>

namespace rover::recording {

bool TopicFilter::Selects(std::string_view topic) const {
  bool in = include.empty();
  for (const auto& g : include) {
    if (GlobMatch(g, topic)) {
      in = true;
      break;
    }
  }
  if (!in) return false;
  for (const auto& g : exclude) {
    if (GlobMatch(g, topic)) return false;
  }
  return true;
}

Status TopicFilter::Validate() const {
  for (const auto* list : {&include, &exclude}) {
    const char* what = list == &include ? "topics" : "exclude";
    for (const auto& g : *list) {
      if (g.empty()) return InvalidArgument(std::string(what) + ": empty topic pattern");
      for (char c : g) {
        if (std::isspace(static_cast<unsigned char>(c)) != 0) {
          return InvalidArgument(std::string(what) + ": topic pattern '" + g +
                                 "' contains whitespace");
        }
      }
    }
  }
  return Status::Ok();
}

std::string TopicFilter::Describe() const {
  std::string out;
  for (const auto& g : include) out += (out.empty() ? "" : ", ") + g;
  if (out.empty()) out = "every topic";
  if (!exclude.empty()) {
    out += " (excluding ";
    for (std::size_t i = 0; i < exclude.size(); ++i) out += (i ? ", " : "") + exclude[i];
    out += ")";
  }
  return out;
}

}  // namespace rover::recording
