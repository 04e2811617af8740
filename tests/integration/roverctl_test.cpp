// roverctl end to end: the smoke set as real processes on loopback.
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "rover/base/process.hpp"
#include "rover/runtime/dds.hpp"
#include "rover/testing/test_support.hpp"

namespace rover {
namespace {
namespace fs = std::filesystem;
using testing::WaitFor;

// Every process whose environment says it belongs to `project` (roverctl sets ROVER_PROJECT).
std::vector<int> ProcessesOfProject(const std::string& project) {
  return ProcessesWithEnvironment("ROVER_PROJECT", project);
}

class RoverctlTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::MakeTempDir("roverctl-test");
    state_root_ = dir_ + "/state";
    testing::UseLoopbackDds();
  }
  void TearDown() override {
    for (auto& p : running_) p.Terminate(std::chrono::seconds(10));
    for (const auto& project : projects_) {
      for (int pid : ProcessesOfProject(project)) kill(pid, SIGKILL);
    }
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // A smoke compose file with a unique project name.
  std::string WriteSmoke(const std::string& tag, const std::string& extra_service = "") {
    const std::string project = "t" + std::to_string(getpid()) + "-" + tag;
    projects_.push_back(project);
    const std::string path = dir_ + "/" + tag + ".compose.yaml";
    std::ofstream(path) << "version: \"3.9\"\n"
                           "x-rover: {project: " << project << "}\n"
                           "services:\n"
                           "  ddl-smoke: {command: ddl-smoke --set rate_hz=50, restart: on-failure}\n"
                           "  dl-smoke:\n"
                           "    command: dl-smoke\n"
                           "    restart: on-failure\n"
                           "    depends_on: {ddl-smoke: {condition: service_healthy}}\n"
                           "  apl-smoke:\n"
                           "    command: apl-smoke --set report_every=5\n"
                           "    restart: on-failure\n"
                           "    depends_on: {dl-smoke: {condition: service_healthy}}\n"
                        << extra_service;
    return path;
  }

  std::string ProjectOf(const std::string& tag) {
    return "t" + std::to_string(getpid()) + "-" + tag;
  }

  Process StartRoverctl(const std::vector<std::string>& args, const std::string& log) {
    SpawnOptions o;
    o.argv = {testing::BinDir() + "/roverctl"};
    o.argv.insert(o.argv.end(), args.begin(), args.end());
    o.env["ROVER_STATE_DIR"] = state_root_;
    o.stdout_path = log;
    o.stderr_path = log;
    auto p = Process::Spawn(o);
    EXPECT_TRUE(p.ok()) << p.status().message();
    return std::move(*p);
  }

  // Runs roverctl to completion; returns (exit, output).
  std::pair<ExitInfo, std::string> RunRoverctl(const std::vector<std::string>& args) {
    const std::string log = dir_ + "/run-" + std::to_string(runs_++) + ".log";
    Process p = StartRoverctl(args, log);
    auto e = p.WaitFor(std::chrono::seconds(120));
    if (!e) e = p.Terminate(std::chrono::seconds(5));
    return {*e, testing::ReadFile(log)};
  }

  nlohmann::json State(const std::string& project) {
    std::ifstream in(state_root_ + "/" + project + "/state.json");
    if (!in) return nullptr;
    try {
      return nlohmann::json::parse(in);
    } catch (...) {
      return nullptr;
    }
  }

  bool WaitUp(const std::string& project) {
    return WaitFor([&] {
      auto s = State(project);
      return !s.is_null() && s["phase"] == "up";
    }, std::chrono::seconds(60));
  }

  int PidOf(const std::string& project, const std::string& service) {
    const nlohmann::json state = State(project);
    if (state.is_null()) return 0;
    for (const auto& s : state["services"]) {
      if (s["name"] == service) return s["pid"];
    }
    return 0;
  }

  std::string dir_, state_root_;
  std::vector<std::string> projects_;
  std::vector<Process> running_;
  int runs_ = 0;
};

// Reads apl/mobility_status on `domain` until `n` reports arrive; returns the last command_id.
long CountStatuses(int domain, int n, std::string* last_message = nullptr) {
  auto p = dds::Participant::Create(domain);
  if (!p.ok()) return -1;
  auto r = dds::Reader<rover_apl_MobilityStatus>::Create(*p, "apl/mobility_status");
  if (!r.ok()) return -1;
  int seen = 0;
  long last = -1;
  WaitFor([&] {
    for (auto& s : r->Take()) {
      ++seen;
      last = s->command_id;
      if (last_message) *last_message = s->message;
    }
    return seen >= n;
  }, std::chrono::seconds(30));
  return seen >= n ? last : -1;
}

TEST_F(RoverctlTest, SmokeSetPassesDataThroughAllThreeLayersAndCtrlCLeavesNothing) {
  const std::string file = WriteSmoke("flow");
  const std::string project = ProjectOf("flow");
  Process roverctl = StartRoverctl({"up", file}, dir_ + "/flow.log");
  ASSERT_TRUE(WaitUp(project)) << testing::ReadFile(dir_ + "/flow.log");
  const int domain = State(project)["domain"];

  // ddl/imu (ddl-smoke) -> dl/pose (dl-smoke) -> apl/mobility_status (apl-smoke): the apl
  // service counts poses, which exist only if imu samples crossed the dl service.
  std::string message;
  const long first = CountStatuses(domain, 3, &message);
  ASSERT_GT(first, 0) << "no data reached apl/mobility_status";
  EXPECT_EQ(first % 5, 0);
  EXPECT_NE(message.find("poses="), std::string::npos) << message;

  // `ps` shows every service running with a heartbeat.
  auto [ps_exit, ps_out] = RunRoverctl({"ps", project});
  EXPECT_TRUE(ps_exit.success());
  for (const char* svc : {"ddl-smoke", "dl-smoke", "apl-smoke"}) {
    EXPECT_NE(ps_out.find(svc), std::string::npos) << ps_out;
  }
  EXPECT_NE(ps_out.find("active"), std::string::npos) << ps_out;
  EXPECT_EQ(ProcessesOfProject(project).size(), 3u);

  // Ctrl-C: the whole set stops and no process is left.
  roverctl.Signal(SIGINT);
  auto e = roverctl.WaitFor(std::chrono::seconds(60));
  ASSERT_TRUE(e.has_value());
  EXPECT_TRUE(e->success()) << e->ToString();
  EXPECT_TRUE(ProcessesOfProject(project).empty());
  EXPECT_EQ(State(project)["phase"], "stopped");
  // `ps` on the stopped set does not pass the last heartbeats off as the services' state.
  auto [stopped_exit, stopped] = RunRoverctl({"ps", project});
  EXPECT_TRUE(stopped_exit.success()) << stopped;
  EXPECT_NE(stopped.find("not running"), std::string::npos) << stopped;
  EXPECT_EQ(stopped.find("active"), std::string::npos) << stopped;
  EXPECT_NE(stopped.find("(stopped)"), std::string::npos) << stopped;
}

// `roverctl ps` lists campaigns under way (their runs keep state in the campaign folder, not
// in the state root), with progress and where to look; a registration whose roverctl is gone
// is dropped.
TEST_F(RoverctlTest, PsListsRunningCampaigns) {
  const std::string out = dir_ + "/campaign-out";
  fs::create_directories(out + "/tiny-seed1");
  std::ofstream(out + "/campaign.json") << R"({"scenario": "tiny", "seeds": [1, 2, 3]})";
  std::ofstream(out + "/tiny-seed1/result.json") << "{}";
  fs::create_directories(state_root_ + "/campaigns");
  // This test process stands for the roverctl running it (alive); 999999 for one that is gone.
  std::ofstream(state_root_ + "/campaigns/" + std::to_string(getpid()) + ".json")
      << nlohmann::json{{"pid", getpid()}, {"scenario", "tiny"}, {"kind", "campaign"},
                        {"out", out}, {"started", "20261206-120000"}}
             .dump();
  std::ofstream(state_root_ + "/campaigns/999999.json")
      << nlohmann::json{{"pid", 999999}, {"scenario", "gone"}, {"out", out}}.dump();
  auto [e, ps] = RunRoverctl({"ps"});
  EXPECT_TRUE(e.success()) << ps;
  EXPECT_NE(ps.find("campaign 'tiny'  (roverctl pid " + std::to_string(getpid()) +
                    ", since 20261206-120000): 1 of 3 runs finished, into " + out),
            std::string::npos)
      << ps;
  EXPECT_NE(ps.find("the table so far: roverctl report " + out), std::string::npos) << ps;
  EXPECT_EQ(ps.find("gone"), std::string::npos) << ps;
  EXPECT_FALSE(fs::exists(state_root_ + "/campaigns/999999.json"));
  // --json has them too, beside the sets.
  auto [je, js] = RunRoverctl({"ps", "--json"});
  ASSERT_TRUE(je.success()) << js;
  const nlohmann::json j = nlohmann::json::parse(js);
  ASSERT_TRUE(j["sets"].is_array()) << js;
  ASSERT_EQ(j["campaigns"].size(), 1u) << js;
  EXPECT_EQ(j["campaigns"][0]["scenario"], "tiny");
  EXPECT_EQ(j["campaigns"][0]["finished"], 1);
  EXPECT_EQ(j["campaigns"][0]["total"], 3);
  EXPECT_EQ(j["campaigns"][0]["out"], out);
}

TEST_F(RoverctlTest, KillNineIsRestartedByPolicyAndDataFlowsAgain) {
  const std::string file = WriteSmoke("kill");
  const std::string project = ProjectOf("kill");
  running_.push_back(StartRoverctl({"up", file}, dir_ + "/kill.log"));
  ASSERT_TRUE(WaitUp(project));
  const int domain = State(project)["domain"];
  const int victim = PidOf(project, "dl-smoke");
  ASSERT_GT(victim, 0);
  ASSERT_EQ(kill(victim, SIGKILL), 0);
  int replacement = 0;
  ASSERT_TRUE(WaitFor([&] {
    const nlohmann::json s = State(project);
    if (s.is_null()) return false;
    for (const auto& svc : s["services"]) {
      if (svc["name"] == "dl-smoke" && svc["restarts"] == 1 && svc["state"] == "running" &&
          svc["pid"] != victim && svc["pid"] != 0) {
        replacement = svc["pid"];
        return true;
      }
    }
    return false;
  }, std::chrono::seconds(30)));
  EXPECT_TRUE(ProcessAlive(replacement));
  const nlohmann::json after = State(project);
  EXPECT_NE(after["services"][1]["last_exit"].get<std::string>().find("signal 9"), std::string::npos);
  // The restarted link carries data again (its counter restarted from zero at the apl end is
  // not required: the apl keeps counting poses from the new dl process).
  EXPECT_GT(CountStatuses(domain, 2), 0);
  // `roverctl down` stops it; nothing is left.
  auto [down_exit, down_out] = RunRoverctl({"down", project});
  EXPECT_TRUE(down_exit.success()) << down_out;
  EXPECT_TRUE(WaitFor([&] { return ProcessesOfProject(project).empty(); }, std::chrono::seconds(30)));
}

TEST_F(RoverctlTest, SupervisorKilledHardTakesItsServicesWithIt) {
  const std::string file = WriteSmoke("hard");
  const std::string project = ProjectOf("hard");
  Process roverctl = StartRoverctl({"up", file}, dir_ + "/hard.log");
  ASSERT_TRUE(WaitUp(project));
  ASSERT_EQ(ProcessesOfProject(project).size(), 3u);
  kill(roverctl.pid(), SIGKILL);
  roverctl.WaitFor(std::chrono::seconds(10));
  EXPECT_TRUE(WaitFor([&] { return ProcessesOfProject(project).empty(); }, std::chrono::seconds(30)))
      << "orphans left after the supervisor died";
}

TEST_F(RoverctlTest, TwoSetsOnDifferentDomainsDoNotSeeEachOther) {
  const std::string fa = WriteSmoke("a"), fb = WriteSmoke("b");
  running_.push_back(StartRoverctl({"up", fa}, dir_ + "/a.log"));
  running_.push_back(StartRoverctl({"up", fb}, dir_ + "/b.log"));
  ASSERT_TRUE(WaitUp(ProjectOf("a")));
  ASSERT_TRUE(WaitUp(ProjectOf("b")));
  const int da = State(ProjectOf("a"))["domain"], db = State(ProjectOf("b"))["domain"];
  ASSERT_NE(da, db);
  for (const auto& [project, domain] : {std::pair{ProjectOf("a"), da}, std::pair{ProjectOf("b"), db}}) {
    std::set<int> expected;
    const nlohmann::json state = State(project);
    for (const auto& s : state["services"]) expected.insert(s["pid"].get<int>());
    auto p = dds::Participant::Create(domain);
    ASSERT_TRUE(p.ok());
    auto r = dds::Reader<rover_sys_Heartbeat>::Create(*p, "sys/health");
    ASSERT_TRUE(r.ok());
    std::set<int> seen;
    // Three heartbeat periods: every service of this set is seen, none of the other's.
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(3);
    while (std::chrono::steady_clock::now() < until) {
      for (auto& s : r->Take()) seen.insert(s->pid);
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    EXPECT_EQ(seen, expected) << "domain " << domain << " matched writers " << r->MatchedWriters();
  }
}

TEST_F(RoverctlTest, ServiceExitingAtOnceFailsTheSetAndNothingIsHalfStarted) {
  const std::string file = WriteSmoke(
      "quit", "  quitter:\n    command: sh -c \"echo 'cannot open /dev/motor0' >&2; exit 3\"\n"
              "    depends_on: [apl-smoke]\n");
  const std::string project = ProjectOf("quit");
  auto [e, out] = RunRoverctl({"up", file});
  EXPECT_FALSE(e.success());
  EXPECT_NE(out.find(file + ":13: service 'quitter' exited at once (exit code 3): cannot open "
                            "/dev/motor0"),
            std::string::npos)
      << out;
  EXPECT_TRUE(ProcessesOfProject(project).empty());
  EXPECT_EQ(State(project)["phase"], "failed");
}

TEST_F(RoverctlTest, OutOfRangeParameterIsCaughtBeforeAnythingStarts) {
  const std::string file = WriteSmoke("param");
  std::string text = testing::ReadFile(file);
  text.replace(text.find("rate_hz=50"), 10, "rate_hz=5000");
  std::ofstream(file) << text;
  auto [e, out] = RunRoverctl({"up", file});
  EXPECT_EQ(e.code, 2);
  EXPECT_NE(out.find(file + ":4: services.ddl-smoke: --set rate_hz=5000: key 'rate_hz': 5000 is "
                            "out of range [0.1, 1000]"),
            std::string::npos)
      << out;
  // Nothing was started, so there is not even a log of a start.
  EXPECT_FALSE(fs::exists(state_root_ + "/" + ProjectOf("param") + "/logs/ddl-smoke.log"));
  // `config` runs the same validation (it used to pass this file and leave it to `up`).
  auto [c, config_out] = RunRoverctl({"config", file});
  EXPECT_EQ(c.code, 2);
  EXPECT_NE(config_out.find("--set rate_hz=5000: key 'rate_hz': 5000 is out of range"),
            std::string::npos)
      << config_out;
  auto [skip, skip_out] = RunRoverctl({"config", "--no-preflight", file});
  EXPECT_TRUE(skip.success()) << skip_out;
}

TEST_F(RoverctlTest, BadComposeFilesAreRejectedWithFileLineAndKey) {
  const std::string path = dir_ + "/bad.yaml";
  std::ofstream(path) << "services:\n  a:\n    comand: ddl-smoke\n";
  auto [e, out] = RunRoverctl({"up", path});
  EXPECT_EQ(e.code, 2);
  EXPECT_NE(out.find(path + ":3: services.a: unknown key 'comand' (did you mean 'command'?)"),
            std::string::npos)
      << out;
  auto [e2, out2] = RunRoverctl({"logs", "nope", "-p", "nothing"});
  EXPECT_FALSE(e2.success());
}

TEST_F(RoverctlTest, DetachedUpThenPsAndDown) {
  const std::string file = WriteSmoke("detach");
  const std::string project = ProjectOf("detach");
  auto [e, out] = RunRoverctl({"up", "-d", file});
  ASSERT_TRUE(e.success()) << out;
  EXPECT_NE(out.find("is up on DDS domain"), std::string::npos) << out;
  EXPECT_EQ(ProcessesOfProject(project).size(), 3u);
  const int supervisor = State(project)["supervisor_pid"];
  EXPECT_TRUE(ProcessAlive(supervisor));
  auto [e2, out2] = RunRoverctl({"up", file});         // a second `up` is refused
  EXPECT_EQ(e2.code, 2);
  EXPECT_NE(out2.find("is already up"), std::string::npos) << out2;
  auto [e3, logs] = RunRoverctl({"logs", "apl-smoke", "-p", project});
  EXPECT_TRUE(e3.success());
  EXPECT_NE(logs.find("msg=\"active\""), std::string::npos) << logs;
  auto [e4, out4] = RunRoverctl({"down", project});
  EXPECT_TRUE(e4.success()) << out4;
  EXPECT_TRUE(ProcessesOfProject(project).empty());
  EXPECT_FALSE(ProcessAlive(supervisor));
}


// Usage errors are exit code 2, as docs/roverctl.md says (CLI11's own codes were 105..109).
TEST_F(RoverctlTest, UsageErrorsExitWithTwo) {
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"up"}, {"frobnicate"}, {"ps", "--bogus"}, {"run"},
        {"logs", "x", "-n", "many"}, {}, {"fault"}, {"fault", "add"}, {"fault", "add", "--kind"},
        {"fault", "clear", "x"}, {"fault", "add", "{kind: drop, topic: dl/pose, probability: 2}"}}) {
    auto [e, out] = RunRoverctl(args);
    std::string line;
    for (const auto& a : args) line += a + " ";
    EXPECT_EQ(e.code, 2) << "roverctl " << line << "\n" << out;
    EXPECT_FALSE(e.signaled);
  }
  auto [help, text] = RunRoverctl({"--help"});
  EXPECT_TRUE(help.success()) << text;
  EXPECT_NE(text.find("up"), std::string::npos);
  // An unknown command is named, with the ones that exist.
  auto [frob, frob_out] = RunRoverctl({"frob"});
  EXPECT_EQ(frob.code, 2);
  EXPECT_NE(frob_out.find("unknown command 'frob' (the commands: up, down, ps,"),
            std::string::npos)
      << frob_out;
  // up --wait takes its value after '=': "--wait 30 FILE" says so instead of "FILE not expected".
  auto [wait, wait_out] = RunRoverctl({"up", "--wait", "30", "set.compose.yaml"});
  EXPECT_EQ(wait.code, 2);
  EXPECT_NE(wait_out.find("--wait takes its seconds after '=': write --wait=30"), std::string::npos)
      << wait_out;
}

