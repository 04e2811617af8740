// The campaign without processes: each seed's run is a scripted function that writes its
// result.json as RunScenario does.
#include "rover/deploy/campaign.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <mutex>
#include <set>

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
  EXPECT_EQ(rover::testing::ReadFile(dir_ + "/out/summary.txt"),
            FormatSummaryTable(r->runs, r->summary));
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

}  // namespace
}  // namespace rover::deploy
