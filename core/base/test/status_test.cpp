#include "rover/base/status.hpp"
#include "rover/base/check.hpp"

#include <gtest/gtest.h>

namespace rover {
namespace {

Status Fails() { return InvalidArgument("bad"); }
Status Chain() {
  ROVER_RETURN_IF_ERROR(Fails());
  return Internal("not reached");
}

TEST(Status, OkAndErrors) {
  EXPECT_TRUE(Status::Ok().ok());
  EXPECT_EQ(Status::Ok().ToString(), "ok");
  const Status s = OutOfRange("x is 5");
  EXPECT_FALSE(s.ok());
  EXPECT_EQ(s.ToString(), "out_of_range: x is 5");
  EXPECT_EQ(s.WithPrefix("file.yaml").message(), "file.yaml: x is 5");
  EXPECT_EQ(Chain().code(), StatusCode::kInvalidArgument);
}

TEST(Result, HoldsValueOrError) {
  Result<int> a = 3;
  ASSERT_TRUE(a.ok());
  EXPECT_EQ(*a, 3);
  Result<int> b = NotFound("nope");
  EXPECT_FALSE(b.ok());
  EXPECT_EQ(b.status().code(), StatusCode::kNotFound);
  Result<int> c = Status::Ok();  // a misuse becomes an internal error, not a fake value
  EXPECT_FALSE(c.ok());
  EXPECT_EQ(c.status().code(), StatusCode::kInternal);
}

TEST(Check, DemandAbortsWithMessage) {
  EXPECT_DEATH(ROVER_DEMAND_MSG(1 + 1 == 3, "arithmetic"), "invariant broken: 1 \\+ 1 == 3: arithmetic");
}

}  // namespace
}  // namespace rover
