#include "rover/recording/schema.hpp"

#include <algorithm>
#include <cctype>
#include <set>

namespace rover::recording {
namespace {

const idl::IdlFile* FindFile(std::string_view name, std::span<const idl::IdlFile> files) {
  for (const auto& f : files) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

bool IsWordChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '@';
}

// The name in `#include "name"` (or <name>); "" when the line has none.
std::string IncludedName(std::string_view line) {
  const std::size_t open = line.find_first_of("\"<");
  if (open == std::string_view::npos) return "";
  const char close_char = line[open] == '"' ? '"' : '>';
  const std::size_t close = line.find(close_char, open + 1);
  if (close == std::string_view::npos) return "";
  return std::string(line.substr(open + 1, close - open - 1));
}

struct Resolver {
  std::span<const idl::IdlFile> files;
  std::set<std::string> done;
  std::set<std::string> open;
  std::string out;

  Status Emit(std::string_view name, std::string_view from) {
    const std::string key(name);
    if (done.count(key) != 0) return Status::Ok();
    if (open.count(key) != 0) {
      return InvalidArgument(std::string(from) + " includes " + key +
                             ", which includes it back (an include cycle)");
    }
    const idl::IdlFile* f = FindFile(name, files);
    if (f == nullptr) {
      return NotFound(from.empty() ? key + " is not an IDL file of this build"
                                   : std::string(from) + " includes " + key +
                                         ", which is not an IDL file of this build");
    }
    open.insert(key);
    std::string body;
    std::size_t pos = 0;
    int line_no = 0;
    const std::string_view text = f->text;
    while (pos < text.size()) {
      std::size_t end = text.find('\n', pos);
      if (end == std::string_view::npos) end = text.size();
      const std::string_view line = text.substr(pos, end - pos);
      ++line_no;
      pos = end + 1;
      const std::size_t first = line.find_first_not_of(" \t\r");
      if (first != std::string_view::npos && line[first] == '#') {
        std::string_view directive = line.substr(first + 1);
        directive.remove_prefix(std::min(directive.size(), directive.find_first_not_of(" \t")));
        if (directive.rfind("include", 0) == 0) {
          const std::string inc = IncludedName(directive);
          if (inc.empty()) {
            return InvalidArgument(key + ":" + std::to_string(line_no) +
                                   ": #include without a file name");
          }
          ROVER_RETURN_IF_ERROR(Emit(inc, key));
        }
        continue;  // no preprocessor directive goes into the schema
      }
      body.append(line);
      body.push_back('\n');
    }
    open.erase(key);
    done.insert(key);
    out += body;
    return Status::Ok();
  }
};

}  // namespace

Result<std::string> ResolveIdl(std::string_view file, std::span<const idl::IdlFile> files) {
  Resolver r{files, {}, {}, {}};
  ROVER_RETURN_IF_ERROR(r.Emit(file, ""));
  return std::move(r.out);
}

Result<idl::IdlTopicType> FindTopicType(std::string_view c_name) {
  for (const auto& t : idl::IdlTopicTypes()) {
    if (t.c_name == c_name) return t;
  }
  return NotFound("no @topic type '" + std::string(c_name) + "' in this build's IDL files");
}

Result<TopicSchema> SchemaForType(std::string_view c_name) {
  ROVER_ASSIGN_OR_RETURN(const idl::IdlTopicType type, FindTopicType(c_name));
  ROVER_ASSIGN_OR_RETURN(std::string text, ResolveIdl(type.file, idl::IdlFiles()));
  return TopicSchema{std::string(type.scoped_name), std::move(text)};
}

std::string NormalizeIdl(std::string_view text) {
  std::string out;
  bool space = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '/' && i + 1 < text.size() && text[i + 1] == '/') {
      while (i < text.size() && text[i] != '\n') ++i;
      space = true;
      continue;
    }
    if (text[i] == '/' && i + 1 < text.size() && text[i + 1] == '*') {
      const std::size_t end = text.find("*/", i + 2);
      i = end == std::string_view::npos ? text.size() : end + 1;
      space = true;
      continue;
    }
    if (std::isspace(static_cast<unsigned char>(text[i])) != 0) {
      space = true;
      continue;
    }
    // A space only where it separates two words ("struct A"), none around punctuation.
    if (space && !out.empty() && IsWordChar(out.back()) && IsWordChar(text[i])) out.push_back(' ');
    space = false;
    out.push_back(text[i]);
  }
  return out;
}

}  // namespace rover::recording
