#include "rover/base/lockstep_rule.hpp"

#include <gtest/gtest.h>

namespace rover::lockstep {
namespace {

TEST(LockstepRuleTest, TopicBitIsEmptyOutsideTheMask) {
  EXPECT_EQ(TopicBit(0), 1u);
  EXPECT_EQ(TopicBit(63), TopicMask{1} << 63);
  EXPECT_EQ(TopicBit(-1), 0u);
  EXPECT_EQ(TopicBit(64), 0u);
}

TEST(LockstepRuleTest, ServesOnADeadlineOrANewSampleOfATopicItReads) {
  const std::vector<std::uint64_t> served = {4, 7, 1};
  const TopicMask reads = TopicBit(1);
  // Nothing new on topic 1, the deadline later: idle, whatever topics 0 and 2 do.
  EXPECT_FALSE(MustServe(100, {9, 7, 5}, reads, served, 200));
  // The deadline has come.
  EXPECT_TRUE(MustServe(200, {4, 7, 1}, reads, served, 200));
  EXPECT_TRUE(MustServe(100, {4, 7, 1}, reads, served, 0));  // 0: every tick
  // Topic 1 moved.
  EXPECT_TRUE(MustServe(100, {4, 8, 1}, reads, served, 200));
  // A topic the served frontier did not have yet counts from 0.
  EXPECT_TRUE(MustServe(100, {4, 7, 1, 2}, TopicBit(3), served, 200));
  EXPECT_FALSE(MustServe(100, {4, 7, 1, 0}, TopicBit(3), served, 200));
  // Reads nothing: only the deadline matters.
  EXPECT_FALSE(MustServe(100, {99, 99, 99}, 0, served, 200));
}

}  // namespace
}  // namespace rover::lockstep
