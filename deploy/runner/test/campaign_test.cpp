// The campaign without processes: each seed's run is a scripted function that writes its
// result.json as RunScenario does.
#include "rover/deploy/campaign.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>
#include <unistd.h>

#include "rover/testing/test_support.hpp"

namespace rover::deploy {
namespace {
namespace fs = std::filesystem;

class CampaignTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = rover::testing::MakeTempDir("campaign-test");
    scenario_.name = "tiny";
    scenario_.file = dir_ + "/tiny.yaml";
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  // Seeds 1..n; even seeds fail a criterion, `error_seed` cannot be made at all.
  CampaignOptions Options(std::uint32_t n, int jobs, std::uint32_t error_seed = 0) {
    CampaignOptions o;
    for (std::uint32_t s = 1; s <= n; ++s) o.seeds.push_back(s);
    o.jobs = jobs;
    o.out_dir = dir_ + "/out";
    o.run_one = [this, error_seed](const Scenario& sc, std::uint32_t seed,
                                   const RunOptions& ro) -> Result<RunResult> {
      {
        std::lock_guard lock(mu_);
        started_.insert(seed);
      }
      if (ro.progress) ro.progress("step 1/1 straight", 1.5);
      if (seed == error_seed) return InvalidArgument("cannot create " + ro.out_dir);
      RunResult r;
      r.scenario = sc.name;
      r.seed = seed;
      r.pass = seed % 2 == 1;
      r.failure = r.pass ? "" : "final_position_error: 0.8 > 0.5 m";
      r.criteria.push_back(
          {"final_position_error", r.pass ? 0.1 * seed : 0.8, 0.5, "m", r.pass, ""});
      r.distance_driven = 4;
      r.sim_time_s = 100;
      r.wall_time_s = 10;
      r.run_dir = ro.out_dir + "/" + sc.name + "-seed" + std::to_string(seed);
      fs::create_directories(r.run_dir);
      std::ofstream(r.run_dir + "/result.json") << ToJson(r).dump(2) << "\n";
      if (abort_after_ == seed) abort_.store(true);
      return r;
    };
    o.abort = &abort_;
    return o;
  }
  std::string dir_;
  Scenario scenario_;
  std::mutex mu_;
  std::set<std::uint32_t> started_;
  std::atomic<bool> abort_{false};
  std::uint32_t abort_after_ = 0;
};

TEST_F(CampaignTest, RunsEverySeedAndWritesTheSummaries) {
  auto r = RunCampaign(scenario_, Options(5, 2, /*error_seed=*/5));
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_EQ(started_, (std::set<std::uint32_t>{1, 2, 3, 4, 5}));
  ASSERT_EQ(r->runs.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i) EXPECT_EQ(r->runs[i].seed, i + 1);  // by seed
  ASSERT_EQ(r->errors.size(), 1u);
  EXPECT_EQ(r->errors[0], "seed 5: cannot create " + dir_ + "/out");
  EXPECT_FALSE(r->interrupted);
  EXPECT_FALSE(r->all_passed());
  EXPECT_EQ(r->summary.runs, 4);
  EXPECT_EQ(r->summary.passed, 2);
  EXPECT_EQ(r->summary.scenario, "tiny");

  std::ifstream cj(dir_ + "/out/campaign.json");
  const auto campaign = nlohmann::json::parse(cj);
  EXPECT_EQ(campaign["seeds"].size(), 5u);
  EXPECT_EQ(campaign["jobs"], 2);
  std::ifstream sj(dir_ + "/out/summary.json");
  const auto summary = nlohmann::json::parse(sj);
  EXPECT_EQ(summary["runs"], 4);
  EXPECT_EQ(summary["passed"], 2);
  EXPECT_EQ(summary["errors"].size(), 1u);
  EXPECT_FALSE(summary["interrupted"].get<bool>());
  const std::string junit = rover::testing::ReadFile(dir_ + "/out/junit.xml");
  EXPECT_NE(junit.find("tests=\"4\" failures=\"2\""), std::string::npos) << junit;
  ASSERT_EQ(r->missing.size(), 1u);  // seed 5's run could not be made
  EXPECT_EQ(r->missing[0].seed, 5u);
  EXPECT_EQ(rover::testing::ReadFile(dir_ + "/out/summary.txt"),
            FormatSummaryTable(r->runs, r->summary, r->missing));
}

TEST_F(CampaignTest, ReportReprintsTheTableOfTheCampaign) {
  auto r = RunCampaign(scenario_, Options(3, 1));
  ASSERT_TRUE(r.ok()) << r.status().message();
  auto report = LoadCampaignReport(dir_ + "/out");
  ASSERT_TRUE(report.ok()) << report.status().message();
  EXPECT_EQ(report->table, rover::testing::ReadFile(dir_ + "/out/summary.txt"));
  EXPECT_FALSE(report->all_passed);  // seed 2 failed
  EXPECT_NE(report->table.find("tiny: 2/3 passed (67%)"), std::string::npos) << report->table;
}

// A report on a campaign whose roverctl still runs (campaign.json's pid alive, no summary.json)
// says so, with the runs finished so far, instead of a throughput of zero.
TEST_F(CampaignTest, ReportOnARunningCampaignSaysItRuns) {
  auto r = RunCampaign(scenario_, Options(3, 1));
  ASSERT_TRUE(r.ok()) << r.status().message();
  const std::string out = dir_ + "/out";
  nlohmann::json c;
  {
    std::ifstream in(out + "/campaign.json");
    c = nlohmann::json::parse(in);
  }
  EXPECT_EQ(c["pid"].get<int>(), static_cast<int>(getpid()));
  fs::remove(out + "/summary.json");
  fs::remove_all(out + "/tiny-seed3");
  auto running = LoadCampaignReport(out);
  ASSERT_TRUE(running.ok()) << running.status().message();
  EXPECT_TRUE(running->running);
  EXPECT_EQ(running->table.rfind("campaign still running (roverctl pid " +
                                     std::to_string(getpid()) +
                                     "): 2 of 3 runs finished so far",
                                 0),
            0u)
      << running->table;
  EXPECT_EQ(running->table.find("simulated s per wall s"), std::string::npos) << running->table;
  // The same folder once that roverctl is gone: an ordinary (incomplete) report.
  c["pid"] = 999999;
  std::ofstream(out + "/campaign.json") << c.dump(2);
  auto ended = LoadCampaignReport(out);
  ASSERT_TRUE(ended.ok());
  EXPECT_FALSE(ended->running);
  EXPECT_NE(ended->table.find("seed 3: not run"), std::string::npos) << ended->table;
}

TEST_F(CampaignTest, AllPassedOnlyWhenEveryRunPassed) {
  CampaignOptions o = Options(1, 1);
  auto r = RunCampaign(scenario_, o);
  ASSERT_TRUE(r.ok());
  EXPECT_TRUE(r->all_passed());
  auto report = LoadCampaignReport(dir_ + "/out");
  ASSERT_TRUE(report.ok());
  EXPECT_TRUE(report->all_passed);
}

TEST_F(CampaignTest, AbortKeepsFinishedRunsAndStartsNoMore) {
  abort_after_ = 2;
  auto r = RunCampaign(scenario_, Options(5, 1));
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_TRUE(r->interrupted);
  EXPECT_EQ(r->runs.size(), 2u);
  EXPECT_EQ(started_, (std::set<std::uint32_t>{1, 2}));
  EXPECT_FALSE(r->all_passed());
  std::ifstream sj(dir_ + "/out/summary.json");
  EXPECT_TRUE(nlohmann::json::parse(sj)["interrupted"].get<bool>());
}

TEST_F(CampaignTest, RejectsBadOptionsAndForeignFolders) {
  CampaignOptions o = Options(1, 1);
  o.jobs = 17;
  EXPECT_FALSE(RunCampaign(scenario_, o).ok());
  o = Options(0, 1);
  EXPECT_EQ(RunCampaign(scenario_, o).status().message(), "no seeds to run");
  // A folder with someone's files, not an earlier campaign, is refused.
  fs::create_directories(dir_ + "/mine");
  std::ofstream(dir_ + "/mine/notes.txt") << "keep me\n";
  EXPECT_FALSE(CheckOutputFolder(dir_ + "/mine").ok());
  EXPECT_TRUE(CheckOutputFolder(dir_ + "/nothing-here").ok());
  ASSERT_TRUE(RunCampaign(scenario_, Options(1, 1)).ok());
  EXPECT_TRUE(CheckOutputFolder(dir_ + "/out").ok());  // an earlier campaign may be re-run
  std::ofstream(dir_ + "/file") << "x";
  EXPECT_FALSE(CheckOutputFolder(dir_ + "/file").ok());
}


// A campaign folder holds one scenario: re-using it for another is refused, and a report never
// mixes two scenarios' runs.
TEST_F(CampaignTest, AFolderOfOneScenarioIsNotReusedForAnother) {
  ASSERT_TRUE(RunCampaign(scenario_, Options(2, 1)).ok());
  Scenario other = scenario_;
  other.name = "other";
  auto r = RunCampaign(other, Options(1, 1));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(),
            "--out " + dir_ + "/out: holds a campaign of scenario 'tiny', not 'other'; choose "
            "another folder");
  EXPECT_EQ(started_, (std::set<std::uint32_t>{1, 2}));  // nothing of 'other' ran
  // A folder mixed by hand (or by an older roverctl) reports only its campaign's scenario.
  RunResult stray;
  stray.scenario = "other";
  stray.seed = 9;
  stray.pass = true;
  fs::create_directories(dir_ + "/out/other-seed9");
  std::ofstream(dir_ + "/out/other-seed9/result.json") << ToJson(stray).dump(2) << "\n";
  auto report = LoadCampaignReport(dir_ + "/out");
  ASSERT_TRUE(report.ok()) << report.status().message();
  ASSERT_EQ(report->runs.size(), 2u);
  for (const auto& run : report->runs) EXPECT_EQ(run.scenario, "tiny");
  EXPECT_NE(report->table.find("tiny: 1/2 passed (50%)"), std::string::npos) << report->table;
  EXPECT_NE(report->table.find("ignored: other-seed9 (scenario 'other', not 'tiny')"),
            std::string::npos)
      << report->table;
}

