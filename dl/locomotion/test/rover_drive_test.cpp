// rover-drive as a child process against dl-locomotion running in this test process (fake rover,
// sim clock published by the test): DONE -> exit 0 with every status printed; REJECTED -> exit
// 1; bad arguments -> exit 2 before touching DDS; no service -> exit 3 at --timeout.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <vector>

#include "rover/base/process.hpp"
#include "test/locomotion_rig.hpp"

namespace rover::dl::locomotion {
namespace {

using testing_support::LocomotionRig;

class RoverDriveTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::MakeTempDir("rover-drive-test"); }
  void TearDown() override {
    if (child_.running()) child_.Terminate(std::chrono::seconds(5));
    h_.Stop();
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }

  void Spawn(std::vector<std::string> args) {
    args.insert(args.begin(), testing::BinDir() + "/rover-drive");
    SpawnOptions o;
    o.argv = std::move(args);
    o.stdout_path = dir_ + "/out.txt";
    o.stderr_path = dir_ + "/err.txt";
    auto p = Process::Spawn(o);
    ASSERT_TRUE(p.ok()) << p.status().message();
    child_ = std::move(*p);
  }
  std::string Out() const { return testing::ReadFile(dir_ + "/out.txt"); }
  std::string Err() const { return testing::ReadFile(dir_ + "/err.txt"); }

  std::string dir_;
  LocomotionRig h_;
  Process child_;
};

TEST_F(RoverDriveTest, ArcRunsToDoneAndExitsZero) {
  h_.Start();
  h_.Advance(1.0);
  const std::string domain = std::to_string(h_.domain());
  Spawn({"arc", "--curvature", "0.5", "--distance", "0.2", "--speed", "0.1", "--domain", domain,
         "--clock", "sim", "--id", "4242", "--timeout", "120"});
  // Keep the simulated rover alive (one 20 ms step per poll) until the tool's command arrives.
  ASSERT_TRUE(testing::WaitFor(
      [&] {
        h_.StepOnce();
        return !h_.StatusesOf(4242).empty() || !child_.running();
      },
      std::chrono::seconds(60)))
      << Err();
  ASSERT_TRUE(h_.Advance(120.0, [&] { return h_.Terminal(4242); }));
  EXPECT_EQ(h_.StatusesOf(4242).back().state, rover_dl_DRIVE_DONE);
  const auto exit = child_.WaitFor(std::chrono::seconds(60));
  ASSERT_TRUE(exit.has_value()) << Out() << Err();
  EXPECT_TRUE(exit->success()) << exit->ToString() << "\n" << Out() << Err();
  const std::string out = Out();
  EXPECT_NE(out.find("sent ARC #4242"), std::string::npos) << out;
  // Intermediate states (STEERING, DRIVING) are printed when the tool sees them; dl/drive_status
  // keeps only the latest sample per command, so a loaded machine may skip one. Not checked.
  EXPECT_NE(out.find("#4242 ARC DONE (NOMINAL)"), std::string::npos) << out;
}

TEST_F(RoverDriveTest, RejectedCommandExitsOne) {
  h_.Start();
  h_.Advance(1.0);
  Spawn({"--raw", "arc", "--curvature", "nan", "--distance", "1", "--domain",
         std::to_string(h_.domain()), "--id", "4343", "--timeout", "120"});
  ASSERT_TRUE(testing::WaitFor(
      [&] {
        h_.StepOnce();
        return h_.Terminal(4343) || !child_.running();
      },
      std::chrono::seconds(60)))
      << Err();
  const auto exit = child_.WaitFor(std::chrono::seconds(60));
  ASSERT_TRUE(exit.has_value());
  EXPECT_EQ(exit->code, 1) << Out() << Err();
  EXPECT_NE(Out().find("#4343 ARC REJECTED (REJECTED_INVALID)"), std::string::npos) << Out();
  EXPECT_NE(Out().find("curvature is nan"), std::string::npos) << Out();
}

TEST_F(RoverDriveTest, BadArgumentsExitTwoWithAClearMessage) {
  Spawn({"arc", "--curvature", "nan", "--distance", "1"});
  const auto exit = child_.WaitFor(std::chrono::seconds(60));
  ASSERT_TRUE(exit.has_value());
  EXPECT_EQ(exit->code, 2);
  EXPECT_NE(Err().find("rover-drive: error: --curvature nan must be a finite number"),
            std::string::npos)
      << Err();
}

TEST_F(RoverDriveTest, NoLocomotionServiceExitsThreeAtTheHarnessTimeout) {
  const dds::DomainLease lease = testing::IsolatedDomain();
  Spawn({"stop", "--domain", std::to_string(lease.domain()), "--timeout", "1"});
  const auto exit = child_.WaitFor(std::chrono::seconds(60));
  ASSERT_TRUE(exit.has_value());
  EXPECT_EQ(exit->code, 3);
  EXPECT_NE(Err().find("no dl-locomotion answered on domain"), std::string::npos) << Err();
}

}  // namespace
}  // namespace rover::dl::locomotion
