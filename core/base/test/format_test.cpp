#include "rover/base/format.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace rover {
namespace {

TEST(FormatNumber, ShortestOfFixedAndExponent) {
  EXPECT_EQ(FormatNumber(0.125), "0.125");
  EXPECT_EQ(FormatNumber(3.0), "3");
  EXPECT_EQ(FormatNumber(1e-6), "1e-06");
  EXPECT_EQ(FormatNumber(123456789.0), "1.23457e+08");
  EXPECT_EQ(FormatNumber(2.0 / 3.0, 3), "0.667");
}

TEST(FormatNumber, NonFinite) {
  EXPECT_EQ(FormatNumber(std::nan("")), "nan");
  EXPECT_EQ(FormatNumber(std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(FormatNumber(-std::numeric_limits<double>::infinity()), "-inf");
}

TEST(FormatList, Brackets) {
  const std::vector<double> v{1.0, 0.5, -2.0};
  EXPECT_EQ(FormatList(v), "[1, 0.5, -2]");
  EXPECT_EQ(FormatList(std::vector<double>{}), "[]");
}

TEST(FormatSize, WidthByHeight) {
  EXPECT_EQ(FormatSize(640, 480), "640x480");
  EXPECT_EQ(FormatSize(0, -1), "0x-1");
}

}  // namespace
}  // namespace rover
