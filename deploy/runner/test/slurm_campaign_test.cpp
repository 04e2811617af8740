// The Slurm backend against a scripted Slurm: sbatch, squeue and scontrol answers as a real
// controller gives them, the tasks' result.json written as `roverctl run-task` would.
#include "rover/deploy/slurm_campaign.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "rover/testing/test_support.hpp"

namespace rover::deploy {
namespace {
namespace fs = std::filesystem;

class SlurmCampaignTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = rover::testing::MakeTempDir("slurm-campaign");
    scenario_.name = "tiny";
    scenario_.file = dir_ + "/tiny.yaml";
    std::ofstream(scenario_.file) << "name: tiny\n";
  }
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  static CommandOutput Answer(const std::string& out, int code = 0, const std::string& err = "") {
    CommandOutput c;
    c.exit.code = code;
    c.out = out;
    c.err = err;
    return c;
  }
  void WriteResult(std::uint32_t seed, bool pass) {
    RunResult r;
    r.scenario = "tiny";
    r.seed = seed;
    r.pass = pass;
    r.failure = pass ? "" : "criterion failed";
    r.run_dir = dir_ + "/out/tiny-seed" + std::to_string(seed);
    fs::create_directories(r.run_dir);
    std::ofstream(r.run_dir + "/result.json") << ToJson(r).dump(2);
  }
  SlurmCampaignOptions Options() {
    SlurmCampaignOptions o;
    o.seeds = {1, 2, 3};
    o.out_dir = dir_ + "/out";
    o.roverctl = "/opt/rover/bin/roverctl";
    o.slurm.poll_s = 0.2;
    o.run = [this](const std::vector<std::string>& argv) -> Result<CommandOutput> {
      calls_.push_back(argv);
      if (argv[0] == "sbatch") return Answer(sbatch_out_, sbatch_code_, sbatch_err_);
      if (argv[0] == "squeue") {
        ++polls_;
        // First poll: task 0 running, 1 and 2 pending; then nothing queued.
        return Answer(polls_ == 1 ? "42_0|RUNNING\n42_1|PENDING\n42_2|PENDING\n" : "");
      }
      if (argv[0] == "scontrol") {
        if (polls_ < 2) return Answer("");
        WriteResult(1, true);
        WriteResult(2, false);
        return Answer(
            "JobId=43 ArrayJobId=42 ArrayTaskId=0 JobName=rover-tiny JobState=COMPLETED "
            "Reason=None ExitCode=0:0\n"
            "JobId=44 ArrayJobId=42 ArrayTaskId=1 JobState=COMPLETED ExitCode=0:0\n"
            "JobId=45 ArrayJobId=42 ArrayTaskId=2 JobState=TIMEOUT Reason=TimeLimit "
            "ExitCode=0:15\n");
      }
      return Answer("", 1, "unexpected command");
    };
    return o;
  }
  std::string dir_;
  Scenario scenario_;
  std::vector<std::vector<std::string>> calls_;
  std::string sbatch_out_ = "42\n", sbatch_err_;
  int sbatch_code_ = 0;
  int polls_ = 0;
};

