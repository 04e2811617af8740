#include "rover/runtime/topic_access.hpp"

#include <gtest/gtest.h>

#include <algorithm>
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
        EXPECT_TRUE(t == "*" || FindTopic(t).has_value()) << r.role << ": " << t;
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
                          "dl-locomotion", "dl-mast", "dl-pose", "dl-stereo", "dl-vo",
                          "rover-sim"}) {
    EXPECT_TRUE(FindRole(svc).has_value()) << svc;
  }
}

}  // namespace
}  // namespace rover::dds
