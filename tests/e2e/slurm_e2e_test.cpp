// `roverctl run --backend slurm` on a one-node Slurm cluster started on this machine
// (scripts/slurm-local.sh, Debian's packages, run as root as CI is): the merged campaign folder
// matches a local --jobs 2 campaign's outcomes and figures; a cancelled job shows as cancelled
// with the command that resubmits it; a partition Slurm does not have is refused with its flag.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <nlohmann/json.hpp>

#include "rover/base/process.hpp"
#include "rover/testing/roverctl_runner.hpp"
#include "rover/testing/test_support.hpp"

namespace rover {
namespace {
namespace fs = std::filesystem;

class SlurmE2e : public ::testing::Test {
 protected:
  void SetUp() override {
    if (getuid() != 0) GTEST_SKIP() << "the one-node Slurm cluster needs root (CI runs as root)";
    testing::UseLoopbackDds();
    dir_ = testing::MakeTempDir("slurm-e2e");
    roverctl_.emplace(dir_);
    auto up = RunCommand({testing::SourceDir() + "/scripts/slurm-local.sh", "start"}, dir_,
                         std::chrono::seconds(120));
    ASSERT_TRUE(up.ok()) << up.status().message();
    ASSERT_TRUE(up->exit.success()) << up->out << up->err;
  }
  void TearDown() override {
    if (roverctl_) roverctl_->KillLeftovers();
    std::error_code ec;
    if (!dir_.empty()) fs::remove_all(dir_, ec);
  }
  std::string Scenario() const {
    return testing::SourceDir() + "/tests/e2e/scenarios/short_drive.yaml";
  }
  static nlohmann::json Json(const std::string& path) {
    std::ifstream in(path);
    return nlohmann::json::parse(in);
  }
  std::string dir_;
  std::optional<testing::RoverctlRunner> roverctl_;
};

TEST_F(SlurmE2e, ArrayJobMatchesALocalCampaignAndFailuresShowAsWhatTheyWere) {
  auto [se, sout] = roverctl_->Run({"run", Scenario(), "--seeds", "1..4", "--backend", "slurm",
                                    "--out", dir_ + "/slurm"});
  EXPECT_EQ(se.code, 0) << sout;
  EXPECT_NE(sout.find("slurm job "), std::string::npos) << sout;
  auto [le, lout] = roverctl_->Run({"run", Scenario(), "--seeds", "1..4", "--jobs", "2", "--out",
                                    dir_ + "/local"});
  EXPECT_EQ(le.code, 0) << lout;
  for (const char* f : {"summary.txt", "summary.json", "junit.xml"}) {
    EXPECT_TRUE(fs::exists(dir_ + "/slurm/" + f)) << f;
  }
  for (int seed = 1; seed <= 4; ++seed) {
    const std::string run = "/short-drive-seed" + std::to_string(seed) + "/result.json";
    const auto s = Json(dir_ + "/slurm" + run);
    const auto l = Json(dir_ + "/local" + run);
    EXPECT_EQ(s["pass"], l["pass"]) << seed;
    EXPECT_EQ(s["terrain_digest"], l["terrain_digest"]) << seed;
    // Strict lock-step: the same figures bit for bit whichever machine slot ran them.
    EXPECT_EQ(s["criteria"], l["criteria"]) << seed;
    EXPECT_EQ(s["figures"], l["figures"]) << seed;
  }
  const auto ss = Json(dir_ + "/slurm/summary.json");
  const auto ls = Json(dir_ + "/local/summary.json");
  EXPECT_EQ(ss["passed"], ls["passed"]);
  EXPECT_EQ(ss["runs"], ls["runs"]);

  // Detached, then cancelled before it ran: the report gathers it as CANCELLED, not missing,
  // and prints the one command that resubmits those seeds.
  auto [de, dout] = roverctl_->Run({"run", Scenario(), "--seeds", "5..6", "--backend", "slurm",
                                    "--detach", "--time", "5", "--out", dir_ + "/cancel"});
  ASSERT_EQ(de.code, 0) << dout;
  const auto c = Json(dir_ + "/cancel/campaign.json");
  const std::string job = c["slurm_jobs"][0]["job_id"];
  auto cancel = RunCommand({"scancel", job}, dir_, std::chrono::seconds(30));
  ASSERT_TRUE(cancel.ok() && cancel->exit.success());
  std::string report;
  ASSERT_TRUE(testing::WaitFor(
      [&] {
        auto [re, rout] = roverctl_->Run({"report", dir_ + "/cancel"});
        report = rout;
        return rout.find("still queued or running") == std::string::npos;
      },
      std::chrono::seconds(60)))
      << report;
  EXPECT_NE(report.find("slurm: CANCELLED"), std::string::npos) << report;
  EXPECT_NE(report.find("resubmit what has no result: roverctl run " + Scenario() +
                        " --backend slurm --seeds 5,6 --out "),
            std::string::npos)
      << report;

  // A partition the cluster does not have: Slurm's refusal, with the flag, nothing submitted.
  auto [pe, pout] = roverctl_->Run({"run", Scenario(), "--seeds", "1", "--backend", "slurm",
                                    "--partition", "nosuch", "--out", dir_ + "/badpart"});
  EXPECT_NE(pe.code, 0) << pout;
  EXPECT_NE(pout.find("sbatch refused the job"), std::string::npos) << pout;
  EXPECT_NE(pout.find("--partition nosuch"), std::string::npos) << pout;
}

}  // namespace
}  // namespace rover