TEST_F(SlurmCampaignTest, SubmitsOneTaskPerSeedWaitsAndSummarises) {
  SlurmCampaignOptions o = Options();
  o.slurm.partition = "rover";
  o.slurm.time_limit = "30";
  auto job = SubmitSlurmCampaign(scenario_, o);
  ASSERT_TRUE(job.ok()) << job.status().message();
  EXPECT_EQ(*job, "42");
  const auto& sbatch = calls_.front();
  auto has = [&](const std::string& a) {
    return std::find(sbatch.begin(), sbatch.end(), a) != sbatch.end();
  };
  EXPECT_TRUE(has("--array=0-2"));
  EXPECT_TRUE(has("--partition=rover"));
  EXPECT_TRUE(has("--time=30"));
  EXPECT_TRUE(has("--cpus-per-task=1"));
  const std::string script = rover::testing::ReadFile(sbatch.back());
  EXPECT_NE(script.find("SEEDS=(1 2 3 )"), std::string::npos) << script;
  EXPECT_NE(script.find("run-task"), std::string::npos);
  EXPECT_NE(script.find("has no build at $ROVERCTL"), std::string::npos);
  // roverctl's global options go before the command; an open set passes none.
  EXPECT_NE(script.find("exec \"$ROVERCTL\" run-task '"), std::string::npos) << script;
  EXPECT_EQ(script.find("--security"), std::string::npos) << script;

  auto r = WaitSlurmCampaign(scenario_, o, *job);
  ASSERT_TRUE(r.ok()) << r.status().message();
  ASSERT_EQ(r->runs.size(), 3u);
  EXPECT_TRUE(r->runs[0].pass);
  EXPECT_EQ(r->runs[1].failure, "criterion failed");
  // The timed-out task is a row saying so, not a missing seed.
  EXPECT_EQ(r->runs[2].failure, "slurm: TIMEOUT, exit code 0:15 (no result; log: slurm/task-2.log)");
  EXPECT_TRUE(r->missing.empty());
  for (const char* f : {"summary.txt", "summary.json", "junit.xml"}) {
    EXPECT_TRUE(fs::exists(o.out_dir + "/" + f)) << f;
  }
  EXPECT_NE(rover::testing::ReadFile(o.out_dir + "/summary.txt").find("slurm: TIMEOUT"),
            std::string::npos);
  // Resubmitting only what Slurm ended without a result.
  EXPECT_EQ(ResubmitCommand(o.out_dir),
            "roverctl run " + fs::absolute(scenario_.file).string() +
                " --backend slurm --seeds 3 --out " + fs::absolute(o.out_dir).string());
}

// A pending array cancelled as a whole is one scontrol record with a range of task ids.
TEST_F(SlurmCampaignTest, AWholeArrayCancelledBeforeItRanIsEveryTask) {
  SlurmCampaignOptions o = Options();
  o.slurm.detach = true;
  auto job = SubmitSlurmCampaign(scenario_, o);
  ASSERT_TRUE(job.ok()) << job.status().message();
  o.run = [](const std::vector<std::string>& argv) -> Result<CommandOutput> {
    if (argv[0] == "scontrol") {
      return Answer("JobId=42 ArrayJobId=42 ArrayTaskId=0-2 JobState=CANCELLED ExitCode=0:0\n");
    }
    return Answer("");
  };
  std::map<std::uint32_t, SlurmTask> tasks;
  ASSERT_TRUE(QuerySlurmTasks(o, *job, &tasks).ok());
  ASSERT_EQ(tasks.size(), 3u);
  for (const auto& [seed, t] : tasks) {
    EXPECT_EQ(t.state, "CANCELLED") << seed;
    EXPECT_TRUE(t.ended());
  }
}

TEST_F(SlurmCampaignTest, RefusalsNameWhatCausedThem) {
  SlurmCampaignOptions o = Options();
  o.slurm.partition = "nosuch";
  sbatch_code_ = 1;
  sbatch_out_ = "";
  sbatch_err_ = "sbatch: error: invalid partition specified: nosuch\n"
                "sbatch: error: Batch job submission failed: Invalid partition name specified\n";
  auto job = SubmitSlurmCampaign(scenario_, o);
  ASSERT_FALSE(job.ok());
  EXPECT_EQ(job.status().message(),
            "sbatch refused the job (exit code 1): sbatch: error: Batch job submission failed: "
            "Invalid partition name specified [given: --partition nosuch]; nothing submitted");
  SlurmOptions bad;
  bad.cpus_per_task = 0;
  EXPECT_EQ(bad.Validate().message(), "--cpus-per-task: 0 is not in [1, 256]");
  bad.cpus_per_task = 1;
  bad.time_limit = "1 hour";
  EXPECT_EQ(bad.Validate().message(),
            "--time: '1 hour' is not a Slurm time (minutes, MM:SS, HH:MM:SS or D-HH)");
  // A folder of another scenario is refused before anything is submitted.
  fs::create_directories(dir_ + "/other");
  std::ofstream(dir_ + "/other/campaign.json") << R"({"scenario": "big"})";
  o = Options();
  o.out_dir = dir_ + "/other";
  calls_.clear();
  EXPECT_NE(SubmitSlurmCampaign(scenario_, o).status().message().find("holds a campaign of "
                                                                       "scenario 'big'"),
            std::string::npos);
  EXPECT_TRUE(calls_.empty());
}

}  // namespace
}  // namespace rover::deploy
