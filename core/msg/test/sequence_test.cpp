#include "rover/msg/sequence.hpp"

#include <gtest/gtest.h>

namespace rover::msg {
namespace {

TEST(Sequence, StateNamesFollowTheIdlAndFlagUnknownValues) {
  EXPECT_STREQ(SequenceStateName(SequenceState::kIdle), "IDLE");
  EXPECT_STREQ(SequenceStateName(SequenceState::kRunning), "RUNNING");
  EXPECT_STREQ(SequenceStateName(SequenceState::kDone), "DONE");
  EXPECT_STREQ(SequenceStateName(SequenceState::kFailed), "FAILED");
  EXPECT_STREQ(SequenceStateName(static_cast<SequenceState>(4)), "UNKNOWN");
}

TEST(SequenceOverrides, FormatAndParseRoundTripAndBadLinesAreNamed) {
  const std::map<std::string, std::string> m = {{"target", "(2, -1, 0.5)"}, {"step", " 10 cm "}};
  Result<std::string> text = FormatSequenceOverrides(m);
  ASSERT_TRUE(text.ok()) << text.status().message();
  EXPECT_EQ(*text, "step = 10 cm\ntarget = (2, -1, 0.5)\n");
  Result<std::map<std::string, std::string>> back = ParseSequenceOverrides(*text);
  ASSERT_TRUE(back.ok());
  EXPECT_EQ(back->at("target"), "(2, -1, 0.5)");
  EXPECT_EQ(back->at("step"), "10 cm");
  EXPECT_TRUE(ParseSequenceOverrides("")->empty());
  EXPECT_EQ(ParseSequenceOverrides("a = 1\n\nstep 10 cm\n").status().message(),
            "overrides line 3: 'step 10 cm' has no '='");
  EXPECT_EQ(ParseSequenceOverrides("a b = 1\n").status().message(),
            "overrides line 1: name 'a b' is not a word");
  EXPECT_EQ(ParseSequenceOverrides("a = 1\na = 2\n").status().message(),
            "overrides line 2: a is given twice");
  EXPECT_EQ(ParseSequenceOverrides("a =\n").status().message(), "overrides line 1: a has no value");
  EXPECT_FALSE(FormatSequenceOverrides({{"x=y", "1"}}).ok());
  EXPECT_FALSE(FormatSequenceOverrides({{"x", "1\n2"}}).ok());
}

}  // namespace
}  // namespace rover::msg
