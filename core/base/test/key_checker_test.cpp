#include "rover/base/key_checker.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover {
namespace {

TEST(KeyCheckerTest, PassingChecksLeaveItOk) {
  KeyChecker c;
  EXPECT_TRUE(c.Finite("a", 1.0));
  EXPECT_TRUE(c.Positive("b", 1e-9));
  EXPECT_TRUE(c.AtLeast("c", 0.0, 0.0));
  EXPECT_TRUE(c.InRange("d", 1.5, 0.5, 1.5));
  EXPECT_TRUE(c.ok());
  EXPECT_TRUE(c.key().empty());
}

TEST(KeyCheckerTest, EachCheckNamesTheKeyAndTheValue) {
  struct Case {
    bool (*check)(KeyChecker&);
    const char* message;
  };
  const Case cases[] = {
      {[](KeyChecker& c) { return c.Finite("x", std::nan("")); }, "x: nan is not a finite number"},
      {[](KeyChecker& c) { return c.Positive("x", 0.0); }, "x: 0 must be > 0"},
      {[](KeyChecker& c) { return c.Positive("x", INFINITY); }, "x: inf is not a finite number"},
      {[](KeyChecker& c) { return c.AtLeast("x", -0.25, 0.0); }, "x: -0.25 must be >= 0"},
      {[](KeyChecker& c) { return c.InRange("x", 2.0, 0.5, 1.5); },
       "x: 2 is out of range [0.5, 1.5]"},
      {[](KeyChecker& c) { return c.InRange("x", 1e7, 0.0, 1e6); },
       "x: 1e+07 is out of range [0, 1e+06]"},
  };
  for (const Case& k : cases) {
    KeyChecker c;
    EXPECT_FALSE(k.check(c));
    EXPECT_EQ(c.status().code(), StatusCode::kInvalidArgument);
    EXPECT_EQ(c.status().message(), k.message);
    EXPECT_EQ(c.key(), "x");
  }
}

TEST(KeyCheckerTest, KeepsTheFirstFailureOnly) {
  KeyChecker c;
  EXPECT_TRUE(c.Positive("a", 1.0));
  EXPECT_FALSE(c.Positive("b", -1.0));
  EXPECT_FALSE(c.Fail("c", "later"));
  EXPECT_FALSE(c.Finite("d", NAN));
  EXPECT_EQ(c.key(), "b");
  EXPECT_EQ(c.status().message(), "b: -1 must be > 0");
}

TEST(KeyCheckerTest, ChainedChecksStopAtTheFirstFailure) {
  KeyChecker c;
  int later = 0;
  (void)(c.Positive("r", -1.0) && (++later, c.InRange("r", -1.0, 0.0, 1.0)));
  EXPECT_EQ(later, 0);
}

}  // namespace
}  // namespace rover
