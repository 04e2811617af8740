// What README.md and docs/ tell a user to type, and what the README names, against the tree:
//   - every `roverctl <command> [<subcommand>] [--flag ...]` quoted in an inline code span or a
//     code block names a command that exists and flags that command's --help lists;
//   - every service the README names (ddl-*, dl-*, apl-*, rover-sim) is built, and every
//     deploy/... or tests/... path it names exists.
// A doc that drifts from the code fails here instead of on a user's terminal.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "rover/testing/test_support.hpp"

namespace rover::testing {
namespace {

namespace fs = std::filesystem;

std::string Roverctl() { return BinDir() + "/roverctl"; }

// The commands a --help text lists under "Subcommands:".
std::set<std::string> Subcommands(const std::string& help) {
  std::set<std::string> out;
  const auto start = help.find("Subcommands:");
  if (start == std::string::npos) return out;
  std::istringstream in(help.substr(start));
  std::string line;
  std::getline(in, line);
  const std::regex entry(R"(^\s+([a-z][a-z-]*)\s)");
  while (std::getline(in, line)) {
    std::smatch m;
    if (std::regex_search(line, m, entry)) out.insert(m[1]);
  }
  return out;
}

// The flags a --help text lists: "-d,--detach", "--wait{120}", "--domain INT" -> -d, --detach,
// --wait, --domain.
std::set<std::string> Flags(const std::string& help) {
  std::set<std::string> out;
  const std::regex flag(R"((?:^|[\s,])(--?[A-Za-z][A-Za-z0-9-]*))");
  std::istringstream in(help);
  std::string line;
  while (std::getline(in, line)) {
    const auto first = line.find_first_not_of(' ');
    if (first == std::string::npos || line[first] != '-') continue;  // option lines only
    const std::string head = line.substr(first, line.find("  ", first) - first);
    for (std::sregex_iterator it(head.begin(), head.end(), flag), end; it != end; ++it) {
      out.insert((*it)[1]);
    }
  }
  return out;
}

// Inline code spans and code-block lines of a markdown file, each with its line number.
std::vector<std::pair<int, std::string>> CodeSnippets(const std::string& text) {
  std::vector<std::pair<int, std::string>> out;
  std::istringstream in(text);
  std::string line;
  bool fenced = false;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (line.rfind("```", 0) == 0) {
      fenced = !fenced;
      continue;
    }
    if (fenced) {
      out.emplace_back(number, line);
      continue;
    }
    std::size_t pos = 0;
    while (true) {
      const auto open = line.find('`', pos);
      if (open == std::string::npos) break;
      const auto close = line.find('`', open + 1);
      if (close == std::string::npos) break;
      out.emplace_back(number, line.substr(open + 1, close - open - 1));
      pos = close + 1;
    }
  }
  return out;
}

std::vector<std::string> Words(const std::string& s) {
  std::vector<std::string> out;
  std::istringstream in(s);
  std::string w;
  while (in >> w) out.push_back(w);
  return out;
}

std::vector<fs::path> DocFiles() {
  std::vector<fs::path> out = {fs::path(SourceDir()) / "README.md"};
  for (const auto& e : fs::recursive_directory_iterator(fs::path(SourceDir()) / "docs")) {
    if (e.is_regular_file() && e.path().extension() == ".md") out.push_back(e.path());
  }
  return out;
}

TEST(DocsClaims, EveryQuotedRoverctlCommandAndFlagExists) {
  const std::set<std::string> commands = Subcommands(CaptureStdout(Roverctl() + " --help"));
  ASSERT_TRUE(commands.count("run") && commands.count("up")) << "roverctl --help unreadable";
  std::map<std::string, std::set<std::string>> flags;       // "run", "fault add" -> flags
  std::map<std::string, std::set<std::string>> subcommands;  // "fault" -> add, list, clear
  auto flags_of = [&](const std::string& command) -> const std::set<std::string>& {
    auto it = flags.find(command);
    if (it == flags.end()) {
      const std::string help = CaptureStdout(Roverctl() + " " + command + " --help");
      it = flags.emplace(command, Flags(help)).first;
      subcommands[command] = Subcommands(help);
    }
    return it->second;
  };
  int checked = 0;
  std::vector<std::string> problems;
  for (const fs::path& file : DocFiles()) {
    const std::string rel = fs::relative(file, SourceDir()).string();
    const std::string text = ReadFile(file.string());
    std::vector<std::string> lines;
    {
      std::istringstream in(text);
      for (std::string l; std::getline(in, l);) lines.push_back(l);
    }
    for (const auto& [line, raw] : CodeSnippets(text)) {
      // What the docs say does not exist yet ("No `roverctl seq run` yet") is not a claim.
      const std::string& prose = lines[static_cast<std::size_t>(line - 1)];
      if (prose.find("not yet") != std::string::npos ||
          prose.find("Not yet") != std::string::npos ||
          prose.find("No `roverctl") != std::string::npos) {
        continue;
      }
      const std::string snippet = raw.substr(0, raw.find(" #"));  // shell comments
      std::vector<std::string> words = Words(snippet);
      for (std::size_t i = 0; i < words.size(); ++i) {
        const std::string& w = words[i];
        const bool is_roverctl =
            w == "roverctl" || (w.size() > 9 && w.compare(w.size() - 9, 9, "/roverctl") == 0);
        if (!is_roverctl || i + 1 >= words.size()) continue;
        // A command: first on its line, or after a shell separator or environment assignments
        // (not the word "roverctl" in a sentence or an error message).
        std::size_t k = i;
        while (k > 0 && words[k - 1].find('=') != std::string::npos &&
               words[k - 1].find('=') > 0) {
          --k;
        }
        static const std::set<std::string> kSeparators = {"$", "|", "&&", "||", ";", "nohup",
                                                          "time", "then", "do", "("};
        if (k > 0 && !kSeparators.count(words[k - 1])) continue;
        std::string command = words[i + 1];
        if (command.empty() || !std::isalpha(static_cast<unsigned char>(command[0]))) continue;
        // "record/replay/info", "up|down": each must exist; flags are not checked then.
        if (command.find_first_of("/|") != std::string::npos) {
          std::string name;
          for (char c : command + "/") {
            if (c == '/' || c == '|') {
              if (!name.empty() && !commands.count(name)) {
                problems.push_back(rel + ":" + std::to_string(line) + ": roverctl " + name +
                                   ": no such command");
              }
              name.clear();
            } else if (std::isalpha(static_cast<unsigned char>(c))) {
              name += c;
            }
          }
          continue;
        }
        ++checked;
        if (!commands.count(command)) {
          problems.push_back(rel + ":" + std::to_string(line) + ": roverctl " + command +
                             ": no such command");
          continue;
        }
        (void)flags_of(command);
        std::size_t j = i + 2;
        if (!subcommands[command].empty() && j < words.size() &&
            subcommands[command].count(words[j])) {
          command += " " + words[j];
          ++j;
        }
        const std::set<std::string>& known = flags_of(command);
        for (; j < words.size(); ++j) {
          const std::string& word = words[j];
          if (kSeparators.count(word) || word == "\\") break;
          if (word.size() < 2 || word[0] != '-') continue;  // arguments, values
          std::string flag = word.substr(0, word.find_first_of("=[<"));
          while (!flag.empty() && !std::isalnum(static_cast<unsigned char>(flag.back()))) {
            flag.pop_back();
          }
          const std::size_t name_at = flag.size() > 1 && flag[1] == '-' ? 2 : 1;
          if (flag.size() <= name_at || !std::isalpha(static_cast<unsigned char>(flag[name_at]))) {
            continue;  // "-5", "--"
          }
          if (!known.count(flag)) {
            problems.push_back(rel + ":" + std::to_string(line) + ": roverctl " + command + " " +
                               flag + ": no such option");
          }
        }
      }
    }
  }
  EXPECT_GT(checked, 20) << "too few roverctl commands found in the docs: the scan is broken";
  for (const auto& p : problems) ADD_FAILURE() << p;
}

TEST(DocsClaims, TheReadmeNamesOnlyServicesAndFilesThatExist) {
  const std::string readme = ReadFile(SourceDir() + "/README.md");
  ASSERT_FALSE(readme.empty());
  int services = 0, paths = 0;
  const std::regex service(R"(\b((?:ddl|dl|apl)-[a-z][a-z-]*[a-z]|rover-sim)\b)");
  for (std::sregex_iterator it(readme.begin(), readme.end(), service), end; it != end; ++it) {
    const std::string name = (*it)[1];
    ++services;
    EXPECT_TRUE(fs::exists(fs::path(BinDir()) / name))
        << "README.md names service '" << name << "', which is not built";
  }
  const std::regex path(R"(\b((?:deploy|tests|docs|scripts)/[A-Za-z0-9_./-]*[A-Za-z0-9_]))");
  for (std::sregex_iterator it(readme.begin(), readme.end(), path), end; it != end; ++it) {
    const std::string p = (*it)[1];
    if (p.find('*') != std::string::npos) continue;
    ++paths;
    EXPECT_TRUE(fs::exists(fs::path(SourceDir()) / p))
        << "README.md names '" << p << "', which the tree does not have";
  }
  EXPECT_GE(services, 3) << "too few services found in the README: the scan is broken";
  EXPECT_GE(paths, 5) << "too few paths found in the README: the scan is broken";
}

}  // namespace
}  // namespace rover::testing
