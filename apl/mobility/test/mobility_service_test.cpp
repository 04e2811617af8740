// apl-mobility in-process over DDS (tests/support's ServiceHarness on the simulated run clock),
// with fake locomotion and stereo over a rock field (tests/support/fakes/fake_mobility_dl.hpp).
#include "mobility_service.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "rover/msg/mobility_idl.hpp"
#include "rover/testing/fakes/fake_mobility_dl.hpp"
#include "rover/testing/service_harness.hpp"
#include "rover/testing/test_support.hpp"

namespace rover::apl::mobility {
namespace {

class MobilityServiceTest : public ::testing::Test {
 protected:
  void Start(std::vector<std::string> overrides = {}) {
    harness_ = std::make_unique<rover::testing::ServiceHarness>(service_, "apl-mobility-test",
                                                                std::move(overrides));
    ASSERT_TRUE(harness_->ok()) << harness_->status().message();
    ASSERT_TRUE(loco_.Create(harness_->peer()).ok());
    ASSERT_TRUE(stereo_.Create(harness_->peer()).ok());
    commands_ = harness_->Writer<rover_apl_MobilityCommand>("apl/mobility_command");
    status_ = harness_->Reader<rover_apl_MobilityStatus>("apl/mobility_status");
    maps_ = harness_->Reader<rover_apl_GoodnessMap>("apl/goodness_map");
    votes_ = harness_->Reader<rover_apl_ArcVotes>("apl/arc_votes");
    ASSERT_TRUE(harness_->SpinUntil([&] { return loco_.Matched() && stereo_.Matched(); }));
    t_ = 0.1;
    ASSERT_TRUE(Tick());
  }
  // One 0.1 s step of the world: the fakes serve, time moves, the service spins.
  bool Tick() {
    loco_.Advance(Time::FromSeconds(t_));
    stereo_.Serve(Time::FromSeconds(t_));
    t_ += 0.1;
    const bool ok = harness_->AdvanceTo(Time::FromSeconds(t_));
    for (auto& m : maps_.Take()) maps_seen_ += m.data().goodness._length > 0 ? 1 : 0;
    for (auto& v : votes_.Take()) votes_seen_ += v.data().votes._length > 0 ? 1 : 0;
    return ok;
  }
  void Send(const MobilityCommand& c) {
    MobilityCommand stamped = c;
    stamped.stamp = Time::FromSeconds(t_);
    msg::MobilityCommandMessage m;
    msg::MobilityCommandToIdl(stamped, &m);
    ASSERT_TRUE(commands_.Write(m.msg).ok());
  }
  // Steps until a terminal status of `id` (or `max_s` of simulated time).
  std::optional<MobilityStatus> WaitEnd(std::uint32_t id, double max_s) {
    const double end = t_ + max_s;
    while (t_ < end) {
      for (auto& s : status_.Take()) {
        const Result<MobilityStatus> read = msg::MobilityStatusFromIdl(s.data());
        EXPECT_TRUE(read.ok()) << read.status().message();
        if (!read.ok()) continue;
        const MobilityStatus& st = *read;
        if (st.command_id == id && st.state != State::kRunning) return st;
      }
      if (!Tick()) return std::nullopt;
    }
    return std::nullopt;
  }

