#include "rover/apl/mobility/motion_geometry.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "rover/base/units.hpp"

namespace rover::apl::mobility {
namespace {

TEST(MotionGeometry, PropagateArcsStraightsAndTurns) {
  const Pose2 start{1.0, 2.0, kPi / 2};
  Pose2 p = Propagate(start, {PrimitiveKind::kStraight, 0.0, 2.0, 0.0});
  EXPECT_NEAR(p.x, 1.0, 1e-12);
  EXPECT_NEAR(p.y, 4.0, 1e-12);
  // A quarter circle of radius 1 to the left from heading north-west... from +y heading.
  p = Propagate(start, {PrimitiveKind::kArc, 1.0, kPi / 2, 0.0});
  EXPECT_NEAR(p.x, 0.0, 1e-12);
  EXPECT_NEAR(p.y, 3.0, 1e-12);
  EXPECT_NEAR(p.heading, kPi, 1e-12);
  // Backward arc: heading changes by k s (negative).
  p = Propagate({0, 0, 0}, {PrimitiveKind::kArc, 1.0, -kPi / 2, 0.0});
  EXPECT_NEAR(p.x, -1.0, 1e-12);
  EXPECT_NEAR(p.y, 1.0, 1e-12);
  EXPECT_NEAR(p.heading, -kPi / 2, 1e-12);
  p = Propagate(start, {PrimitiveKind::kTurnInPlace, 0.0, 0.0, kPi});
  EXPECT_NEAR(p.x, 1.0, 1e-12);
  EXPECT_NEAR(p.heading, -kPi / 2, 1e-12);
}

TEST(MotionGeometry, SweptCentreSamplesTheTrack) {
  const auto pts = SweptCentre({0, 0, 0}, {PrimitiveKind::kStraight, 0.0, 1.0, 0.0}, 0.1);
  ASSERT_EQ(pts.size(), 11u);
  EXPECT_NEAR(pts.back().x(), 1.0, 1e-12);
  EXPECT_EQ(SweptCentre({0, 0, 0}, {PrimitiveKind::kTurnInPlace, 0, 0, 1.0}, 0.1).size(), 1u);
}

TEST(MotionGeometry, SimplePolygons) {
  KeepOutZone z{"a", {{0, 0}, {1, 0}, {1, 1}, {0, 1}}};
  EXPECT_TRUE(CheckSimplePolygon("keep_out[0]", z).ok());
  z.vertices = {{0, 0}, {2, 2}, {2, 0}, {0, 1}};  // bow tie
  Status s = CheckSimplePolygon("keep_out[0]", z);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("keep_out[0] ('a').vertices: edges 0 and 2 cross"), std::string::npos)
      << s.message();
  z.vertices = {{0, 0}, {1, 0}, {2, 0}};  // collinear, no area
  EXPECT_FALSE(CheckSimplePolygon("k", z).ok());
  z.vertices = {{0, 0}, {1, 0}, {1, 0}, {0, 1}};
  s = CheckSimplePolygon("k", z);
  EXPECT_NE(s.message().find("are equal"), std::string::npos);
  z.vertices = {{0, 0}, {std::nan(""), 0}, {0, 1}};
  s = CheckSimplePolygon("k", z);
  EXPECT_NE(s.message().find("vertices[1].x is nan"), std::string::npos) << s.message();
  z.vertices = {{0, 0}, {2, 0}, {1, 0}, {1, 1}};  // folds back along itself
  EXPECT_FALSE(CheckSimplePolygon("k", z).ok());
  z.vertices = {{0, 0}, {4, 0}, {4, 4}, {2, 1}, {0, 4}};  // concave but simple
  EXPECT_TRUE(CheckSimplePolygon("k", z).ok());
}

TEST(MotionGeometry, InsideAndDistance) {
  const std::vector<Eigen::Vector2d> sq = {{0, 0}, {2, 0}, {2, 2}, {0, 2}};
  EXPECT_TRUE(InsidePolygon(sq, {1, 1}));
  EXPECT_FALSE(InsidePolygon(sq, {3, 1}));
  EXPECT_NEAR(DistanceToPolygon(sq, {3, 1}), 1.0, 1e-12);
  EXPECT_NEAR(DistanceToPolygon(sq, {1, 1.5}), 0.5, 1e-12);
  const std::vector<Eigen::Vector2d> path = {{-2, 1}, {-1, 1}, {-0.5, 1}, {1, 1}};
  const KeepOutHit hit = FirstKeepOutHit(path, {{"sq", sq}}, 0.6);
  EXPECT_EQ(hit.point, 2);  // 0.5 m from the edge, inside the margin
  EXPECT_EQ(hit.zone, 0);
  EXPECT_FALSE(FirstKeepOutHit(path, {{"sq", sq}}, 0.0).point == 1);
}

TEST(MotionGeometry, MarsLocalMeanSolarTime) {
  const double t0 = 946728000.0;  // J2000 noon UTC
  const double h = MarsLocalMeanSolarTimeHours(t0, 0.0);
  EXPECT_GE(h, 0.0);
  EXPECT_LT(h, 24.0);
  // Allison & McEwen (2000) eq. 32: MSD = (JD_TT - 2451549.5) / 1.0274912517 + 44796.0 -
  // 0.0009626, which is 44791.6202 at J2000 noon UTC (JD_TT 2451545.0008): MST 14.885 h.
  EXPECT_NEAR(h, 14.885, 0.005);
  // One sol later: the same time; 15 deg east: one hour later; one Mars hour later: +1 h.
  EXPECT_NEAR(MarsLocalMeanSolarTimeHours(t0 + 88775.244, 0.0), h, 1e-6);
  EXPECT_NEAR(MarsLocalMeanSolarTimeHours(t0, 15.0 * kPi / 180.0), std::fmod(h + 1.0, 24.0), 1e-9);
  EXPECT_NEAR(MarsLocalMeanSolarTimeHours(t0 + kSecondsPerMarsHour, 0.0), std::fmod(h + 1.0, 24.0),
              1e-6);
}

}  // namespace
}  // namespace rover::apl::mobility
