#include "rover/recording/topic_filter.hpp"

#include <gtest/gtest.h>

namespace rover::recording {
namespace {

TEST(GlobMatch, StarsQuestionMarksAndLiterals) {
  EXPECT_TRUE(GlobMatch("ddl/*", "ddl/imu"));
  EXPECT_TRUE(GlobMatch("ddl/*", "ddl/"));
  EXPECT_FALSE(GlobMatch("ddl/*", "dl/pose"));
  EXPECT_TRUE(GlobMatch("*", "sim/clock"));
  EXPECT_TRUE(GlobMatch("*", ""));
  EXPECT_TRUE(GlobMatch("*/pose", "dl/pose"));
  EXPECT_FALSE(GlobMatch("*/pose", "dl/pose_odometry"));
  EXPECT_TRUE(GlobMatch("dl/pose*", "dl/pose_odometry"));
  EXPECT_TRUE(GlobMatch("d?/pose", "dl/pose"));
  EXPECT_FALSE(GlobMatch("d?/pose", "ddl/pose"));
  EXPECT_TRUE(GlobMatch("*l/*e", "ddl/joint_state"));
  EXPECT_TRUE(GlobMatch("dl/pose", "dl/pose"));
  EXPECT_FALSE(GlobMatch("dl/pose", "dl/pos"));
  EXPECT_FALSE(GlobMatch("dl/pos", "dl/pose"));
  EXPECT_TRUE(GlobMatch("a*b*c", "aXXbYYbZc"));
  EXPECT_FALSE(GlobMatch("a*b*c", "aXXbYYbZ"));
  EXPECT_TRUE(GlobMatch("**", "x"));
}

TEST(TopicFilter, IncludeThenExclude) {
  TopicFilter all;
  EXPECT_TRUE(all.Selects("hw/imu"));
  TopicFilter f{{"ddl/*", "dl/range_image"}, {"ddl/stereo_frame"}};
  EXPECT_TRUE(f.Selects("ddl/imu"));
  EXPECT_TRUE(f.Selects("dl/range_image"));
  EXPECT_FALSE(f.Selects("ddl/stereo_frame"));
  EXPECT_FALSE(f.Selects("dl/pose"));
  TopicFilter no_images{{}, {"hw/camera_frame", "ddl/stereo_frame"}};
  EXPECT_TRUE(no_images.Selects("dl/pose"));
  EXPECT_FALSE(no_images.Selects("hw/camera_frame"));
}

TEST(TopicFilter, ValidateAndDescribe) {
  EXPECT_TRUE((TopicFilter{{"ddl/*"}, {}}).Validate().ok());
  const Status empty = TopicFilter{{""}, {}}.Validate();
  EXPECT_EQ(empty.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(empty.message().find("topics: empty topic pattern"), std::string::npos);
  const Status space = TopicFilter{{}, {"dl/ pose"}}.Validate();
  EXPECT_NE(space.message().find("exclude: topic pattern 'dl/ pose' contains whitespace"),
            std::string::npos)
      << space.message();
  EXPECT_EQ(TopicFilter{}.Describe(), "every topic");
  EXPECT_EQ((TopicFilter{{"ddl/*", "dl/pose"}, {"ddl/imu"}}).Describe(),
            "ddl/*, dl/pose (excluding ddl/imu)");
}

}  // namespace
}  // namespace rover::recording