  MobilityService service_;
  std::unique_ptr<rover::testing::ServiceHarness> harness_;
  rover::testing::RockField field_;
  rover::testing::FakeLocomotion loco_;
  rover::testing::FakeStereo stereo_{&field_, &loco_};
  dds::Writer<rover_apl_MobilityCommand> commands_;
  dds::Reader<rover_apl_MobilityStatus> status_;
  dds::Reader<rover_apl_GoodnessMap> maps_;
  dds::Reader<rover_apl_ArcVotes> votes_;
  double t_ = 0.0;
  int maps_seen_ = 0, votes_seen_ = 0;
};

MobilityCommand Autonav(std::uint32_t id, double x, double y) {
  MobilityCommand c;
  c.command_id = id;
  c.mode = Mode::kAutoNav;
  c.goal = {x, y, 0};
  c.tolerance = 0.3;
  return c;
}

TEST_F(MobilityServiceTest, AutonavAroundARockOverTopics) {
  field_.rocks().push_back({3.0, 0.0, 0.3, 0.45});
  Start();
  Send(Autonav(1, 6.0, 0.0));
  const auto end = WaitEnd(1, 600.0);
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->state, State::kSucceeded) << end->message;
  EXPECT_LE(end->distance_to_goal, 0.3 + 1e-9);
  EXPECT_GT(field_.Clearance(loco_.x, loco_.y), 0.3);
  EXPECT_GT(stereo_.served(), 0);
  EXPECT_GT(maps_seen_, 0);
  EXPECT_GT(votes_seen_, 0);
}

TEST_F(MobilityServiceTest, BadCommandIsRejectedAndNothingMoves) {
  Start();
  Send(Autonav(1, std::nan(""), 0.0));
  const auto end = WaitEnd(1, 5.0);
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->state, State::kRejected);
  EXPECT_EQ(end->fault, Fault::kBadCommand);
  EXPECT_NE(end->message.find("goal.x is nan"), std::string::npos) << end->message;
  EXPECT_EQ(loco_.accepted(), 0);
}

TEST_F(MobilityServiceTest, WrongCameraIsAnImgMotionErrorUntilCleared) {
  Start();
  stereo_.answer_camera = rover_CAMERA_NAVCAM;
  Send(Autonav(1, 6.0, 0.0));
  auto end = WaitEnd(1, 30.0);
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->fault, Fault::kImg) << end->message;
  EXPECT_TRUE(end->motion_error_latched);
  Send(Autonav(2, 6.0, 0.0));
  end = WaitEnd(2, 5.0);
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->state, State::kRejected);
  EXPECT_EQ(end->fault, Fault::kImg);
  MobilityCommand clear;
  clear.command_id = 3;
  clear.mode = Mode::kClearFault;
  Send(clear);
  end = WaitEnd(3, 5.0);
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->state, State::kSucceeded);
  EXPECT_FALSE(end->motion_error_latched);
  EXPECT_EQ(loco_.accepted(), 0);
}

// Issue 12: a corrupted dl/pose while driving is SAPP (the drive stopped) and shows on sys/health
// as a rejected input; dl/pose that then stays away is a stale input there.
TEST_F(MobilityServiceTest, CorruptPoseWhileDrivingIsSappAndAnInputFinding) {
  Start();
  MobilityCommand c;
  c.command_id = 1;
  c.mode = Mode::kDirected;
  c.primitives = {{PrimitiveKind::kStraight, 0.0, 3.0, 0.0}};
  Send(c);
  for (int i = 0; i < 50 && !loco_.busy(); ++i) ASSERT_TRUE(Tick());
  ASSERT_TRUE(loco_.busy());
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(Tick());  // driving
  EXPECT_EQ(harness_->health(), rover_HEALTH_OK) << harness_->health_message();
  loco_.publish_pose = false;
  auto bad_pose = harness_->Writer<rover_dl_PoseEstimate>("dl/pose");
  rover_dl_PoseEstimate m =
      rover::testing::PoseEstimateMessage(Time::FromSeconds(t_), loco_.pose_publisher().state);
  m.pose.position.x = std::nan("");
  ASSERT_TRUE(bad_pose.Write(m).ok());
  const auto end = WaitEnd(1, 5.0);
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->state, State::kFailed);
  EXPECT_EQ(end->fault, Fault::kSapp);
  EXPECT_EQ(end->message, "dl/pose rejected: pose.position.x is nan (must be finite)");
  EXPECT_TRUE(end->motion_error_latched);
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(Tick());
  EXPECT_FALSE(loco_.busy());  // the STOP reached locomotion
  const auto said = [&](const std::string& text) {
    for (const rover_sys_Heartbeat& hb : harness_->heartbeats()) {
      if (std::string(hb.message).find(text) != std::string::npos) return true;
    }
    return false;
  };
  EXPECT_TRUE(said("dl/pose rejected: pose.position.x is nan"));
  // No dl/pose since: stale after inputs.dl_pose.max_age_s (1 s).
  for (int i = 0; i < 15; ++i) ASSERT_TRUE(Tick());
  EXPECT_TRUE(harness_->SpinUntil([&] { return harness_->health() == rover_HEALTH_STALE; }))
      << harness_->health_message();
  EXPECT_EQ(harness_->health_message().rfind("dl/pose stale: no sample since", 0), 0u)
      << harness_->health_message();
}

