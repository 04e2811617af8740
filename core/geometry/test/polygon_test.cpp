#include "rover/geometry/polygon.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace rover::geometry {
namespace {

using V = Eigen::Vector2d;

TEST(PolygonTest, SegmentsTouchAtCrossingsEndsAndCollinearOverlaps) {
  EXPECT_TRUE(SegmentsTouch(V(0, 0), V(2, 2), V(0, 2), V(2, 0)));   // proper crossing
  EXPECT_TRUE(SegmentsTouch(V(0, 0), V(1, 0), V(1, 0), V(1, 1)));   // shared end
  EXPECT_TRUE(SegmentsTouch(V(0, 0), V(2, 0), V(1, 0), V(3, 0)));   // collinear overlap
  EXPECT_FALSE(SegmentsTouch(V(0, 0), V(1, 0), V(2, 0), V(3, 0)));  // collinear, apart
  EXPECT_FALSE(SegmentsTouch(V(0, 0), V(1, 0), V(0, 1), V(1, 1)));  // parallel
  EXPECT_FALSE(SegmentsTouch(V(0, 0), V(1, 1), V(1, 0), V(2, -1)));
}

TEST(PolygonTest, DistanceToSegmentClampsToTheEnds) {
  EXPECT_DOUBLE_EQ(DistanceToSegment(V(0, 0), V(2, 0), V(1, 3)), 3.0);
  EXPECT_DOUBLE_EQ(DistanceToSegment(V(0, 0), V(2, 0), V(5, 4)), 5.0);
  EXPECT_DOUBLE_EQ(DistanceToSegment(V(1, 1), V(1, 1), V(4, 5)), 5.0);
}

TEST(PolygonTest, WhyNotSimpleNamesTheFirstProblem) {
  const std::vector<V> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_EQ(WhyNotSimple(square), "");
  const std::vector<V> bow{{0, 0}, {2, 2}, {2, 0}, {0, 2}};
  EXPECT_EQ(WhyNotSimple(bow), "edges 0 and 2 cross");
  const std::vector<V> repeated{{0, 0}, {1, 0}, {1, 0}, {0, 1}};
  EXPECT_EQ(WhyNotSimple(repeated), "vertices 1 and 2 are equal");
  const std::vector<V> closed_twice{{0, 0}, {1, 0}, {0, 1}, {0, 0}};
  EXPECT_EQ(WhyNotSimple(closed_twice), "vertices 3 and 0 are equal");
  const std::vector<V> flat{{0, 0}, {1, 0}, {2, 0}};
  EXPECT_EQ(WhyNotSimple(flat), "edges 0 and 2 overlap");  // edge 2 runs back along edge 0
  const std::vector<V> fold{{0, 0}, {2, 0}, {1, 0}, {1, 1}};  // edge 1 runs back along edge 0
  EXPECT_EQ(WhyNotSimple(fold), "edges 0 and 1 overlap");
  const std::vector<V> concave{{0, 0}, {4, 0}, {4, 4}, {2, 1}, {0, 4}};
  EXPECT_EQ(WhyNotSimple(concave), "");
}

TEST(PolygonTest, InsideAndDistanceOfAConcavePolygon) {
  const std::vector<V> u{{0, 0}, {3, 0}, {3, 3}, {2, 3}, {2, 1}, {1, 1}, {1, 3}, {0, 3}};
  EXPECT_TRUE(InsidePolygon(u, V(0.5, 2.0)));
  EXPECT_TRUE(InsidePolygon(u, V(2.5, 2.0)));
  EXPECT_FALSE(InsidePolygon(u, V(1.5, 2.0)));  // in the notch
  EXPECT_FALSE(InsidePolygon(u, V(-1.0, 0.5)));
  EXPECT_DOUBLE_EQ(DistanceToPolygon(u, V(1.5, 2.0)), 0.5);
  EXPECT_DOUBLE_EQ(DistanceToPolygon(u, V(-1.0, 0.5)), 1.0);
  EXPECT_TRUE(std::isinf(DistanceToPolygon({}, V(0, 0))));
}

}  // namespace
}  // namespace rover::geometry
