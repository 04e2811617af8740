// Fault campaigns without processes: the campaign file's validation, the judging of one run
// (detection, response, safety, goal) and the table, with scripted runs that write result.json
// as RunScenario does, so that the report read back from the folder is checked too.
#include "rover/deploy/fault_campaign.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>

#include "rover/testing/test_support.hpp"

namespace rover::deploy {
namespace {
namespace fs = std::filesystem;

constexpr const char* kTwoFaults = R"(# two faults
- name: no pose
  kind: drop
  topic: dl/pose
  probability: 1
  start_s: 20
- name: frozen imu
  kind: freeze
  topic: ddl/imu
  start_s: 30
  duration_s: 5
)";

TEST(CampaignFile, ParsesFaultsWithLabelsAndNames) {
  auto f = ParseCampaignFaults(kTwoFaults, "c.yaml");
  ASSERT_TRUE(f.ok()) << f.status().message();
  ASSERT_EQ(f->size(), 2u);
  EXPECT_EQ((*f)[0].label, "01-no-pose");
  EXPECT_EQ((*f)[0].name, "no pose");
  EXPECT_EQ((*f)[1].label, "02-frozen-imu");
  EXPECT_DOUBLE_EQ((*f)[1].fault.spec.start_s, 30);
  // The same list under `faults:`.
  auto g = ParseCampaignFaults("faults:\n  - {kind: drop, topic: dl/pose}\n", "c.yaml");
  ASSERT_TRUE(g.ok()) << g.status().message();
  EXPECT_EQ((*g)[0].label.substr(0, 3), "01-");
}

TEST(CampaignFile, KillEntries) {
  auto f = ParseCampaignFaults(
      "- {kind: drop, topic: dl/pose}\n- name: kill pose\n  kill: {service: dl-pose, at_s: 30}\n"
      "- kill: {service: dl-stereo, at_s: 12.5}\n",
      "c.yaml");
  ASSERT_TRUE(f.ok()) << f.status().message();
  ASSERT_EQ(f->size(), 3u);
  EXPECT_FALSE((*f)[0].kill.has_value());
  ASSERT_TRUE((*f)[1].kill.has_value());
  EXPECT_EQ((*f)[1].kill->service, "dl-pose");
  EXPECT_DOUBLE_EQ((*f)[1].start_s(), 30);
  EXPECT_EQ((*f)[1].label, "02-kill-pose");
  EXPECT_EQ((*f)[1].source, "c.yaml:2");
  EXPECT_EQ((*f)[2].name, "kill -9 dl-stereo at 12.5 s");
  // A kill names a service of the scenario's compose file.
  const std::string dir = rover::testing::MakeTempDir("campaign-kill");
  std::ofstream(dir + "/set.yaml") << "services:\n  dl-pose:\n    command: dl-pose\n";
  Scenario sc;
  sc.compose_path = dir + "/set.yaml";
  const Status s = CheckCampaignKills(sc, *f);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("c.yaml:4: key 'kill.service': no service 'dl-stereo'"),
            std::string::npos)
      << s.message();
  f->pop_back();
  EXPECT_TRUE(CheckCampaignKills(sc, *f).ok()) << CheckCampaignKills(sc, *f).message();
  std::error_code ec;
  fs::remove_all(dir, ec);
}

