#include "rover/apl/mobility/command_checkpoint.hpp"

#include <gtest/gtest.h>

namespace rover::apl::mobility {
namespace {

MobilityStatus StatusOf(std::uint32_t id, State state, Mode mode = Mode::kAutoNav) {
  MobilityStatus s;
  s.command_id = id;
  s.state = state;
  s.mode = mode;
  return s;
}

TEST(CommandCheckpointTest, FieldsRoundTrip) {
  const CommandCheckpoint c{true, 4000000000u, Mode::kGuardedArc};
  const auto back = CommandCheckpointFromFields(CommandCheckpointFields(c));
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(*back, c);
}

TEST(CommandCheckpointTest, BadFieldsAreNamedWithTheirValue) {
  auto f = CommandCheckpointFields({true, 7, Mode::kAutoNav});
  f.erase("mode");
  EXPECT_NE(CommandCheckpointFromFields(f).status().message().find("'mode' is missing"),
            std::string::npos);
  f = CommandCheckpointFields({true, 7, Mode::kAutoNav});
  f["running"] = "yes";
  EXPECT_NE(CommandCheckpointFromFields(f).status().message().find("running 'yes'"),
            std::string::npos);
  f = CommandCheckpointFields({true, 7, Mode::kAutoNav});
  f["command_id"] = "4294967296";
  EXPECT_NE(CommandCheckpointFromFields(f).status().message().find("command_id '4294967296'"),
            std::string::npos);
  f["command_id"] = "12x";
  EXPECT_FALSE(CommandCheckpointFromFields(f).ok());
  f = CommandCheckpointFields({true, 7, Mode::kAutoNav});
  f["mode"] = "FLY";
  EXPECT_NE(CommandCheckpointFromFields(f).status().message().find("mode 'FLY'"),
            std::string::npos);
}

TEST(CommandCheckpointTest, RunningStartsAndTheRunningCommandsEndStopsIt) {
  CommandCheckpoint c;
  c = NextCommandCheckpoint(c, StatusOf(3, State::kRunning));
  EXPECT_EQ(c, (CommandCheckpoint{true, 3, Mode::kAutoNav}));
  // Another command rejected as BUSY while 3 runs does not end 3.
  c = NextCommandCheckpoint(c, StatusOf(4, State::kRejected, Mode::kDirected));
  EXPECT_EQ(c, (CommandCheckpoint{true, 3, Mode::kAutoNav}));
  c = NextCommandCheckpoint(c, StatusOf(3, State::kSucceeded));
  EXPECT_EQ(c, (CommandCheckpoint{false, 3, Mode::kAutoNav}));
  c = NextCommandCheckpoint(c, StatusOf(3, State::kIdle));
  EXPECT_FALSE(c.running);
  c = NextCommandCheckpoint(c, StatusOf(5, State::kRunning, Mode::kDirected));
  c = NextCommandCheckpoint(c, StatusOf(5, State::kFailed, Mode::kDirected));
  EXPECT_EQ(c, (CommandCheckpoint{false, 5, Mode::kDirected}));
}

TEST(CommandCheckpointTest, AnInterruptedCommandEndsWithTheGoalErrorRestart) {
  const MobilityStatus s =
      InterruptedCommandStatus({true, 9, Mode::kAutoNav}, Time::FromSeconds(31.5));
  EXPECT_EQ(s.command_id, 9u);
  EXPECT_EQ(s.mode, Mode::kAutoNav);
  EXPECT_EQ(s.state, State::kFailed);
  EXPECT_EQ(s.fault, Fault::kRestart);
  EXPECT_EQ(s.fault_class, FaultClass::kGoalError);
  EXPECT_FALSE(s.motion_error_latched);
  EXPECT_EQ(s.stamp, Time::FromSeconds(31.5));
  EXPECT_NE(s.message.find("command 9 (AUTONAV)"), std::string::npos) << s.message;
  EXPECT_LE(s.message.size(), 127u);  // fits the wire's bound
}

}  // namespace
}  // namespace rover::apl::mobility
