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

}  // namespace
}  // namespace rover::msg
