// Child processes, and finding and stopping a process tree by a marker in its environment.
#include "rover/base/process.hpp"

#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <string>
#include <thread>

namespace rover {
namespace {

// A marker no other test or process on this machine carries.
std::string Marker(const std::string& tag) {
  return "process-test-" + std::to_string(getpid()) + "-" + tag;
}

bool Contains(const std::vector<pid_t>& pids, pid_t pid) {
  return std::find(pids.begin(), pids.end(), pid) != pids.end();
}

// Polls until `condition` holds; a liveness bound of the test, not an assertion on speed.
template <class F>
bool Eventually(F condition) {
  for (int i = 0; i < 2000; ++i) {
    if (condition()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

Process Spawn(std::vector<std::string> argv, const std::string& marker) {
  SpawnOptions o;
  o.argv = std::move(argv);
  o.env["ROVER_TEST_MARK"] = marker;
  auto p = Process::Spawn(o);
  EXPECT_TRUE(p.ok()) << p.status().message();
  return std::move(*p);
}

TEST(Process, SpawnsInItsOwnGroupAndReportsHowItEnded) {
  Process s = Spawn({"sleep", "60"}, Marker("group"));
  EXPECT_EQ(ProcessGroupOf(s.pid()), s.pid());
  EXPECT_EQ(s.Terminate(std::chrono::seconds(5)).ToString(), "killed by signal 15 (SIGTERM)");
  Process p = Spawn({"sh", "-c", "exit 3"}, Marker("exit"));
  auto e = p.WaitFor(std::chrono::seconds(20));
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->ToString(), "exit code 3");
  SpawnOptions missing;
  missing.argv = {"no-such-program-xyz"};
  EXPECT_FALSE(Process::Spawn(missing).ok());
}

TEST(Process, FindsProcessesByAnEnvironmentEntryExactlyOrByPrefix) {
  const std::string marker = Marker("find");
  Process a = Spawn({"sleep", "60"}, marker + "/a");
  Process b = Spawn({"sleep", "60"}, marker + "/b");
  ASSERT_TRUE(Eventually([&] {
    return ProcessesWithEnvironment("ROVER_TEST_MARK", marker + "/a").size() == 1;
  }));
  const auto exact = ProcessesWithEnvironment("ROVER_TEST_MARK", marker + "/a");
  EXPECT_EQ(exact, std::vector<pid_t>{a.pid()});
  const auto both = ProcessesWithEnvironment("ROVER_TEST_MARK", marker + "/", EnvMatch::kPrefix);
  EXPECT_EQ(both.size(), 2u);
  EXPECT_TRUE(Contains(both, a.pid()) && Contains(both, b.pid()));
  EXPECT_TRUE(ProcessesWithEnvironment("ROVER_TEST_MARK", marker).empty());  // exact: no
  EXPECT_GT(ProcessStartTicks(a.pid()), 0);
  EXPECT_EQ(ProcessStartTicks(a.pid()), ProcessStartTicks(a.pid()));
  a.Terminate(std::chrono::seconds(5));
  b.Terminate(std::chrono::seconds(5));
  EXPECT_TRUE(ProcessesWithEnvironment("ROVER_TEST_MARK", marker + "/", EnvMatch::kPrefix).empty());
  EXPECT_EQ(ProcessGroupOf(a.pid()), -1);
  EXPECT_EQ(ProcessStartTicks(a.pid()), -1);
}

// The tree of a wrapper script whose parent is gone: a plain child, one that ignores SIGTERM and
// one in a session of its own. All go; a process with another marker stays.
TEST(Process, StopMarkedProcessesStopsAWholeOrphanedTree) {
  const std::string marker = Marker("tree");
  Process bystander = Spawn({"sleep", "60"}, Marker("bystander"));
  Process script = Spawn({"sh", "-c",
                          "sleep 60 & (trap '' TERM; exec sleep 61) & setsid sleep 62 & "
                          "echo started; wait"},
                         marker + "/svc");
  ASSERT_TRUE(Eventually([&] {
    return ProcessesWithEnvironment("ROVER_TEST_MARK", marker + "/svc").size() == 4;
  }));
  kill(script.pid(), SIGKILL);  // the script alone: its children are orphaned
  ASSERT_TRUE(script.WaitFor(std::chrono::seconds(10)).has_value());
  ASSERT_TRUE(Eventually([&] {
    return ProcessesWithEnvironment("ROVER_TEST_MARK", marker + "/svc").size() == 3;
  }));
  const MarkedStop stop = StopMarkedProcesses("ROVER_TEST_MARK", marker + "/", EnvMatch::kPrefix,
                                              std::chrono::milliseconds(300));
  EXPECT_EQ(stop.found.size(), 3u);
  EXPECT_TRUE(stop.all_gone);
  EXPECT_EQ(stop.killed.size(), 1u);  // the one that ignores SIGTERM
  EXPECT_TRUE(ProcessesWithEnvironment("ROVER_TEST_MARK", marker + "/", EnvMatch::kPrefix).empty());
  EXPECT_TRUE(ProcessAlive(bystander.pid()));
  EXPECT_TRUE(StopMarkedProcesses("ROVER_TEST_MARK", marker + "/", EnvMatch::kPrefix,
                                  std::chrono::milliseconds(10))
                  .found.empty());
  bystander.Terminate(std::chrono::seconds(5));
}

}  // namespace
}  // namespace rover