TEST(CampaignFile, ErrorsNameFileLineAndKey) {
  auto bad_kind = ParseCampaignFaults("- {kind: drop, topic: dl/pose}\n- {kind: dorp, topic: dl/pose}\n",
                                      "c.yaml");
  ASSERT_FALSE(bad_kind.ok());
  EXPECT_NE(bad_kind.status().message().find("c.yaml:2"), std::string::npos)
      << bad_kind.status().message();
  EXPECT_NE(bad_kind.status().message().find("kind"), std::string::npos);

  auto kill_key = ParseCampaignFaults("- name: kill pose\n  kill: {service: dl-pose, when: 30}\n",
                                      "c.yaml");
  ASSERT_FALSE(kill_key.ok());
  EXPECT_NE(kill_key.status().message().find("c.yaml:2"), std::string::npos)
      << kill_key.status().message();
  EXPECT_NE(kill_key.status().message().find("'when'"), std::string::npos);
  auto kill_time = ParseCampaignFaults("- kill: {service: dl-pose, at_s: -1}\n", "c.yaml");
  ASSERT_FALSE(kill_time.ok());
  EXPECT_NE(kill_time.status().message().find("kill.at_s"), std::string::npos)
      << kill_time.status().message();
  auto kill_and_kind = ParseCampaignFaults("- {kind: drop, kill: {service: dl-pose, at_s: 3}}\n",
                                           "c.yaml");
  EXPECT_FALSE(kill_and_kind.ok());

  auto prob = ParseCampaignFaults("- {kind: drop, topic: dl/pose, probability: 1.5}\n", "c.yaml");
  ASSERT_FALSE(prob.ok());
  EXPECT_NE(prob.status().message().find("probability"), std::string::npos);

  auto key = ParseCampaignFaults("faults: []\nseeds: 3\n", "c.yaml");
  ASSERT_FALSE(key.ok());
  EXPECT_NE(key.status().message().find("c.yaml:2: key 'seeds'"), std::string::npos)
      << key.status().message();
  EXPECT_FALSE(ParseCampaignFaults("[]\n", "c.yaml").ok());
  EXPECT_FALSE(ParseCampaignFaults("- {kind: drop, topic: no/such_topic}\n", "c.yaml").ok());
}

// A run as the scripted "stack" behaves: the baseline drives 4 m; with dl/pose gone, locomotion
// reports it stale 0.4 s after the fault and fails the step; a frozen IMU goes unnoticed.
RunResult ScriptedRun(const Scenario& sc, std::uint32_t seed, const std::string& dir) {
  RunResult r;
  r.scenario = sc.name;
  r.seed = seed;
  r.wall_time_s = 5;
  r.health_changes = {{0.5, "dl-pose", "degraded", "levelling"}, {12, "dl-pose", "ok", ""}};
  r.criteria = {{"max_tilt", 2, 10, "deg", true, ""},
                {"hazard_contacts", 0, std::numeric_limits<double>::quiet_NaN(), "count", true, ""},
                {"final_position_error", 0.1, 0.3, "m", true, ""}};
  StepResult step{"straight", 1, "done", "nominal", "", 13, 50};
  const bool no_pose = !sc.faults.empty() && sc.faults.back().spec.topic == "dl/pose";
  if (!sc.faults.empty()) {
    InjectedFault f;
    f.id = sc.faults.back().spec.id;
    f.kind = "x";
    f.start_s = sc.faults.back().spec.start_s;
    f.samples_hit = 42;
    r.faults.push_back(f);
  }
  if (no_pose) {
    r.health_changes.push_back({20.4, "dl-locomotion", "stale", "dl/pose stale for 0.4 s"});
    step.state = "failed";
    step.termination = "stale_pose";
    step.sim_end_s = 20.6;
    r.criteria[2] = {"final_position_error", 2.0, 0.3, "m", false, ""};
    r.failure = "final_position_error: 2.0 m";
  }
  // Seed 2's frozen IMU tips the rover over (so that an unsafe, undetected run is counted).
  if (!sc.faults.empty() && sc.faults.back().spec.topic == "ddl/imu" && seed == 2) {
    r.criteria[0] = {"max_tilt", 14, 10, "deg", false, ""};
    r.failure = "max_tilt: 14 deg";
  }
  r.steps = {step};
  r.pass = r.failure.empty();
  r.run_dir = dir + "/" + sc.name + "-seed" + std::to_string(seed);
  fs::create_directories(r.run_dir);
  std::ofstream(r.run_dir + "/result.json") << ToJson(r).dump(2) << "\n";
  return r;
}

