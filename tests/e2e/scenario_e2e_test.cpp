// `roverctl run` end to end with the real service set: pass, fail on purpose, parallel runs that
// must not cross-talk, Ctrl-C, and same seed -> the same figures bit for bit (strict lock-step).
#include <gtest/gtest.h>
#include <signal.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <nlohmann/json.hpp>

#include "rover/base/process.hpp"
#include "rover/deploy/run_report.hpp"
#include "rover/testing/roverctl_runner.hpp"
#include "rover/testing/test_support.hpp"

namespace rover {
namespace {
namespace fs = std::filesystem;

class ScenarioE2e : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::UseLoopbackDds();  // roverctl inherits it, whatever the shell exported
    dir_ = testing::MakeTempDir("scenario-e2e");
    roverctl_.emplace(dir_);
  }
  void TearDown() override {
    KillLeftovers();
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  // What this test's runs started and left behind (testing::RoverctlRunner).
  std::vector<pid_t> Leftovers() const { return roverctl_->Leftovers(); }
  void KillLeftovers() { roverctl_->KillLeftovers(); }
  std::string Scenario(const std::string& name) {
    return testing::SourceDir() + "/tests/e2e/scenarios/" + name;
  }
  Process Start(const std::vector<std::string>& args, const std::string& log) {
    auto p = roverctl_->Start(args, log);
    return std::move(*p);
  }
  std::pair<ExitInfo, std::string> Run(const std::vector<std::string>& args) {
    return roverctl_->Run(args);
  }
  static nlohmann::json Json(const std::string& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
  }
  std::string dir_;
  std::optional<testing::RoverctlRunner> roverctl_;
};

TEST_F(ScenarioE2e, PassingAndDeliberatelyFailingScenarios) {
  auto [ok_exit, ok_out] = Run({"run", Scenario("short_drive.yaml"), "--out", dir_ + "/pass"});
  EXPECT_EQ(ok_exit.code, 0) << ok_out;
  const auto pass = Json(dir_ + "/pass/short-drive-seed1/result.json");
  EXPECT_TRUE(pass["pass"].get<bool>()) << pass.dump(2);
  for (const char* f : {"map.png", "estimate_error.png", "logs/rover-sim.log", "logs/dl-pose.log"}) {
    EXPECT_TRUE(fs::exists(dir_ + "/pass/short-drive-seed1/" + f)) << f;
  }
  EXPECT_EQ(std::system(("xmllint --noout " + dir_ + "/pass/junit.xml").c_str()), 0);

  auto [bad_exit, bad_out] =
      Run({"run", Scenario("short_drive_wrong_target.yaml"), "--out", dir_ + "/fail"});
  EXPECT_EQ(bad_exit.code, 1) << bad_out;
  const auto fail = Json(dir_ + "/fail/short-drive-wrong-target-seed1/result.json");
  EXPECT_FALSE(fail["pass"].get<bool>());
  // The JSON says which criterion failed and by how much (about 2 m beyond its 0.3 m limit).
  bool found = false;
  for (const auto& c : fail["criteria"]) {
    if (c["name"] == "final_position_error") {
      found = true;
      EXPECT_FALSE(c["pass"].get<bool>());
      EXPECT_NEAR(c["measured"].get<double>(), 2.0, 0.4);
      EXPECT_EQ(c["limit"].get<double>(), 0.3);
    }
  }
  EXPECT_TRUE(found) << fail.dump(2);
  EXPECT_NE(fail["failure"].get<std::string>().find("final_position_error"), std::string::npos);
  // `roverctl report` re-prints the table.
  auto [rep_exit, rep_out] = Run({"report", dir_ + "/fail"});
  EXPECT_EQ(rep_exit.code, 1);
  EXPECT_NE(rep_out.find("0/1 passed"), std::string::npos) << rep_out;
}

// Each off-nominal termination of the drive primitives, triggered in the simulator: the scenario
// passes only if its step ends with the termination it expects.
// A scenario's `faults:` reach the services at start and act on simulated time; the run report
// lists each with its window and the samples it touched (result.json and summary.txt).
TEST_F(ScenarioE2e, ScenarioFaultsAreInjectedAndListedInTheRunReport) {
  auto [e, out] = Run({"run", Scenario("short_drive_faults.yaml"), "--out", dir_ + "/faults"});
  const std::string run = dir_ + "/faults/short-drive-faults-seed1";
  ASSERT_TRUE(fs::exists(run + "/result.json")) << out;
  const auto result = Json(run + "/result.json");
  ASSERT_EQ(result["faults"].size(), 1u) << result["faults"].dump(2) << out;
  const auto& f = result["faults"][0];
  EXPECT_EQ(f["id"], 1);
  EXPECT_EQ(f["name"], "sun dropouts");
  EXPECT_EQ(f["kind"], "drop");
  EXPECT_EQ(f["topic"], "ddl/sun_sensor");
  EXPECT_EQ(f["side"], "writer");
  EXPECT_DOUBLE_EQ(f["start_s"].get<double>(), 1.0) << f.dump(2);
  EXPECT_EQ(f["services"], nlohmann::json::array({"ddl-sun-sensor"})) << f.dump(2);
  EXPECT_GT(f["samples_seen"].get<std::uint64_t>(), 0u) << f.dump(2);
  EXPECT_GT(f["samples_hit"].get<std::uint64_t>(), 0u) << f.dump(2);
  EXPECT_LT(f["samples_hit"].get<std::uint64_t>(), f["samples_seen"].get<std::uint64_t>());
  // The services said so too, in their logs (msg="fault" event=started ...).
  EXPECT_NE(testing::ReadFile(run + "/logs/ddl-sun-sensor.log").find("event=started"), std::string::npos);
  const std::string summary = testing::ReadFile(dir_ + "/faults/summary.txt");
  EXPECT_NE(summary.find("fault 1 'sun dropouts' drop ddl/sun_sensor (writer of ddl-sun-sensor): 1.0 s"),
            std::string::npos)
      << summary;
}

TEST_F(ScenarioE2e, OffNominalTerminationsInTheSimulator) {
  for (const char* name : {"terminate_tilt", "terminate_stall", "terminate_timeout", "terminate_stop"}) {
    const std::string out = dir_ + "/" + name;
    auto [e, log] = Run({"run", Scenario(std::string(name) + ".yaml"), "--out", out});
    EXPECT_EQ(e.code, 0) << name << "\n" << log;
    auto runs = deploy::LoadRunFolder(out);
    ASSERT_TRUE(runs.ok()) << runs.status().message();
    ASSERT_EQ(runs->size(), 1u);
    ASSERT_FALSE((*runs)[0].steps.empty()) << name;
    EXPECT_EQ((*runs)[0].steps[0].state, "failed") << name;
  }
}

TEST_F(ScenarioE2e, ParallelRunsDoNotCrossTalkAndSameSeedSameOutcome) {
  auto [e, out] = Run({"run", Scenario("short_drive.yaml"), "--seeds", "1..2", "--jobs", "2",
                       "--out", dir_ + "/par"});
  EXPECT_EQ(e.code, 0) << out;
  auto runs = deploy::LoadRunFolder(dir_ + "/par");
  ASSERT_TRUE(runs.ok()) << runs.status().message();
  ASSERT_EQ(runs->size(), 2u);
  EXPECT_NE((*runs)[0].domain, (*runs)[1].domain);
  for (const auto& r : *runs) {
    const auto j = Json(r.run_dir + "/result.json");
    // Each run heard exactly one simulator: no cross-talk between the parallel sets.
    EXPECT_EQ(j["truth_publishers"].get<int>(), 1) << r.run_dir;
    EXPECT_TRUE(r.pass) << r.failure;
  }
  // Same seed again, alone and with DDS Security (docs/security.md: every participant
  // authenticated, every sample encrypted): same terrain and the same outcome.
  const std::string keys = dir_ + "/keys";
  auto [ke, kout] = Run({"--security-dir", keys, "security", "init"});
  ASSERT_EQ(ke.code, 0) << kout;
  auto [e2, out2] = Run({"--security-dir", keys, "run", Scenario("short_drive.yaml"), "--seeds",
                         "1", "--security", "--out", dir_ + "/again"});
  EXPECT_EQ(e2.code, 0) << out2;
  const auto a = Json(dir_ + "/par/short-drive-seed1/result.json");
  const auto b = Json(dir_ + "/again/short-drive-seed1/result.json");
  EXPECT_EQ(a["pass"], b["pass"]);
  EXPECT_EQ(a["terrain_digest"], b["terrain_digest"]);
  // Strict lock-step (the default): the same figures bit for bit, although one run had a
  // neighbour (--jobs 2) and the other ran alone and secured.
  EXPECT_EQ(a["timings"]["lockstep"], "strict");
  EXPECT_EQ(a["timings"]["late_samples"], 0);
  EXPECT_EQ(b["timings"]["late_samples"], 0);
  for (const char* key : {"criteria", "figures", "steps", "distance_driven_m", "estimate_error",
                          "odometry_only_error", "truth_track", "estimate_track"}) {
    EXPECT_EQ(a[key], b[key]) << key << ":\n--jobs 2: " << a[key].dump().substr(0, 2000)
                              << "\n--jobs 1, secured: " << b[key].dump().substr(0, 2000);
  }
  EXPECT_EQ(a["timings"]["sim_time_s"], b["timings"]["sim_time_s"]);
  EXPECT_NE(a["terrain_digest"], Json(dir_ + "/par/short-drive-seed2/result.json")["terrain_digest"]);
}

TEST_F(ScenarioE2e, CtrlCStopsEverythingAndKeepsFinishedRuns) {
  Process p = Start({"run", Scenario("short_drive.yaml"), "--seeds", "1..3", "--jobs", "1", "--out",
                     dir_ + "/int"},
                    dir_ + "/int.log");
  ASSERT_TRUE(testing::WaitFor([&] { return fs::exists(dir_ + "/int/short-drive-seed1/result.json"); },
                               std::chrono::minutes(5)))
      << testing::ReadFile(dir_ + "/int.log");
  // Let the second run get under way, then interrupt.
  testing::WaitFor([&] { return fs::exists(dir_ + "/int/short-drive-seed2/logs"); }, std::chrono::seconds(60));
  p.Signal(SIGINT);
  auto e = p.WaitFor(std::chrono::minutes(2));
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->code, 1);
  EXPECT_TRUE(testing::WaitFor([&] { return Leftovers().empty(); }, std::chrono::seconds(30)));
  const auto summary = Json(dir_ + "/int/summary.json");
  EXPECT_TRUE(summary["interrupted"].get<bool>());
  EXPECT_GE(summary["runs"].get<int>(), 1);
  EXPECT_TRUE(Json(dir_ + "/int/short-drive-seed1/result.json")["pass"].get<bool>());
  EXPECT_FALSE(fs::exists(dir_ + "/int/short-drive-seed3/result.json"));
}


// The clean-up kills only what this test started: another engineer's run of the same scenario
// on this machine (same project prefix) is left alone.
TEST_F(ScenarioE2e, CleanUpLeavesOtherPeoplesRunsAlone) {
  SpawnOptions o;
  o.argv = {"sleep", "120"};
  o.env["ROVER_PROJECT"] = "short-drive-seed1-someone-else";
  auto other = Process::Spawn(o);
  ASSERT_TRUE(other.ok()) << other.status().message();
  ASSERT_TRUE(testing::WaitFor([&] {
    return testing::ReadFile("/proc/" + std::to_string(other->pid()) + "/environ")
               .find("ROVER_PROJECT=short-drive-seed1-someone-else") != std::string::npos;
  }));
  KillLeftovers();
  EXPECT_FALSE(other->WaitFor(std::chrono::milliseconds(500)).has_value())
      << "the clean-up killed a process this test did not start";
  EXPECT_TRUE(ProcessAlive(other->pid()));
  other->Terminate(std::chrono::seconds(1));
}

}  // namespace
}  // namespace rover
