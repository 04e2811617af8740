// Every service's parameters, as `<service> --help-params` lists them, against the "## Parameters"
// section of its page docs/services/<service>.md: each key must be documented there, and the page
// must not name a key the service no longer has. Keys are matched as people write them in the
// tables: literally (`drive.max_speed`), with brace alternatives (`drive.{a,b}_gain`), or under a
// wildcard (`geometry.*`). A dotted token counts as a key when its first segment is one of the
// service's key prefixes (so `rover_hardware.yaml` is not mistaken for one).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <regex>
#include <sstream>
#include <set>
#include <string>
#include <vector>

#include "rover/testing/test_support.hpp"

namespace rover::testing {
namespace {

namespace fs = std::filesystem;

// Expands the first {a,b,...} group of `token`, recursively.
void ExpandBraces(const std::string& token, std::vector<std::string>* out) {
  const auto open = token.find('{');
  const auto close = open == std::string::npos ? std::string::npos : token.find('}', open);
  if (close == std::string::npos) {
    out->push_back(token);
    return;
  }
  const std::string head = token.substr(0, open), tail = token.substr(close + 1);
  const std::string alternatives = token.substr(open + 1, close - open - 1);
  std::size_t start = 0;
  while (true) {
    const auto comma = alternatives.find(',', start);
    ExpandBraces(head + alternatives.substr(start, comma - start) + tail, out);
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
}

// The "## Parameters" section of a service page ("" if it has none).
std::string ParametersSection(const std::string& page) {
  const auto start = page.find("\n## Parameters");
  if (start == std::string::npos) return "";
  const auto end = page.find("\n## ", start + 1);
  return page.substr(start, end == std::string::npos ? std::string::npos : end - start);
}

// Whether the last non-space character before `pos` in `line` is a comma.
bool AfterComma(const std::string& line, std::size_t pos) {
  while (pos > 0 && line[pos - 1] == ' ') --pos;
  return pos > 0 && line[pos - 1] == ',';
}

// Backticked tokens of `text`, brace groups expanded. Within one line a bare name that follows a
// dotted key after a comma continues its prefix, as the tables write it: "`motor_manager.stall_window_s` (1),
// `stall_fraction`" documents motor_manager.stall_fraction.
// A bare name that is itself a key (`hardware_file`) stays as it is.
std::vector<std::string> BacktickedTokens(const std::string& text, const std::set<std::string>& keys) {
  std::vector<std::string> tokens;
  const std::regex re("`([^`]+)`");
  const std::regex bare("[a-z_][a-z0-9_]*");
  std::size_t line_start = 0;
  while (line_start < text.size()) {
    std::size_t line_end = text.find('\n', line_start);
    if (line_end == std::string::npos) line_end = text.size();
    const std::string line = text.substr(line_start, line_end - line_start);
    std::string prefix;
    for (auto it = std::sregex_iterator(line.begin(), line.end(), re);
         it != std::sregex_iterator(); ++it) {
      std::string token = (*it)[1].str();
      if (token.find('{') != std::string::npos) {  // "{a, b}" as well as "{a,b}"
        token.erase(std::remove(token.begin(), token.end(), ' '), token.end());
      }
      const auto dot = token.rfind('.', token.find('{'));  // the last dot before any brace
      if (dot != std::string::npos) {
        prefix = token.substr(0, dot + 1);
      } else if (!prefix.empty() && !keys.contains(token) && std::regex_match(token, bare) &&
                 AfterComma(line, static_cast<std::size_t>(it->position(0)))) {
        token = prefix + token;
      }
      ExpandBraces(token, &tokens);
    }
    line_start = line_end + 1;
  }
  return tokens;
}

// Keys from --help-params output: lines "  key (kind), default ...".
std::vector<std::string> HelpParamKeys(const std::string& help) {
  // Line by line: ECMAScript's '^' anchors at the start of the whole text only, so a pattern
  // over the whole output found no key after a header line and every page passed.
  std::vector<std::string> keys;
  const std::regex re("  ([A-Za-z0-9_.]+) \\(.*");
  std::istringstream in(help);
  for (std::string line; std::getline(in, line);) {
    std::smatch m;
    if (std::regex_match(line, m, re)) keys.push_back(m[1].str());
  }
  return keys;
}

std::vector<std::string> ServicePages() {
  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(SourceDir() + "/docs/services")) {
    if (entry.path().extension() == ".md") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

// build/rover_executables.txt (written by CMake): "<kind> <name>" per line.
std::vector<std::string> ExecutablesOfKind(const std::string& kind) {
  std::vector<std::string> names;
  const std::string text = ReadFile(BinaryDir() + "/rover_executables.txt");
  std::size_t start = 0;
  while (start < text.size()) {
    std::size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    const auto space = line.find(' ');
    if (space != std::string::npos && line.substr(0, space) == kind) {
      names.push_back(line.substr(space + 1));
    }
    start = end + 1;
  }
  return names;
}

// Every executable CMake builds as a service (rover_add_service) has a page, and every page
// belongs to a service (tools and benchmarks are documented in their component's README).
TEST(ServicePages, OnePagePerService) {
  const std::vector<std::string> services = ExecutablesOfKind("service");
  ASSERT_FALSE(services.empty()) << BinaryDir() << "/rover_executables.txt lists no service";
  const std::vector<std::string> pages = ServicePages();
  for (const auto& s : services) {
    EXPECT_TRUE(std::find(pages.begin(), pages.end(), s) != pages.end())
        << "service " << s << " has no page docs/services/" << s << ".md";
  }
  for (const auto& p : pages) {
    EXPECT_TRUE(std::find(services.begin(), services.end(), p) != services.end())
        << "docs/services/" << p << ".md: no service " << p
        << " is built (rover_add_service); tools and benchmarks belong in their README";
  }
}

class ServiceParamsDocs : public ::testing::TestWithParam<std::string> {};

TEST_P(ServiceParamsDocs, PageDocumentsEveryKeyAndNoStaleOne) {
  const std::string service = GetParam();
  const std::string exe = BinDir() + "/" + service;
  ASSERT_TRUE(fs::exists(exe)) << "docs/services/" << service << ".md names no executable " << exe;
  const std::vector<std::string> keys =
      HelpParamKeys(CaptureStdout(exe + " --help-params 2>/dev/null"));
  const std::string page = ReadFile(SourceDir() + "/docs/services/" + service + ".md");
  const std::string section = ParametersSection(page);
  if (keys.empty()) {
    SUCCEED() << service << " has no parameters";
    return;
  }
  ASSERT_FALSE(section.empty()) << "docs/services/" << service << ".md has no '## Parameters' "
                                << "section but " << service << " --help-params lists "
                                << keys.size() << " keys, e.g. " << keys.front();
  const std::set<std::string> key_set(keys.begin(), keys.end());
  const std::vector<std::string> tokens = BacktickedTokens(section, key_set);
  std::set<std::string> prefixes;
  for (const auto& k : keys) prefixes.insert(k.substr(0, k.find('.') + 1));

  for (const auto& key : keys) {
    bool covered = false;
    for (const auto& t : tokens) {
      if (t == key) covered = true;
      if (t.size() > 2 && t.ends_with(".*") && key.starts_with(t.substr(0, t.size() - 1))) {
        covered = true;
      }
    }
    EXPECT_TRUE(covered) << "docs/services/" << service << ".md: parameter '" << key
                         << "' (from " << service << " --help-params) is not in the Parameters "
                         << "section";
  }
  const std::regex key_like("[a-z_][a-z0-9_]*(\\.[a-z0-9_]+)+");
  for (const auto& t : tokens) {
    if (!std::regex_match(t, key_like)) continue;
    if (!prefixes.contains(t.substr(0, t.find('.') + 1))) continue;
    EXPECT_TRUE(key_set.contains(t)) << "docs/services/" << service << ".md names parameter '"
                                     << t << "', which " << service << " does not declare";
  }
}

INSTANTIATE_TEST_SUITE_P(AllServices, ServiceParamsDocs, ::testing::ValuesIn(ServicePages()),
                         [](const ::testing::TestParamInfo<std::string>& param_info) {
                           std::string name = param_info.param;
                           for (char& c : name) {
                             if (c == '-') c = '_';
                           }
                           return name;
                         });

}  // namespace
}  // namespace rover::testing
