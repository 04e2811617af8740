// `roverctl run --faults` end to end with the real drive set: the CI fault campaign
// (tests/e2e/campaigns/short_faults.yaml on short_drive.yaml) writes its table, the 100 % drop
// of dl/pose (which the drive needs) is detected within the attitude staleness limit, and a bad
// campaign file is refused before anything starts.
#include <gtest/gtest.h>
#include <signal.h>
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

class FaultCampaignE2e : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::UseLoopbackDds();
    dir_ = testing::MakeTempDir("fault-campaign-e2e");
    roverctl_.emplace(dir_);
  }
  void TearDown() override {
    roverctl_->KillLeftovers();
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  std::pair<ExitInfo, std::string> Run(const std::vector<std::string>& args) {
    return roverctl_->Run(args, std::chrono::minutes(5));
  }
  static std::string Source(const std::string& rel) { return testing::SourceDir() + "/" + rel; }
  std::string dir_;
  std::optional<testing::RoverctlRunner> roverctl_;
};

TEST_F(FaultCampaignE2e, ShortCampaignDetectsALostPose) {
  const std::string out = dir_ + "/campaign";
  auto [e, log] = Run({"run", Source("tests/e2e/scenarios/short_drive.yaml"), "--faults",
                       Source("tests/e2e/campaigns/short_faults.yaml"), "--jobs", "2", "--out",
                       out});
  ASSERT_TRUE(fs::exists(out + "/campaign.json")) << log;
  std::ifstream in(out + "/campaign.json");
  const auto c = nlohmann::json::parse(in);
  ASSERT_EQ(c["type"], "fault_campaign");
  ASSERT_EQ(c["rows"].size(), 3u) << c.dump(2);  // baseline + 2 faults, one seed
  const auto& base = c["rows"][0];
  const auto& no_pose = c["rows"][1];
  const auto& sun = c["rows"][2];
  EXPECT_EQ(base["fault"], "baseline");
  EXPECT_EQ(no_pose["fault"], "01-no-pose");
  EXPECT_EQ(sun["fault"], "02-sun-dropouts");
  for (const auto& r : c["rows"]) {
    EXPECT_TRUE(r["has_result"].get<bool>()) << r.dump(2) << log;
    EXPECT_TRUE(r["safe"].get<bool>()) << r.dump(2);
  }
  EXPECT_TRUE(base["goal"].get<bool>()) << base.dump(2);
  // The lost pose: the services saw it start at 20 s, hit samples, and the stack noticed.
  EXPECT_NEAR(no_pose["fault_start_s"].get<double>(), 20.0, 0.1) << no_pose.dump(2);
  EXPECT_GT(no_pose["samples_hit"].get<std::uint64_t>(), 0u) << no_pose.dump(2);
  EXPECT_TRUE(no_pose["detected"].get<bool>()) << no_pose.dump(2);
  EXPECT_GE(no_pose["detection_delay_s"].get<double>(), 0.0) << no_pose.dump(2);
  EXPECT_LE(no_pose["detection_delay_s"].get<double>(), 2.0) << no_pose.dump(2);
  EXPECT_NE(no_pose["response"], "none") << no_pose.dump(2);
  EXPECT_EQ(e.code, 0) << log;

  const std::string summary = testing::ReadFile(out + "/summary.txt");
  EXPECT_NE(summary.find("01-no-pose"), std::string::npos) << summary;
  ASSERT_NE(summary.find("\ndetection: "), std::string::npos) << summary;
  EXPECT_NE(summary.find("safe: 2 of 2 fault runs safe (100%)\n"), std::string::npos) << summary;
  EXPECT_TRUE(fs::exists(out + "/campaign.txt"));
  EXPECT_TRUE(fs::exists(out + "/01-no-pose/short-drive-seed1/result.json"));
  // `roverctl report` rebuilds the same table.
  auto [re, report] = Run({"report", out});
  EXPECT_EQ(re.code, 0) << report;
  EXPECT_NE(report.find(summary.substr(summary.find("\ndetection: "))), std::string::npos)
      << report;
}

TEST_F(FaultCampaignE2e, BadCampaignFileIsRefusedBeforeAnythingStarts) {
  const std::string file = dir_ + "/bad.yaml";
  std::ofstream(file) << "- {kind: drop, topic: dl/pose}\n- {kind: dorp, topic: dl/pose}\n";
  const std::string out = dir_ + "/never";
  auto [e, log] = Run({"run", Source("tests/e2e/scenarios/short_drive.yaml"), "--faults", file,
                       "--out", out});
  EXPECT_EQ(e.code, 2) << log;
  EXPECT_NE(log.find(file + ":2"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(out));
  std::ofstream(file) << "- name: kill\n  kill: {service: dl-nothing, at_s: 30}\n";
  auto [k, klog] = Run({"run", Source("tests/e2e/scenarios/short_drive.yaml"), "--faults", file,
                        "--out", out});
  EXPECT_EQ(k.code, 2) << klog;
  EXPECT_NE(klog.find(file + ":1: key 'kill.service': no service 'dl-nothing'"),
            std::string::npos)
      << klog;
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace
}  // namespace rover