// A smoke set whose dl service stays DEGRADED for `warmup` imu samples (ddl-smoke at 20 Hz), as
// dl-pose does while it levels.
std::string WarmupService(int warmup) {
  return "    command: dl-smoke --set warmup_samples=" + std::to_string(warmup) + "\n";
}

// `ps` shows each heartbeat's health and message, and says the set is not ready yet.
TEST_F(RoverctlTest, PsShowsHealthAndMessageOfEveryHeartbeat) {
  const std::string file = WriteSmoke("health");
  std::string text = testing::ReadFile(file);
  text.replace(text.find("    command: dl-smoke\n"), 22, WarmupService(1000000));
  std::ofstream(file) << text;
  const std::string project = ProjectOf("health");
  auto [up, up_out] = RunRoverctl({"up", "-d", file});
  ASSERT_TRUE(up.success()) << up_out;
  std::string ps;
  EXPECT_TRUE(WaitFor([&] {
    ps = RunRoverctl({"ps", project}).second;
    // Every service has sent its first heartbeat (under load apl-smoke's may come later).
    return ps.find("warming up:") != std::string::npos &&
           ps.find("no heartbeat yet") == std::string::npos;
  }, std::chrono::seconds(30))) << ps;
  EXPECT_NE(ps.find("HEALTH"), std::string::npos) << ps;
  EXPECT_NE(ps.find("MESSAGE"), std::string::npos) << ps;
  EXPECT_NE(ps.find("not ready"), std::string::npos) << ps;
  // One line per service: dl-smoke degraded with its message, the others ok.
  std::istringstream lines(ps);
  std::string line;
  int checked = 0;
  while (std::getline(lines, line)) {
    if (line.find("  dl-smoke ") == 0) {
      EXPECT_NE(line.find("degraded"), std::string::npos) << line;
      EXPECT_NE(line.find("of 1000000 ddl/imu samples"), std::string::npos) << line;
      ++checked;
    } else if (line.find("  ddl-smoke ") == 0 || line.find("  apl-smoke ") == 0) {
      EXPECT_NE(line.find(" ok "), std::string::npos) << line;
      ++checked;
    }
  }
  EXPECT_EQ(checked, 3) << ps;
  const nlohmann::json state = State(project);
  EXPECT_FALSE(state["ready"].get<bool>()) << state.dump(2);
  for (const auto& svc : state["services"]) {
    if (svc["name"] == "dl-smoke") {
      EXPECT_EQ(svc["health"], "degraded");
      EXPECT_NE(svc["message"].get<std::string>().find("warming up"), std::string::npos);
      EXPECT_FALSE(svc["ready"].get<bool>());
    }
  }
  EXPECT_TRUE(RunRoverctl({"down", project}).first.success());
}

