#include "rover/apl/sequencer/units.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace rover::apl::sequencer {
namespace {

TEST(Units, FindsKnownUnitsCaseSensitively) {
  ASSERT_NE(FindUnit("cm"), nullptr);
  EXPECT_EQ(FindUnit("cm")->dimension, Dimension::kLength);
  EXPECT_DOUBLE_EQ(FindUnit("cm")->to_si, 0.01);
  EXPECT_EQ(FindUnit("m/s")->dimension, Dimension::kSpeed);
  EXPECT_EQ(FindUnit("CM"), nullptr);
  EXPECT_EQ(FindUnit("meters"), nullptr);
  EXPECT_EQ(FindUnit(""), nullptr);       // a missing unit is not a unit
  EXPECT_EQ(FindUnit("count"), nullptr);  // declared-only
}

TEST(Units, DeclaredUnitsIncludeDimensionless) {
  EXPECT_EQ(DeclaredUnit("").dimension, Dimension::kNone);
  EXPECT_EQ(DeclaredUnit("count").dimension, Dimension::kNone);
  EXPECT_EQ(DeclaredUnit("1/m").dimension, Dimension::kCurvature);
  EXPECT_EQ(DeclaredUnit("px").dimension, Dimension::kPixel);
}

TEST(Units, ConvertsWithinADimension) {
  EXPECT_DOUBLE_EQ(*ConvertUnit(30.0, *FindUnit("cm"), DeclaredUnit("m"), "distance"), 0.3);
  EXPECT_NEAR(*ConvertUnit(std::numbers::pi / 2, *FindUnit("rad"), DeclaredUnit("deg"), "a"),
              90.0, 1e-12);
  EXPECT_DOUBLE_EQ(*ConvertUnit(2.0, *FindUnit("min"), DeclaredUnit("s"), "WAIT"), 120.0);
  EXPECT_DOUBLE_EQ(*ConvertUnit(5.0, *FindUnit("cm/s"), DeclaredUnit("m/s"), "speed"), 0.05);
}

TEST(Units, RefusesAnotherDimensionNamingBoth) {
  Result<double> r = ConvertUnit(5.0, *FindUnit("s"), DeclaredUnit("m"), "distance");
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message(),
            "unit 's' is a time; distance takes a length (m, cm, mm, km)");
  Result<double> count = ConvertUnit(5.0, *FindUnit("m"), DeclaredUnit(""), "REPEAT count");
  ASSERT_FALSE(count.ok());
  EXPECT_EQ(count.status().message(), "unit 'm' is a length; REPEAT count takes a plain number");
}

TEST(Units, ListsUnitsPerDimension) {
  EXPECT_EQ(UnitsOf(Dimension::kAngle), "deg, rad");
  EXPECT_EQ(UnitsOf(Dimension::kTime), "s, ms, min, h");
  EXPECT_EQ(UnitsOf(Dimension::kCurvature), "1/m");
  EXPECT_EQ(DimensionPhrase(Dimension::kAngle), "an angle");
  const auto names = UnitNames();
  EXPECT_NE(std::find(names.begin(), names.end(), "mm"), names.end());
  EXPECT_EQ(std::find(names.begin(), names.end(), "count"), names.end());
}

}  // namespace
}  // namespace rover::apl::sequencer
