#include "rover/msg/navigation.hpp"

#include <gtest/gtest.h>

namespace rover::msg {
namespace {

TEST(NavigationMsg, GoodnessMapSizesNameTheArray) {
  GoodnessMap m;
  m.width = 2;
  m.height = 2;
  m.goodness = {1, 2, 3, 4};
  m.certainty = {1, 2, 3};
  m.flags = {0, 0, 0, 0};
  Status s = m.CheckSizes();
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message(), "apl/goodness_map certainty: 3 cells for 4 = 2 x 2");
  m.certainty.push_back(4);
  EXPECT_TRUE(m.CheckSizes().ok());
  m.height = -1;
  s = m.CheckSizes();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("negative"), std::string::npos) << s.message();
  EXPECT_TRUE(GoodnessMap{}.CheckSizes().ok());  // an empty map is well formed
}

}  // namespace
}  // namespace rover::msg