// Row `id`/`service` of `roverctl fault list`: {seen, hit}, or {-1, -1} if absent; `state` gets
// its STATE column.
std::pair<long long, long long> FaultRow(const std::string& table, int id,
                                         const std::string& service, std::string* state = nullptr) {
  std::istringstream lines(table);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream cols(line);
    std::string rid, kind, st, svc;
    long long seen = -1, hit = -1;
    if (!(cols >> rid >> kind >> st >> svc >> seen >> hit)) continue;
    if (rid == std::to_string(id) && svc == service) {
      if (state) *state = st;
      return {seen, hit};
    }
  }
  return {-1, -1};
}

// Faults from the compose file (x-rover.faults) and from `roverctl fault add|list|clear`: a
// bad spec is refused with exit 2 and nothing applied; a drop is acknowledged by the services,
// its counts rise in `list`, and `clear` removes it.
TEST_F(RoverctlTest, FaultAddListClearAgainstARunningSet) {
  std::string file = WriteSmoke("faults");
  const std::string project = ProjectOf("faults");
  std::string text = testing::ReadFile(file);
  const std::string xr = "x-rover: {project: " + project + "}\n";
  text.replace(text.find(xr), xr.size(),
               "x-rover:\n  project: " + project + "\n  faults:\n"
               // Noise, not a duplicate: repeated seqs would make apl-smoke's inputs DEGRADED
               // (detection, docs/faults.md) and the set would never be ready for --wait.
               "    - {kind: noise, topic: dl/pose, service: dl-smoke, field: pose.position.x, "
               "sigma: 0.001, seed: 4}\n");
  std::ofstream(file) << text;
  auto [up, up_out] = RunRoverctl({"up", "-d", "--wait=60", file});
  ASSERT_TRUE(up.success()) << up_out;

  // Refused before anything is sent: exit 2, one line naming the key.
  auto [bad, bad_out] = RunRoverctl({"fault", "add", "--kind", "dorp", "--topic", "ddl/imu", "-p", project});
  EXPECT_EQ(bad.code, 2) << bad_out;
  EXPECT_NE(bad_out.find("fault add: key 'kind': 'dorp' is not a fault kind (did you mean 'drop'?)"),
            std::string::npos) << bad_out;
  auto [topic, topic_out] = RunRoverctl({"fault", "add", "{kind: drop, topic: ddl/imuu}", "-p", project});
  EXPECT_EQ(topic.code, 2) << topic_out;
  EXPECT_NE(topic_out.find("matches no catalog topic (nearest: ddl/imu"), std::string::npos) << topic_out;
  auto [prob, prob_out] = RunRoverctl(
      {"fault", "add", "--kind", "drop", "--topic", "ddl/imu", "--probability", "1.5", "-p", project});
  EXPECT_EQ(prob.code, 2) << prob_out;
  EXPECT_NE(prob_out.find("probability = 1.5 is outside [0, 1]"), std::string::npos) << prob_out;

  // Only the compose file's fault is there (id 1), acting in dl-smoke.
  auto [l0, l0_out] = RunRoverctl({"fault", "list", "-p", project});
  ASSERT_TRUE(l0.success()) << l0_out;
  EXPECT_GE(FaultRow(l0_out, 1, "dl-smoke").first, 0) << l0_out;
  EXPECT_EQ(FaultRow(l0_out, 2, "ddl-smoke").first, -1) << l0_out;

  auto [add, add_out] = RunRoverctl({"fault", "add", "--kind", "drop", "--topic", "ddl/imu",
                                     "--service", "ddl-smoke", "--probability", "0.5", "--seed",
                                     "9", "-p", project});
  ASSERT_TRUE(add.success()) << add_out;
  EXPECT_NE(add_out.find("fault 2: drop 50% of ddl/imu at the writers of ddl-smoke"),
            std::string::npos) << add_out;
  EXPECT_NE(add_out.find("applies in: ddl-smoke (held by 3 of 3 services)"), std::string::npos)
      << add_out;

  // Its counts rise while it acts (ddl-smoke writes ddl/imu at 50 Hz).
  long long first_hit = -1;
  ASSERT_TRUE(WaitFor([&] {
    auto [l, out] = RunRoverctl({"fault", "list", "-p", project});
    first_hit = FaultRow(out, 2, "ddl-smoke").second;
    return l.success() && first_hit > 0;
  }, std::chrono::seconds(30)));
  std::string state;
  ASSERT_TRUE(WaitFor([&] {
    auto [l, out] = RunRoverctl({"fault", "list", "-p", project});
    const auto [seen, hit] = FaultRow(out, 2, "ddl-smoke", &state);
    return hit > first_hit && hit < seen;
  }, std::chrono::seconds(30)));
  EXPECT_EQ(state, "active");
  auto [l1, l1_out] = RunRoverctl({"fault", "list", "-p", project});
  EXPECT_EQ(FaultRow(l1_out, 2, "dl-smoke").first, -1) << l1_out;  // not where it does not act
  EXPECT_GT(FaultRow(l1_out, 1, "dl-smoke").second, 0) << l1_out;  // the compose file's acts

  auto [clear, clear_out] = RunRoverctl({"fault", "clear", "2", "-p", project});
  ASSERT_TRUE(clear.success()) << clear_out;
  EXPECT_NE(clear_out.find("fault 2 removed in"), std::string::npos) << clear_out;
  auto [l2, l2_out] = RunRoverctl({"fault", "list", "-p", project});
  const auto [seen_after, hit_after] = FaultRow(l2_out, 2, "ddl-smoke", &state);
  EXPECT_EQ(state, "ended") << l2_out;
  auto [l3, l3_out] = RunRoverctl({"fault", "list", "-p", project});
  EXPECT_EQ(FaultRow(l3_out, 2, "ddl-smoke").second, hit_after) << l3_out;  // no longer counts
  (void)seen_after;
  auto [all, all_out] = RunRoverctl({"fault", "clear", "-p", project});
  ASSERT_TRUE(all.success()) << all_out;
  EXPECT_NE(all_out.find("cleared 1 fault in 3 services"), std::string::npos) << all_out;
  auto [again, again_out] = RunRoverctl({"fault", "clear", "7", "-p", project});
  EXPECT_EQ(again.code, 1) << again_out;
  EXPECT_NE(again_out.find("no fault 7"), std::string::npos) << again_out;
  EXPECT_TRUE(RunRoverctl({"down", project}).first.success());
}

