// DDS Security end to end: a secured set (x-rover.security: enabled) with three intruders that
// try to command a drive and to read dl/pose — one without a certificate, one with a
// certificate of another authority, one with a valid identity whose permissions do not include
// the command topic — beside a trusted observer and a permitted operator (which shows that the
// test can fail: its commands are heard).
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "rover/base/process.hpp"
#include "rover/testing/test_support.hpp"

namespace rover {
namespace {
namespace fs = std::filesystem;

class SecurityTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = testing::MakeTempDir("security-test");
    state_root_ = dir_ + "/state";
    keys_ = state_root_ + "/security";
    testing::UseLoopbackDds();
  }
  void TearDown() override {
    if (up_.running()) up_.Terminate(std::chrono::seconds(10));
    for (int pid : ProcessesWithEnvironment("ROVER_PROJECT", project_)) kill(pid, SIGKILL);
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }

  // Runs a program to completion with `env`; returns (exit, output).
  std::pair<ExitInfo, std::string> Run(const std::vector<std::string>& argv,
                                       const std::map<std::string, std::string>& env,
                                       double timeout_s = 120) {
    const std::string log = dir_ + "/run-" + std::to_string(runs_++) + ".log";
    SpawnOptions o;
    o.argv = argv;
    o.env = env;
    o.env["ROVER_STATE_DIR"] = state_root_;
    o.stdout_path = log;
    o.stderr_path = dir_ + "/run-" + std::to_string(runs_ - 1) + ".err";
    auto p = Process::Spawn(o);
    EXPECT_TRUE(p.ok()) << p.status().message();
    auto e = p->WaitFor(std::chrono::duration_cast<Duration>(std::chrono::duration<double>(timeout_s)));
    if (!e) e = p->Terminate(std::chrono::seconds(5));
    return {*e, testing::ReadFile(log) + testing::ReadFile(o.stderr_path)};
  }

  std::pair<ExitInfo, std::string> Roverctl(const std::vector<std::string>& args) {
    std::vector<std::string> argv = {testing::BinDir() + "/roverctl"};
    argv.insert(argv.end(), args.begin(), args.end());
    return Run(argv, {});
  }

  // Starts an intruder (or observer) in the background; its JSON line goes to `out`.
  Process Intruder(const std::string& out, const std::map<std::string, std::string>& env,
                   std::vector<std::string> args) {
    SpawnOptions o;
    o.argv = {testing::BinDir() + "/rover-intruder", "--domain", std::to_string(domain_)};
    o.argv.insert(o.argv.end(), args.begin(), args.end());
    o.env = env;
    o.stdout_path = out;
    o.stderr_path = out + ".err";
    auto p = Process::Spawn(o);
    EXPECT_TRUE(p.ok()) << p.status().message();
    return std::move(*p);
  }

  nlohmann::json Report(Process& p, const std::string& out) {
    auto e = p.WaitFor(std::chrono::seconds(60));
    if (!e) e = p.Terminate(std::chrono::seconds(5));
    EXPECT_TRUE(e->success()) << e->ToString() << testing::ReadFile(out + ".err");
    try {
      return nlohmann::json::parse(testing::ReadFile(out));
    } catch (...) {
      ADD_FAILURE() << out << ": " << testing::ReadFile(out) << testing::ReadFile(out + ".err");
      return nlohmann::json::object();
    }
  }

  std::map<std::string, std::string> As(const std::string& keys, const std::string& role) {
    return {{"ROVER_SECURITY_DIR", keys}, {"ROVER_SECURITY_IDENTITY", role}};
  }

  std::string dir_, state_root_, keys_, project_;
  int domain_ = -1;
  Process up_;
  int runs_ = 0;
};

