#include "rover/msg/sequence_idl.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <string>

#include "rover/idl/access.hpp"

namespace rover::msg {
namespace {

TEST(SequenceIdl, CommandRoundTripKeepsTheTextAndRefusesOneTooLong) {
  SequenceCommand c;
  c.stamp = Time{17};
  c.command_id = 3;
  c.text = "TARGET rock = (5, 1, 0)\nVISODOM TURN TO rock\n";
  c.overrides = "rock = (6, 1, 0)\n";
  rover_apl_SequenceCommand m{};
  ASSERT_TRUE(SequenceCommandToIdl(c, &m).ok());
  EXPECT_EQ(SequenceCommandFromIdl(m).overrides, c.overrides);
  c.overrides = std::string(kMaxSequenceOverridesBytes + 1, 'x');
  EXPECT_FALSE(SequenceCommandToIdl(c, &m).ok());
  c.overrides.clear();
  ASSERT_TRUE(SequenceCommandToIdl(c, &m).ok());
  EXPECT_EQ(m.header.stamp_ns, 17);
  EXPECT_STREQ(m.text, c.text.c_str());
  const SequenceCommand back = SequenceCommandFromIdl(m);
  EXPECT_EQ(back.stamp, c.stamp);
  EXPECT_EQ(back.command_id, 3u);
  EXPECT_EQ(back.text, c.text);

  // The longest text fits exactly; one byte more is refused, not cut.
  c.text = std::string(kMaxSequenceTextBytes, 'x');
  ASSERT_TRUE(SequenceCommandToIdl(c, &m).ok());
  EXPECT_EQ(SequenceCommandFromIdl(m).text.size(), kMaxSequenceTextBytes);
  c.text += "y";
  c.command_id = 9;
  const Status too_long = SequenceCommandToIdl(c, &m);
  EXPECT_EQ(too_long.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(too_long.message(),
            "apl/sequence_command text is 4096 bytes; the message carries at most 4095");
  EXPECT_EQ(m.command_id, 3u);  // untouched
}

TEST(SequenceIdl, StatusRoundTripTruncatesTheMessageAndRefusesAnUnknownState) {
  SequenceStatus s;
  s.stamp = Time{99};
  s.command_id = 4;
  s.state = SequenceState::kFailed;
  s.step = 6;
  s.message = std::string(300, 'm');
  rover_apl_SequenceStatus m{};
  SequenceStatusToIdl(s, &m);
  EXPECT_EQ(m.state, rover_apl_SEQUENCE_FAILED);
  EXPECT_EQ(std::strlen(m.message), 127u);
  const auto back = SequenceStatusFromIdl(m);
  ASSERT_TRUE(back.ok()) << back.status().message();
  EXPECT_EQ(back->stamp, s.stamp);
  EXPECT_EQ(back->command_id, 4u);
  EXPECT_EQ(back->state, SequenceState::kFailed);
  EXPECT_EQ(back->step, 6u);
  EXPECT_EQ(back->message, std::string(127, 'm'));

  idl::SetRawEnum(&m.state, 7);
  const auto bad = SequenceStatusFromIdl(m);
  ASSERT_FALSE(bad.ok());
  EXPECT_EQ(bad.status().message(),
            "apl/sequence_status state = 7 is not a SequenceState (0..3)");
}

}  // namespace
}  // namespace rover::msg