// kill -9 of apl-mobility mid-command (issue 37): in a supervised set the running command is
// checkpointed, and the restarted service ends it with the goal error RESTART and says so on
// sys/health, instead of leaving the commander waiting for a command nobody runs.
TEST_F(MobilityServiceTest, ARestartEndsTheInterruptedCommandWithRestart) {
  const std::string dir = rover::testing::MakeTempDir("mobility-restart");
  ASSERT_EQ(setenv("ROVER_STATE_DIR", dir.c_str(), 1), 0);
  ASSERT_EQ(setenv("ROVER_SET_ID", "set-1", 1), 0);
  const std::string path = dir + "/checkpoints/apl-mobility-test.ckpt";  // the harness name
  Start();
  Send(Autonav(7, 6.0, 0.0));
  for (int i = 0; i < 50 && !loco_.busy(); ++i) ASSERT_TRUE(Tick());
  ASSERT_TRUE(loco_.busy());
  auto written = CheckpointStore(path, "set-1").Load();
  ASSERT_TRUE(written.ok() && written->has_value()) << written.status().message();
  EXPECT_EQ((**written).at("running"), "1");
  EXPECT_EQ((**written).at("command_id"), "7");
  std::stringstream crash_leftover;
  crash_leftover << std::ifstream(path).rdbuf();

  // A crash leaves the checkpoint as it was (a clean stop removes it).
  harness_.reset();
  EXPECT_FALSE(std::filesystem::exists(path));
  std::ofstream(path) << crash_leftover.str();
  Start();
  const auto end = WaitEnd(7, 2.0);
  ASSERT_TRUE(end.has_value());
  EXPECT_EQ(end->state, State::kFailed);
  EXPECT_EQ(end->fault, Fault::kRestart);
  EXPECT_EQ(end->fault_class, FaultClass::kGoalError);
  for (int i = 0; i < 30 && harness_->health() != rover_HEALTH_DEGRADED; ++i) ASSERT_TRUE(Tick());
  EXPECT_EQ(harness_->health(), rover_HEALTH_DEGRADED);
  EXPECT_EQ(harness_->health_message(), "restarted: command 7 (AUTONAV) abandoned");
  written = CheckpointStore(path, "set-1").Load();
  ASSERT_TRUE(written.ok() && written->has_value());
  EXPECT_EQ((**written).at("running"), "0");  // reported once, not again at the next restart

  // The next command clears the finding and runs.
  Send(Autonav(8, 1.0, 0.0));
  const auto next = WaitEnd(8, 120.0);
  ASSERT_TRUE(next.has_value());
  EXPECT_EQ(next->state, State::kSucceeded) << next->message;
  EXPECT_EQ(harness_->health(), rover_HEALTH_OK) << harness_->health_message();
  harness_.reset();
  unsetenv("ROVER_STATE_DIR");
  unsetenv("ROVER_SET_ID");
  std::filesystem::remove_all(dir);
}

TEST(MobilityServiceParams, InvalidParametersRefuseConfigurationNamingTheKey) {
  for (const std::string bad : {"mobility.step_length_m=0", "gestalt.max_step_m=-1"}) {
    MobilityService service;
    rover::testing::ServiceHarness h(service, "apl-mobility-test", {bad});
    ASSERT_FALSE(h.ok()) << bad;
    EXPECT_NE(h.status().message().find(bad.substr(0, bad.find('='))), std::string::npos)
        << h.status().message();
  }
}

}  // namespace
}  // namespace rover::apl::mobility
