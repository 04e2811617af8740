#include "rover/msg/sequence.hpp"

#include <cctype>

namespace rover::msg {

const char* SequenceStateName(SequenceState s) {
  switch (s) {
    case SequenceState::kIdle:
      return "IDLE";
    case SequenceState::kRunning:
      return "RUNNING";
    case SequenceState::kDone:
      return "DONE";
    case SequenceState::kFailed:
      return "FAILED";
  }
  return "UNKNOWN";
}

namespace {

bool IsWord(const std::string& s) {
  if (s.empty()) return false;
  for (const char c : s) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  }
  return true;
}

std::string Trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r");
  if (a == std::string::npos) return "";
  const std::size_t b = s.find_last_not_of(" \t\r");
  return s.substr(a, b - a + 1);
}

}  // namespace

Result<std::string> FormatSequenceOverrides(const std::map<std::string, std::string>& overrides) {
  std::string out;
  for (const auto& [name, value] : overrides) {
    if (!IsWord(name)) return InvalidArgument("override name '" + name + "' is not a word");
    if (value.find('\n') != std::string::npos || Trim(value).empty()) {
      return InvalidArgument("override " + name + ": value '" + value +
                             "' is empty or has a line break");
    }
    out += name + " = " + Trim(value) + "\n";
  }
  return out;
}

Result<std::map<std::string, std::string>> ParseSequenceOverrides(const std::string& text) {
  std::map<std::string, std::string> out;
  std::size_t start = 0;
  int line = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string l = Trim(text.substr(start, end - start));
    ++line;
    start = end + 1;
    if (l.empty()) continue;
    const std::size_t eq = l.find('=');
    const std::string where = "overrides line " + std::to_string(line) + ": ";
    if (eq == std::string::npos) return InvalidArgument(where + "'" + l + "' has no '='");
    const std::string name = Trim(l.substr(0, eq)), value = Trim(l.substr(eq + 1));
    if (!IsWord(name)) return InvalidArgument(where + "name '" + name + "' is not a word");
    if (value.empty()) return InvalidArgument(where + name + " has no value");
    if (!out.emplace(name, value).second) return InvalidArgument(where + name + " is given twice");
  }
  return out;
}

}  // namespace rover::msg