TEST(CampaignJudging, DetectionResponseSafetyGoal) {
  Scenario sc;
  sc.name = "tiny";
  auto faults = ParseCampaignFaults(kTwoFaults, "c.yaml");
  ASSERT_TRUE(faults.ok());
  const std::string dir = rover::testing::MakeTempDir("fault-judging");
  Scenario with = sc;
  with.faults.push_back((*faults)[0].fault);
  const RunResult base = ScriptedRun(sc, 1, dir);
  const RunResult hit = ScriptedRun(with, 1, dir + "/f");
  // The levelling message before the fault is not a detection of it.
  EXPECT_FALSE(FirstDetection(base, 20).detected);
  EXPECT_TRUE(FirstDetection(base, 0).detected);
  const Detection d = FirstDetection(hit, 20);
  ASSERT_TRUE(d.detected);
  EXPECT_DOUBLE_EQ(d.t_s, 20.4);
  EXPECT_NE(d.by.find("sys/health dl-locomotion stale: dl/pose stale"), std::string::npos) << d.by;
  EXPECT_EQ(Response(hit, 20), "stopped");
  EXPECT_EQ(Response(base, 20), "none");
  EXPECT_TRUE(IsSafe(hit));
  EXPECT_TRUE(GoalReached(base));
  EXPECT_FALSE(GoalReached(hit));
  RunResult crashed = hit;
  crashed.crashes = {"dl-pose: killed by signal 11"};
  EXPECT_EQ(Response(crashed, 20), "crashed");
  RunResult killed = base;
  killed.kills = {{"dl-pose", 30, 30.1, 31.2, ""}};
  EXPECT_EQ(Response(killed, 30.1), "restarted");
  RunResult unjudged;
  unjudged.failure = "service set did not start";
  std::string why;
  EXPECT_FALSE(IsSafe(unjudged, &why));
  EXPECT_NE(why.find("not judged"), std::string::npos);
  // A mobility fault counts as detection, at the time of its terminal status.
  RunResult mob = base;
  mob.mobility.emplace();
  mob.mobility->fault = "SAPP";
  mob.mobility->outcome = "SAPP";
  mob.mobility->sim_end_s = 25;
  const Detection m = FirstDetection(mob, 22);
  EXPECT_TRUE(m.detected);
  EXPECT_DOUBLE_EQ(m.t_s, 25);
  EXPECT_EQ(Response(mob, 22), "stopped");
  EXPECT_FALSE(GoalReached(mob));
  // sim/clock frozen at 20 s under strict lock-step: the run stalls with its clock at the last
  // tick (19.99 s) and rover-sim's lock-step alarm, taken after the start, carries that tick.
  RunResult frozen = base;
  frozen.sim_time_s = 19.99;
  frozen.health_changes.push_back({19.99, "rover-sim", "failed", "lock-step stalled"});
  const Detection f = FirstDetection(frozen, 20);
  ASSERT_TRUE(f.detected);
  EXPECT_DOUBLE_EQ(f.t_s, 20);
  EXPECT_NE(f.by.find("lock-step stalled"), std::string::npos);
  frozen.sim_time_s = 40;  // a clock that ran on: 19.99 s is before the start
  EXPECT_FALSE(FirstDetection(frozen, 20).detected);
  std::error_code ec;
  fs::remove_all(dir, ec);
}

class FaultCampaignRun : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = rover::testing::MakeTempDir("fault-campaign");
    scenario_.name = "tiny";
    scenario_.file = dir_ + "/tiny.yaml";
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  FaultCampaignOptions Options() {
    FaultCampaignOptions o;
    o.seeds = {1, 2};
    o.jobs = 2;
    o.out_dir = dir_ + "/out";
    o.run_one = [this](const Scenario& sc, std::uint32_t seed, const RunOptions& ro) {
      {
        std::lock_guard lock(mu_);
        ++runs_;
      }
      return Result<RunResult>(ScriptedRun(sc, seed, ro.out_dir));
    };
    return o;
  }
  std::string dir_;
  Scenario scenario_;
  std::mutex mu_;
  int runs_ = 0;
};