TEST_F(SecurityTest, IntrudersCommandNothingAndReadNothing) {
  // Keys: this site's, and another authority's.
  auto [init_exit, init_out] = Roverctl({"security", "init"});
  ASSERT_TRUE(init_exit.success()) << init_out;
  const std::string other = dir_ + "/other-keys";
  auto [other_exit, other_out] = Roverctl({"--security-dir", other, "security", "init"});
  ASSERT_TRUE(other_exit.success()) << other_out;

  // A secured set: a pose publisher and the drive-primitive service.
  project_ = "sec" + std::to_string(getpid());
  const std::string file = dir_ + "/secured.compose.yaml";
  std::ofstream(file) << "x-rover: {project: " << project_ << ", security: enabled}\n"
                         "services:\n"
                         "  ddl-smoke: {command: ddl-smoke --set rate_hz=50}\n"
                         "  dl-smoke: {command: dl-smoke}\n"
                         "  dl-locomotion: {command: dl-locomotion}\n";
  SpawnOptions o;
  o.argv = {testing::BinDir() + "/roverctl", "up", file};
  o.env["ROVER_STATE_DIR"] = state_root_;
  o.stdout_path = dir_ + "/up.log";
  o.stderr_path = dir_ + "/up.log";
  auto up = Process::Spawn(o);
  ASSERT_TRUE(up.ok());
  up_ = std::move(*up);
  nlohmann::json state;
  ASSERT_TRUE(testing::WaitFor(
      [&] {
        std::ifstream in(state_root_ + "/" + project_ + "/state.json");
        if (!in) return false;
        try {
          state = nlohmann::json::parse(in);
        } catch (...) {
          return false;
        }
        return state.value("phase", "") == "up";
      },
      std::chrono::seconds(60)))
      << testing::ReadFile(dir_ + "/up.log");
  domain_ = state["domain"];
  EXPECT_EQ(state["security_dir"], keys_);

  // The observer (the scenario runner's identity reads everything) watches the intruders' ids
  // for the whole test; the permitted operator (rover-drive) commands with id 104.
  const std::string obs_out = dir_ + "/observer.json";
  Process observer = Intruder(obs_out, As(keys_, "scenario-runner"),
                              {"--seconds", "16", "--observe", "101,102,103,104"});
  sleep(2);  // the observer has matched the set
  Process none = Intruder(dir_ + "/none.json", {}, {"--seconds", "8", "--command-id", "101"});
  Process foreign = Intruder(dir_ + "/foreign.json", As(other, "scenario-runner"),
                             {"--seconds", "8", "--command-id", "102"});
  Process unpermitted = Intruder(dir_ + "/unpermitted.json", As(keys_, "fault-controller"),
                                 {"--seconds", "8", "--command-id", "103"});
  Process permitted = Intruder(dir_ + "/permitted.json", As(keys_, "rover-drive"),
                               {"--seconds", "8", "--command-id", "104"});
  const nlohmann::json n = Report(none, dir_ + "/none.json");
  const nlohmann::json f = Report(foreign, dir_ + "/foreign.json");
  const nlohmann::json u = Report(unpermitted, dir_ + "/unpermitted.json");
  const nlohmann::json p = Report(permitted, dir_ + "/permitted.json");
  const nlohmann::json obs = Report(observer, obs_out);
  std::printf("observer %s\nno certificate %s\nforeign authority %s\nunpermitted %s\n"
              "permitted %s\n",
              obs.dump().c_str(), n.dump().c_str(), f.dump().c_str(), u.dump().c_str(),
              p.dump().c_str());

  // The trusted observer saw the set (poses) and the permitted operator's commands obeyed...
  EXPECT_GT(obs.value("pose_samples", 0), 0) << obs.dump();
  EXPECT_GT(obs["statuses"].value("104", 0), 0) << obs.dump() << p.dump();
  // ...and no status for any intruder's command: none was obeyed.
  for (const char* id : {"101", "102", "103"}) {
    EXPECT_EQ(obs["statuses"].value(id, -1), 0) << id << " " << obs.dump();
  }
  // No intruder read a pose. Without a certificate and with a foreign one, the participant is
  // made but never matched; the unpermitted identity may not even create the endpoints.
  EXPECT_EQ(n.value("pose_samples", -1), 0) << n.dump();
  EXPECT_EQ(f.value("pose_samples", -1), 0) << f.dump();
  EXPECT_EQ(u.value("pose_samples", 0), 0) << u.dump();
  EXPECT_NE(u.value("writer", ""), "ok") << u.dump();
  EXPECT_NE(u.value("pose_reader", ""), "ok") << u.dump();
  // The open and foreign intruders did write: DDS Security, not a failed write, stopped them.
  EXPECT_GT(n.value("written", 0), 0) << n.dump();
  EXPECT_GT(f.value("written", 0), 0) << f.dump();
  EXPECT_GT(p.value("written", 0), 0) << p.dump();

  // The foreign authority's participant could read (its own permissions allow it) and still
  // got nothing: authentication, not access control, shut it out.
  EXPECT_EQ(f.value("pose_reader", ""), "ok") << f.dump();

  std::string logs;
  for (const auto& e : fs::directory_iterator(state_root_ + "/" + project_ + "/logs")) {
    logs += testing::ReadFile(e.path().string());
  }
  // The set's services log the foreign certificate's failed handshakes; the others never got
  // as far as a handshake (no certificate) or as a writer (no permission).
  EXPECT_NE(logs.find("Certificate not valid"), std::string::npos) << logs.substr(0, 4000);

  // roverctl's own tools join the secured set with their identities (state.json names the
  // keys): a recording of dl/pose, a replay of it, the fault agents' list.
  const std::string rec = dir_ + "/pose.mcap";
  auto [rec_exit, rec_out] = Roverctl({"record", "-p", project_, "-o", rec, "--topics",
                                       "dl/pose", "--duration", "2"});
  EXPECT_TRUE(rec_exit.success()) << rec_out;
  auto [info_exit, info_out] = Roverctl({"info", rec});
  EXPECT_NE(info_out.find("dl/pose"), std::string::npos) << info_out;
  auto [rep_exit, rep_out] =
      Roverctl({"replay", rec, "-p", project_, "--force", "--no-clock", "--rate", "4"});
  EXPECT_TRUE(rep_exit.success()) << rep_out;
  auto [add_exit, add_out] = Roverctl(
      {"fault", "add", "{kind: drop, topic: dl/pose, service: dl-locomotion}", "-p", project_});
  EXPECT_TRUE(add_exit.success()) << add_out;
  auto [fault_exit, fault_out] = Roverctl({"fault", "list", "-p", project_});
  EXPECT_TRUE(fault_exit.success()) << fault_out;
  EXPECT_NE(fault_out.find("dl-locomotion"), std::string::npos) << fault_out;
  EXPECT_NE(fault_out.find("drop"), std::string::npos) << fault_out;

  up_.Signal(SIGINT);
  auto e = up_.WaitFor(std::chrono::seconds(30));
  EXPECT_TRUE(e.has_value());
}

