#include "rover/msg/range.hpp"

#include <gtest/gtest.h>

#include <string>

namespace rover::msg {
namespace {

TEST(RangeMessages, ArraySizesMustMatchTheImage) {
  RangeImage r;
  r.width = 4;
  r.height = 2;
  r.xyz.assign(24, 0.0F);
  r.valid.assign(8, 1);
  r.disparity.assign(8, 2.0F);
  EXPECT_TRUE(r.CheckSizes().ok());
  r.valid.pop_back();
  const Status s = r.CheckSizes();
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message(), "range image valid has 7 values; expected 8 for 4x2");
  r.valid.push_back(0);
  r.xyz.resize(8);
  EXPECT_NE(r.CheckSizes().message().find("xyz has 8 values; expected 24"), std::string::npos);
}

}  // namespace
}  // namespace rover::msg