// `up -d --wait` returns once every service is ready (heartbeat ACTIVE and health OK), not when
// the processes are merely running.
TEST_F(RoverctlTest, UpWaitReturnsOnceEveryServiceIsReady) {
  const std::string file = WriteSmoke("ready");
  std::string text = testing::ReadFile(file);
  text.replace(text.find("    command: dl-smoke\n"), 22, WarmupService(60));  // about 3 s
  std::ofstream(file) << text;
  const std::string project = ProjectOf("ready");
  auto [up, out] = RunRoverctl({"up", "-d", "--wait=120", file});
  ASSERT_TRUE(up.success()) << out;
  EXPECT_NE(out.find("is ready"), std::string::npos) << out;
  // When it returned, the state file already said ready, and every heartbeat said OK.
  const nlohmann::json state = State(project);
  EXPECT_TRUE(state["ready"].get<bool>()) << state.dump(2);
  for (const auto& svc : state["services"]) {
    EXPECT_EQ(svc["health"], "ok") << svc.dump();
    EXPECT_EQ(svc["lifecycle"], "active") << svc.dump();
    EXPECT_TRUE(svc["ready"].get<bool>()) << svc.dump();
  }
  EXPECT_TRUE(RunRoverctl({"down", project}).first.success());
}

// Not ready within the timeout: exit 1 naming what is not ready and why; the set is stopped.
TEST_F(RoverctlTest, UpWaitTimesOutNamingTheServicesThatAreNotReady) {
  const std::string file = WriteSmoke("slow");
  std::string text = testing::ReadFile(file);
  text.replace(text.find("    command: dl-smoke\n"), 22, WarmupService(1000000));
  std::ofstream(file) << text;
  const std::string project = ProjectOf("slow");
  auto [up, out] = RunRoverctl({"up", "-d", "--wait=10", file});
  EXPECT_EQ(up.code, 1) << out;
  EXPECT_NE(out.find("not ready within 10 s"), std::string::npos) << out;
  EXPECT_NE(out.find("dl-smoke: health degraded: warming up"), std::string::npos) << out;
  EXPECT_TRUE(WaitFor([&] { return ProcessesOfProject(project).empty(); }, std::chrono::seconds(30)));
}

