#include "rover/msg/sensors.hpp"

#include <gtest/gtest.h>

#include <limits>

namespace rover::msg {
namespace {

TEST(SensorMessages, JointStateFiniteness) {
  JointState s;
  EXPECT_TRUE(s.AllFinite());
  s.bogie_angle[1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(s.AllFinite());
  s.bogie_angle[1] = 0.0;
  s.wheel_rate[5] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(s.AllFinite());
  s.wheel_rate[5] = 0.0;
  s.mast_pan = std::numeric_limits<double>::quiet_NaN();  // not a mobility joint
  EXPECT_TRUE(s.AllFinite());
}

}  // namespace
}  // namespace rover::msg