TEST_F(FaultCampaignRun, TableShapeSharesAndReport) {
  auto faults = ParseCampaignFaults(kTwoFaults, "c.yaml");
  ASSERT_TRUE(faults.ok());
  auto t = RunFaultCampaign(scenario_, "c.yaml", *faults, Options());
  ASSERT_TRUE(t.ok()) << t.status().message();
  EXPECT_EQ(runs_, 6);  // (baseline + 2 faults) x 2 seeds
  ASSERT_EQ(t->rows.size(), 6u);
  EXPECT_EQ(t->rows[0].fault, "baseline");
  EXPECT_EQ(t->rows[2].fault, "01-no-pose");
  EXPECT_EQ(t->rows[4].fault, "02-frozen-imu");
  for (int i : {2, 3}) {
    const CampaignRow& r = t->rows[static_cast<std::size_t>(i)];
    EXPECT_TRUE(r.detected);
    EXPECT_NEAR(r.detection_delay_s, 0.4, 1e-9);
    EXPECT_EQ(r.response, "stopped");
    EXPECT_TRUE(r.safe);
    EXPECT_FALSE(r.goal);
    EXPECT_TRUE(r.baseline_goal);
    EXPECT_TRUE(r.differs);
    EXPECT_EQ(r.samples_hit, 42u);
  }
  EXPECT_FALSE(t->rows[4].detected);
  EXPECT_FALSE(t->rows[4].differs);  // seed 1: unnoticed and harmless
  EXPECT_FALSE(t->rows[5].safe);     // seed 2: unnoticed and unsafe
  EXPECT_TRUE(t->rows[5].differs);
  // Relevant: both no-pose runs and the unsafe frozen-IMU run; two of them detected.
  EXPECT_EQ(t->relevant, 3);
  EXPECT_EQ(t->detected, 2);
  EXPECT_EQ(t->detected_within_1s, 2);
  EXPECT_EQ(t->fault_runs, 4);
  EXPECT_EQ(t->safe_runs, 3);
  EXPECT_EQ(t->missing, 0);

  const std::string out = dir_ + "/out";
  for (const char* f : {"campaign.json", "campaign.txt", "summary.txt",
                        "baseline/tiny-seed1/result.json", "01-no-pose/tiny-seed2/result.json"}) {
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  }
  const std::string summary = rover::testing::ReadFile(out + "/summary.txt");
  const std::string tail = "detection: 2 of 3 fault runs detected (67%; 2 within 1 s), counting "
                           "the runs that were detected or whose outcome differs from the "
                           "baseline\nsafe: 3 of 4 fault runs safe (75%)\n";
  ASSERT_GE(summary.size(), tail.size());
  EXPECT_EQ(summary.substr(summary.size() - tail.size()), tail) << summary;
  EXPECT_NE(summary.find("UNSAFE tilt 14.0 deg over 10.0"), std::string::npos) << summary;
  EXPECT_TRUE(IsFaultCampaignFolder(out));

  // The report rebuilds the same table from the folder (its wall time aside).
  auto back = LoadFaultCampaignReport(out);
  ASSERT_TRUE(back.ok()) << back.status().message();
  FaultCampaignTable expect = *t;
  EXPECT_EQ(FormatCampaignTable(*back), FormatCampaignTable(expect));
  // A fault that makes a figure unmeasurable (a NaN pose) leaves null in result.json; the
  // report still reads the folder (it once stopped at "type must be number, but is null").
  {
    const std::string f = out + "/01-no-pose/tiny-seed2/result.json";
    nlohmann::json j = nlohmann::json::parse(rover::testing::ReadFile(f));
    ASSERT_FALSE(j["criteria"].empty());
    j["criteria"][0]["measured"] = nullptr;
    std::ofstream(f) << j.dump(2);
    auto with_null = LoadFaultCampaignReport(out);
    ASSERT_TRUE(with_null.ok()) << with_null.status().message();
    EXPECT_EQ(with_null->rows.size(), t->rows.size());
  }

  // The folder holds this scenario's fault campaign: another scenario is refused, and so is a
  // plain folder.
  EXPECT_TRUE(CheckFaultCampaignFolder(out, "tiny").ok());
  EXPECT_FALSE(CheckFaultCampaignFolder(out, "other").ok());
  fs::create_directories(dir_ + "/plain");
  std::ofstream(dir_ + "/plain/notes.txt") << "mine\n";
  EXPECT_FALSE(CheckFaultCampaignFolder(dir_ + "/plain", "tiny").ok());
}

TEST_F(FaultCampaignRun, MissingRunsAreCounted) {
  auto faults = ParseCampaignFaults(kTwoFaults, "c.yaml");
  ASSERT_TRUE(faults.ok());
  std::map<std::string, std::vector<RunResult>> results;
  results["baseline"].push_back(ScriptedRun(scenario_, 1, dir_));
  const FaultCampaignTable t = MakeCampaignTable("tiny", "c.yaml", {1}, *faults, results);
  EXPECT_EQ(t.rows.size(), 3u);
  EXPECT_EQ(t.missing, 2);
  EXPECT_EQ(t.fault_runs, 0);
  const std::string text = FormatCampaignTable(t);
  EXPECT_NE(text.find("2 runs have no result"), std::string::npos) << text;
  EXPECT_NE(text.find("safe: 0 of 0 fault runs safe (n/a)"), std::string::npos) << text;
}

}  // namespace
}  // namespace rover::deploy