// A service whose process tree outlives it: a wrapper script with a plain child, a child that
// ignores SIGTERM and one that left the process group (setsid).
constexpr const char* kTreeService =
    "  tree:\n"
    "    command: [sh, -c, \"sleep 300 & (trap '' TERM; exec sleep 301) & setsid sleep 302 & "
    "wait\"]\n"
    "    stop_grace_period: 1s\n";

int CountCommand(const std::vector<int>& pids, const std::string& needle) {
  int n = 0;
  for (int pid : pids) {
    const std::string cmdline = testing::ReadFile("/proc/" + std::to_string(pid) + "/cmdline");
    if (cmdline.rfind(needle + '\0', 0) == 0) ++n;  // the program itself, not a script naming it
  }
  return n;
}

// roverctl SIGKILLed: the kernel's SIGTERM (PR_SET_PDEATHSIG) reaches only its children, so the
// grandchildren live on; `roverctl down` must still find and stop them from the state file.
TEST_F(RoverctlTest, DownStopsWhatADeadSupervisorLeftBehind) {
  const std::string file = WriteSmoke("orphans", kTreeService);
  const std::string project = ProjectOf("orphans");
  Process roverctl = StartRoverctl({"up", file}, dir_ + "/orphans.log");
  ASSERT_TRUE(WaitUp(project)) << testing::ReadFile(dir_ + "/orphans.log");
  ASSERT_TRUE(WaitFor([&] { return CountCommand(ProcessesOfProject(project), "sleep") == 3; }));
  kill(roverctl.pid(), SIGKILL);
  roverctl.WaitFor(std::chrono::seconds(10));
  // The services die with their parent; the three sleeps do not.
  ASSERT_TRUE(WaitFor([&] {
    return ProcessesOfProject(project).size() == 3u &&
           CountCommand(ProcessesOfProject(project), "sleep") == 3;
  }, std::chrono::seconds(30)));
  auto [ps_exit, ps] = RunRoverctl({"ps", project});
  EXPECT_NE(ps.find("not running"), std::string::npos) << ps;
  EXPECT_NE(ps.find("3 processes of the set are still alive"), std::string::npos) << ps;
  auto [down, out] = RunRoverctl({"down", project});
  EXPECT_TRUE(down.success()) << out;
  EXPECT_NE(out.find("stopped 3 processes it left behind"), std::string::npos) << out;
  EXPECT_TRUE(ProcessesOfProject(project).empty()) << out;
  EXPECT_EQ(State(project)["phase"], "stopped");
}

// With the supervisor alive, `down` (and Ctrl-C) stop whole trees, including a process that left
// its service's process group.
TEST_F(RoverctlTest, DownStopsWholeProcessTrees) {
  const std::string file = WriteSmoke("trees", kTreeService);
  const std::string project = ProjectOf("trees");
  auto [up, up_out] = RunRoverctl({"up", "-d", file});
  ASSERT_TRUE(up.success()) << up_out;
  ASSERT_TRUE(WaitFor([&] { return CountCommand(ProcessesOfProject(project), "sleep") == 3; }));
  auto [down, out] = RunRoverctl({"down", project});
  EXPECT_TRUE(down.success()) << out;
  EXPECT_TRUE(WaitFor([&] { return ProcessesOfProject(project).empty(); }, std::chrono::seconds(5)))
      << CountCommand(ProcessesOfProject(project), "sleep") << " sleeps left";
}

}  // namespace
}  // namespace rover
