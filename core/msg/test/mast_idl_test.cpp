#include "rover/msg/mast_idl.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "rover/idl/access.hpp"

namespace rover::msg {
namespace {

TEST(MastIdl, CommandRoundTripKeepsAnUnknownPointingAndNaN) {
  MastCommand c;
  c.stamp = Time{42};
  c.command_id = 7;
  c.pointing = MastPointing::kLookAt;
  c.pan = 0.5;
  c.tilt = std::nan("");
  c.look_at = {3.0, -1.5, 0.25};
  c.timeout_s = 12.0;
  rover_dl_MastCommand m{};
  MastCommandToIdl(c, &m);
  EXPECT_EQ(m.header.stamp_ns, 42);
  EXPECT_EQ(m.pointing, rover_dl_MAST_POINT_LOOK_AT);
  EXPECT_EQ(m.look_at.y, -1.5);
  const MastCommand back = MastCommandFromIdl(m);
  EXPECT_EQ(back.stamp, c.stamp);
  EXPECT_EQ(back.command_id, 7u);
  EXPECT_EQ(back.pointing, MastPointing::kLookAt);
  EXPECT_EQ(back.pan, 0.5);
  EXPECT_TRUE(std::isnan(back.tilt));
  EXPECT_EQ(back.look_at, c.look_at);
  EXPECT_EQ(back.timeout_s, 12.0);
  // A corrupt pointing value reaches dl-mast as it is, for it to reject by name.
  idl::SetRawEnum(&m.pointing, 5);
  const MastCommand bad = MastCommandFromIdl(m);
  EXPECT_EQ(static_cast<int>(bad.pointing), 5);
  EXPECT_FALSE(IsKnownPointing(bad.pointing));
  EXPECT_STREQ(MastPointingName(bad.pointing), "UNKNOWN");
}

TEST(MastIdl, StatusRoundTripTruncatesTheMessageAndRefusesAnUnknownState) {
  MastStatus s;
  s.stamp = Time{99};
  s.command_id = 4;
  s.state = MastState::kAtGoal;
  s.pan = 0.1;
  s.tilt = -0.2;
  s.pan_goal = 0.11;
  s.tilt_goal = -0.21;
  s.message = std::string(300, 'm');
  rover_dl_MastStatus m{};
  MastStatusToIdl(s, &m);
  EXPECT_EQ(m.state, rover_dl_MAST_AT_GOAL);
  EXPECT_EQ(std::strlen(m.message), 127u);
  const auto back = MastStatusFromIdl(m);
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->stamp, s.stamp);
  EXPECT_EQ(back->command_id, 4u);
  EXPECT_EQ(back->state, MastState::kAtGoal);
  EXPECT_EQ(back->pan, 0.1);
  EXPECT_EQ(back->tilt, -0.2);
  EXPECT_EQ(back->pan_goal, 0.11);
  EXPECT_EQ(back->tilt_goal, -0.21);
  EXPECT_EQ(back->message, std::string(127, 'm'));
  idl::SetRawEnum(&m.state, 9);
  const auto bad = MastStatusFromIdl(m);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(), "dl/mast_status state = 9 is not a MastState (0..4)");
}

TEST(MastNames, EveryEnumeratorHasItsIdlName) {
  EXPECT_STREQ(MastPointingName(MastPointing::kAngles), "ANGLES");
  EXPECT_STREQ(MastStateName(MastState::kIdle), "IDLE");
  EXPECT_STREQ(MastStateName(MastState::kMoving), "MOVING");
  EXPECT_STREQ(MastStateName(MastState::kAtGoal), "AT_GOAL");
  EXPECT_STREQ(MastStateName(MastState::kFault), "FAULT");
  EXPECT_STREQ(MastStateName(MastState::kRejected), "REJECTED");
  EXPECT_STREQ(MastStateName(static_cast<MastState>(17)), "UNKNOWN");
}

}  // namespace
}  // namespace rover::msg