TEST_F(SecurityTest, ASetWithMissingKeysStartsNothing) {
  project_ = "nokeys" + std::to_string(getpid());
  const std::string file = dir_ + "/secured.compose.yaml";
  std::ofstream(file) << "x-rover: {project: " << project_ << ", security: enabled}\n"
                         "services:\n"
                         "  ddl-smoke: {command: ddl-smoke}\n";
  auto [exit, out] = Roverctl({"up", file});
  EXPECT_FALSE(exit.success());
  EXPECT_NE(out.find("x-rover.security: " + keys_ +
                     "/ca.pem: missing CA certificate (run `roverctl security init`)"),
            std::string::npos)
      << out;
  EXPECT_TRUE(ProcessesWithEnvironment("ROVER_PROJECT", project_).empty());
  // Keys made, then one service's certificate lost.
  auto [init_exit, init_out] = Roverctl({"security", "init"});
  ASSERT_TRUE(init_exit.success()) << init_out;
  fs::remove(keys_ + "/identities/ddl-smoke.pem");
  auto [exit1, out1] = Roverctl({"up", file});
  EXPECT_FALSE(exit1.success());
  EXPECT_NE(out1.find("identities/ddl-smoke.pem: missing identity certificate"),
            std::string::npos)
      << out1;
  EXPECT_TRUE(ProcessesWithEnvironment("ROVER_PROJECT", project_).empty());
  // A service whose executable has no role is named.
  std::ofstream(file) << "x-rover: {project: " << project_ << ", security: enabled}\n"
                         "services:\n"
                         "  sleeper: {command: sleep 30}\n";
  auto [exit2, out2] = Roverctl({"up", file});
  EXPECT_FALSE(exit2.success());
  EXPECT_NE(out2.find("services.sleeper: x-rover.security is enabled but 'sleep' has no DDS "
                      "Security role"),
            std::string::npos)
      << out2;
}

}  // namespace
}  // namespace rover