// Seeds re-run with a shorter list: the report covers the campaign's seeds, not old leftovers.
TEST_F(CampaignTest, ReportCoversTheSeedsOfTheLastCampaignOnly) {
  ASSERT_TRUE(RunCampaign(scenario_, Options(3, 1)).ok());
  ASSERT_TRUE(RunCampaign(scenario_, Options(1, 1)).ok());
  auto report = LoadCampaignReport(dir_ + "/out");
  ASSERT_TRUE(report.ok()) << report.status().message();
  ASSERT_EQ(report->runs.size(), 1u);
  EXPECT_TRUE(report->all_passed);
  EXPECT_NE(report->table.find("tiny: 1/1 passed (100%)"), std::string::npos) << report->table;
}

// An interrupted campaign says which seeds have no result, and why.
TEST_F(CampaignTest, InterruptedCampaignNamesTheSeedsWithoutAResult) {
  abort_after_ = 1;
  auto r = RunCampaign(scenario_, Options(3, 1));
  ASSERT_TRUE(r.ok()) << r.status().message();
  // Seed 2 was under way when the campaign stopped: its folder exists, its result does not.
  fs::create_directories(dir_ + "/out/tiny-seed2/logs");
  auto report = LoadCampaignReport(dir_ + "/out");
  ASSERT_TRUE(report.ok()) << report.status().message();
  EXPECT_FALSE(report->all_passed);
  EXPECT_NE(report->table.find("tiny: 1/1 passed (100%); 2 of 3 seeds have no result"),
            std::string::npos)
      << report->table;
  EXPECT_NE(report->table.find("seed 2: incomplete (started, no result.json)"), std::string::npos)
      << report->table;
  EXPECT_NE(report->table.find("seed 3: not run"), std::string::npos) << report->table;
  // Interrupted before any run finished: not "0/0 passed" alone.
  fs::remove_all(dir_ + "/out");
  abort_.store(false);
  abort_after_ = 0;
  abort_.store(true);
  r = RunCampaign(scenario_, Options(2, 1));
  ASSERT_TRUE(r.ok()) << r.status().message();
  report = LoadCampaignReport(dir_ + "/out");
  ASSERT_TRUE(report.ok()) << report.status().message();
  EXPECT_NE(report->table.find("tiny: 0/0 passed (0%); 2 of 2 seeds have no result"),
            std::string::npos)
      << report->table;
  EXPECT_EQ(report->table, rover::testing::ReadFile(dir_ + "/out/summary.txt"));
}

}  // namespace
}  // namespace rover::deploy
