#include "rover/msg/arm_idl.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>

#include "rover/idl/access.hpp"

namespace rover::msg {
namespace {

TEST(ArmIdl, CommandRoundTripKeepsAnUnknownModeAndNaN) {
  ArmCommand c;
  c.stamp = Time{42};
  c.command_id = 9;
  c.mode = ArmMode::kPlace;
  c.joints = {0.1, std::nan(""), -1.2, 0.4};
  c.target = {1.05, -0.1, 0.07};
  c.timeout_s = 30.0;
  rover_dl_ArmCommand m{};
  ArmCommandToIdl(c, &m);
  EXPECT_EQ(m.mode, rover_dl_ARM_MODE_PLACE);
  EXPECT_EQ(m.target.x, 1.05);
  const ArmCommand back = ArmCommandFromIdl(m);
  EXPECT_EQ(back.stamp, c.stamp);
  EXPECT_EQ(back.command_id, 9u);
  EXPECT_EQ(back.mode, ArmMode::kPlace);
  EXPECT_EQ(back.joints[2], -1.2);
  EXPECT_TRUE(std::isnan(back.joints[1]));
  EXPECT_EQ(back.target, c.target);
  EXPECT_EQ(back.timeout_s, 30.0);
  idl::SetRawEnum(&m.mode, 11);
  const ArmCommand bad = ArmCommandFromIdl(m);
  EXPECT_EQ(static_cast<int>(bad.mode), 11);
  EXPECT_FALSE(IsKnownArmMode(bad.mode));
  EXPECT_STREQ(ArmModeName(bad.mode), "UNKNOWN");
  EXPECT_STREQ(ArmModeName(ArmMode::kStow), "STOW");
}

TEST(ArmIdl, StatusRoundTripTruncatesTheMessageAndRefusesAnUnknownState) {
  ArmStatus s;
  s.stamp = Time{99};
  s.command_id = 4;
  s.state = ArmState::kPlaced;
  s.joints = {0.0, 0.1, -1.4, -0.3};
  s.joint_goals = {0.0, 0.09, -1.45, -0.2};
  s.tool_point = {1.0, 0.0, 0.05};
  s.contact = true;
  s.stowed = false;
  s.message = std::string(300, 'a');
  rover_dl_ArmStatus m{};
  ArmStatusToIdl(s, &m);
  EXPECT_EQ(m.state, rover_dl_ARM_PLACED);
  EXPECT_EQ(std::strlen(m.message), 127u);
  auto back = ArmStatusFromIdl(m);
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->state, ArmState::kPlaced);
  EXPECT_EQ(back->joints, s.joints);
  EXPECT_EQ(back->joint_goals, s.joint_goals);
  EXPECT_EQ(back->tool_point, s.tool_point);
  EXPECT_TRUE(back->contact);
  EXPECT_FALSE(back->stowed);
  EXPECT_EQ(back->message.size(), 127u);
  EXPECT_STREQ(ArmStateName(ArmState::kStowed), "STOWED");
  EXPECT_STREQ(ArmStateName(ArmState::kFocused), "FOCUSED");
  idl::SetRawEnum(&m.state, 8);
  back = ArmStatusFromIdl(m);
  ASSERT_FALSE(back.ok());
  EXPECT_NE(back.status().message().find("dl/arm_status state"), std::string::npos);
}

}  // namespace
}  // namespace rover::msg
