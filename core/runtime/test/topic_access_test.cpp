#include "rover/runtime/topic_access.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <map>
#include <set>

#include "rover/runtime/topic_catalog.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::dds {
namespace {

TEST(TopicAccess, EveryTopicIsInTheCatalogAndEveryRoleIsListedOnce) {
  std::set<std::string_view> roles;
  for (const RoleAccess& r : RoleAccessTable()) {
    EXPECT_TRUE(roles.insert(r.role).second) << r.role;
    for (const auto* list : {&r.writes, &r.reads}) {
      for (std::string_view t : *list) {
        // The benchmark's identity uses only its own bench/ topics; everyone else the catalog's.
        const bool bench = r.role == "rover-dds-bench" && t.substr(0, 6) == "bench/";
        EXPECT_TRUE(t == "*" || bench || FindTopic(t).has_value()) << r.role << ": " << t;
      }
    }
  }
  for (std::string_view t : kServiceWrites) EXPECT_TRUE(FindTopic(t).has_value()) << t;
  for (std::string_view t : kServiceReads) EXPECT_TRUE(FindTopic(t).has_value()) << t;
}

TEST(TopicAccess, ServicesGetTheHarnessTopicsAndToolsDoNot) {
  const auto w = TopicsWritten("dl-pose");
  EXPECT_TRUE(std::binary_search(w.begin(), w.end(), "dl/pose"));
  EXPECT_TRUE(std::binary_search(w.begin(), w.end(), "sys/health"));
  EXPECT_FALSE(std::binary_search(w.begin(), w.end(), "dl/drive_command"));
  const auto r = TopicsRead("dl-pose");
  EXPECT_TRUE(std::binary_search(r.begin(), r.end(), "sim/clock"));
  EXPECT_FALSE(std::binary_search(r.begin(), r.end(), "sim/truth"));  // the stack never reads it
  EXPECT_EQ(TopicsWritten("fault-controller"), (std::vector<std::string>{"sys/fault_control"}));
  EXPECT_EQ(TopicsRead("recorder").size(), TopicCatalog().size());
  EXPECT_TRUE(TopicsWritten("no-such-role").empty());
}

// The stack never reads simulator ground truth: only roverctl's own participants may.
TEST(TopicAccess, OnlyTheRunnerAndRecorderReadTruth) {
  for (const RoleAccess& role : RoleAccessTable()) {
    const auto r = TopicsRead(role.role);
    const bool reads = std::binary_search(r.begin(), r.end(), "sim/truth");
    EXPECT_EQ(reads, role.role == "scenario-runner" || role.role == "recorder") << role.role;
  }
}

// Every rover service the tree builds has a role (a secured set refuses a service without one).
TEST(TopicAccess, EveryServiceFolderHasARole) {
  for (const char* svc : {"apl-mobility", "apl-rendezvous", "apl-sequencer", "ddl-camera",
                          "ddl-imu", "ddl-joints", "ddl-motor", "ddl-sun-sensor",
                          "dl-arm", "dl-locomotion", "dl-mast", "dl-pose", "dl-stereo", "dl-vo",
                          "rover-sim"}) {
    EXPECT_TRUE(FindRole(svc).has_value()) << svc;
  }
}

// docs/topics.md's publisher and subscriber columns name every service the table lets write or
// read a topic (a row's cells split at '|' that are not escaped).
TEST(TopicAccess, DocsNameEveryServiceThatWritesOrReadsATopic) {
  const std::string doc = testing::ReadFile(testing::SourceDir() + "/docs/topics.md");
  ASSERT_FALSE(doc.empty());
  std::map<std::string, std::pair<std::string, std::string>> rows;  // topic -> (pubs, subs)
  std::size_t pos = 0;
  while ((pos = doc.find("\n| `", pos)) != std::string::npos) {
    const std::size_t end = doc.find('\n', pos + 1);
    const std::string line = doc.substr(pos + 1, end - pos - 1);
    std::vector<std::string> cells;
    std::string cell;
    for (std::size_t i = 1; i < line.size(); ++i) {
      if (line[i] == '|' && line[i - 1] != '\\') {
        cells.push_back(cell);
        cell.clear();
      } else {
        cell += line[i];
      }
    }
    if (cells.size() >= 5) {
      std::string topic = cells[0];
      topic.erase(std::remove_if(topic.begin(), topic.end(),
                                 [](char c) { return c == '`' || c == ' '; }),
                  topic.end());
      rows[topic] = {cells[3], cells[4]};
    }
    pos = end;
  }
  auto names = [](const std::string& cell, std::string_view role) {
    for (std::size_t at = cell.find(role); at != std::string::npos; at = cell.find(role, at + 1)) {
      const bool left = at == 0 || !(std::isalnum(static_cast<unsigned char>(cell[at - 1])) ||
                                     cell[at - 1] == '-');
      const std::size_t after = at + role.size();
      const bool right = after >= cell.size() ||
                         !(std::isalnum(static_cast<unsigned char>(cell[after])) ||
                           cell[after] == '-');
      if (left && right) return true;
    }
    return false;
  };
  for (const RoleAccess& r : RoleAccessTable()) {
    if (!r.service) continue;
    for (std::string_view t : r.writes) {
      ASSERT_TRUE(rows.count(std::string(t))) << "docs/topics.md has no row for " << t;
      EXPECT_TRUE(names(rows[std::string(t)].first, r.role))
          << "docs/topics.md: " << t << "'s publishers do not name " << r.role;
    }
    for (std::string_view t : r.reads) {
      ASSERT_TRUE(rows.count(std::string(t))) << "docs/topics.md has no row for " << t;
      EXPECT_TRUE(names(rows[std::string(t)].second, r.role))
          << "docs/topics.md: " << t << "'s subscribers do not name " << r.role;
    }
  }
}

}  // namespace
}  // namespace rover::dds
