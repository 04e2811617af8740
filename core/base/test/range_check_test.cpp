#include "rover/base/range_check.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace rover {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

TEST(RangeCheck, FiniteNamesTheField) {
  EXPECT_TRUE(CheckFinite("curvature", 0.5).ok());
  const Status s = CheckFinite("curvature", std::nan(""));
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(s.message(), "curvature is nan (must be finite)");
  EXPECT_EQ(CheckFinite("speed", -kInf).message(), "speed is -inf (must be finite)");
}

TEST(RangeCheck, ClosedRangeWithUnit) {
  EXPECT_TRUE(CheckRange("max_tilt", 45.0, 0.0, 45.0, "deg").ok());
  EXPECT_EQ(CheckRange("max_tilt", 95.0, 0.0, 45.0, "deg").message(),
            "max_tilt = 95 deg is outside [0, 45]");
  EXPECT_EQ(CheckRange("max_tilt", kInf, 0.0, 45.0).message(), "max_tilt is inf (must be finite)");
}

TEST(RangeCheck, OpenBoundsExcludeTheirEnd) {
  EXPECT_FALSE(CheckPositive("step", 0.0).ok());
  EXPECT_EQ(CheckPositive("step", 0.0).message(), "step = 0 is outside (0, inf)");
  EXPECT_TRUE(CheckNonNegative("step", 0.0).ok());
  EXPECT_TRUE(CheckRange("d", 0.9, Bounds::OpenLow(0.0, 0.9)).ok());
  EXPECT_EQ(CheckRange("d", 0.0, Bounds::OpenLow(0.0, 0.9)).message(), "d = 0 is outside (0, 0.9]");
  EXPECT_EQ(Bounds::AtMost(3).ToString(), "(-inf, 3]");
}

TEST(RangeCheck, ElementsNameTheirIndex) {
  const std::vector<double> v{1.0, 2.0, std::nan("")};
  EXPECT_EQ(CheckAllFinite("xyz", v).message(), "xyz[2] is nan (must be finite)");
  const std::vector<double> w{1.0, 7.0};
  EXPECT_EQ(CheckAllInRange("gains", w, Bounds::Closed(0, 5)).message(),
            "gains[1] = 7 is outside [0, 5]");
  EXPECT_TRUE(CheckAllInRange("gains", std::vector<double>{0.0, 5.0}, Bounds::Closed(0, 5)).ok());
}

TEST(RangeCheck, Integers) {
  EXPECT_TRUE(CheckIntRange("cycles", 3, 1, 10).ok());
  EXPECT_EQ(CheckIntRange("cycles", 0, 1, 10).message(), "cycles = 0 is outside [1, 10]");
}

Status UsesAssignOrReturn(Result<int> in, int* out) {
  ROVER_ASSIGN_OR_RETURN(const int v, std::move(in));
  *out = v;
  return Status::Ok();
}

Result<int> Doubles(Result<int> in) {
  ROVER_ASSIGN_OR_RETURN(int v, std::move(in));
  return 2 * v;
}

TEST(AssignOrReturn, ValueOrEarlyReturn) {
  int out = 0;
  EXPECT_TRUE(UsesAssignOrReturn(Result<int>(4), &out).ok());
  EXPECT_EQ(out, 4);
  const Status s = UsesAssignOrReturn(Result<int>(NotFound("no camera")), &out);
  EXPECT_EQ(s.code(), StatusCode::kNotFound);
  EXPECT_EQ(out, 4);
  EXPECT_EQ(*Doubles(Result<int>(5)), 10);
  EXPECT_EQ(Doubles(Result<int>(Busy("x"))).status().code(), StatusCode::kBusy);
}

}  // namespace
}  // namespace rover
