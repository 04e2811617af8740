#include "rover/apl/enav/route_search.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "scene.hpp"

namespace rover::apl::enav {
namespace {

using testing::Block;
using testing::Blocks;
using testing::TerrainOf;
using testing::TestOptions;

constexpr double kPi = std::numbers::pi;

// A wall of 0.5 m blocks (taller than the belly) across x = 2, with a gap |y| < gap / 2.
std::vector<Block> WallWithGap(double gap) {
  std::vector<Block> wall;
  for (double y = -5.0; y <= 5.0 + 1e-9; y += 0.1) {
    if (std::abs(y) < 0.5 * gap) continue;
    wall.push_back({2.0, y, 0.1, 0.5});
  }
  return wall;
}

struct Searched {
  std::optional<Route> route;
  CostToGoField field{false};
};

Searched SearchOver(const HeightTerrain& t, const geometry::Pose2& start,
                    const Eigen::Vector2d& goal, double tolerance,
                    const RouteSearchOptions& options = {}) {
  Searched s;
  s.field.Update(t, goal, tolerance);
  s.route = RouteSearch().Search(t, s.field, start, goal, tolerance, options);
  return s;
}

TEST(RouteSearch, LatticeHeadingsAreTheCellOffsets) {
  EXPECT_DOUBLE_EQ(RouteSearch::Heading(0), 0.0);
  EXPECT_NEAR(RouteSearch::Heading(1), std::atan2(1.0, 2.0), 1e-12);
  EXPECT_NEAR(RouteSearch::Heading(4), 0.5 * kPi, 1e-12);
  EXPECT_NEAR(std::abs(RouteSearch::Heading(8)), kPi, 1e-12);
  EXPECT_NEAR(RouteSearch::Heading(12), -0.5 * kPi, 1e-12);
}

TEST(RouteSearch, NearTheStartAPoseNeedsNoMoreRoomThanTheRoverHas) {
  RouteSearchOptions o;
  o.margin = 0.03;
  o.near_start = 0.5;
  EXPECT_DOUBLE_EQ(NeededRoom(o, 0.2, 0.1), 0.03);   // room to spare: the margin
  EXPECT_NEAR(NeededRoom(o, 0.01, 0.1), 0.01, 1e-5);  // nearer a rock than the margin
  EXPECT_LT(NeededRoom(o, 0.01, 0.1), 0.01);           // as near as the start passes
  EXPECT_DOUBLE_EQ(NeededRoom(o, 0.01, 0.6), 0.03);  // beyond near_start: the margin
}

TEST(RouteSearch, OnOpenGroundItDrivesStraightToTheGoal) {
  const HeightTerrain t = TerrainOf(Blocks({}));
  const Searched s = SearchOver(t, {0.0, 0.0, 0.0}, {3.0, 0.0}, 0.3);
  ASSERT_TRUE(s.route.has_value());
  const Route& r = *s.route;
  EXPECT_TRUE(r.at_goal);
  ASSERT_GE(r.nodes.size(), 2u);
  EXPECT_DOUBLE_EQ(r.nodes.front().pose.x, 0.0);  // the rover's pose itself
  EXPECT_LE((r.nodes.back().pose.xy() - Eigen::Vector2d(3.0, 0.0)).norm(), 0.3);
  for (std::size_t k = 1; k < r.nodes.size(); ++k) {
    EXPECT_EQ(r.nodes[k].move, 1) << "node " << k;
    EXPECT_DOUBLE_EQ(r.nodes[k].pose.heading, 0.0);
  }
  // Cost: the distance driven on seen open ground (factor 1) to the tolerance's edge.
  EXPECT_NEAR(r.cost, 3.0 - 0.3, 0.25);  // + the field's coarser cells at the end
}

TEST(RouteSearch, TheLatticeIsAnchoredAtTheRoversExactPose) {
  // Off the map's cell centres and off its axes: every move is one the rover drives from
  // where it stands, so each node lies a whole lattice offset from the start.
  const HeightTerrain t = TerrainOf(Blocks({}));
  const geometry::Pose2 start{0.037, -0.021, 0.2};
  const Searched s = SearchOver(t, start, {3.0, 0.8}, 0.3);
  ASSERT_TRUE(s.route.has_value());
  const std::vector<RouteNode>& nodes = s.route->nodes;
  EXPECT_EQ(nodes.front().pose.xy(), start.xy());
  EXPECT_EQ(nodes.front().pose.heading, start.heading);
  const Eigen::Vector2d ex(std::cos(start.heading), std::sin(start.heading));
  const Eigen::Vector2d ey(-ex.y(), ex.x());
  for (const RouteNode& n : nodes) {
    const Eigen::Vector2d d = n.pose.xy() - start.xy();
    const double i = d.dot(ex) / 0.1, j = d.dot(ey) / 0.1;  // the test terrain's 0.1 m cells
    EXPECT_NEAR(i, std::round(i), 1e-6);
    EXPECT_NEAR(j, std::round(j), 1e-6);
    double dh = geometry::WrapAngle(n.pose.heading - start.heading);
    bool lattice = false;
    for (int h = 0; h < RouteSearch::kHeadings; ++h) {
      lattice = lattice || std::abs(geometry::WrapAngle(dh - RouteSearch::Heading(h))) < 1e-9;
    }
    EXPECT_TRUE(lattice) << "heading " << n.pose.heading;
  }
}

TEST(RouteSearch, ARoverNearerARockThanTheMarginCanLeave) {
  // The rover in a corridor of blocks (3 m long) with less room on each side than the route's
  // margin (but some): within near_start of the start a pose needs only that room, so the route
  // leaves along the corridor; demanding the margin everywhere (near_start 0) finds none.
  std::optional<HeightTerrain> t;
  double room = 0.0;
  for (double y = 0.6; y < 1.2 && !(room > 0.0); y += 0.05) {
    std::vector<Block> walls;
    for (double x = -1.5; x <= 1.5 + 1e-9; x += 0.1) {
      walls.push_back({x, y, 0.1, 0.5});
      walls.push_back({x, -y, 0.1, 0.5});
    }
    t.emplace(TerrainOf(Blocks(walls)));
    room = ClearanceChecker(*t).Room({0.0, 0.0, 0.0});
  }
  ASSERT_GT(room, 0.0);
  RouteSearchOptions o;
  o.margin = room + 0.02;
  o.near_start = 3.0;
  const Searched s = SearchOver(*t, {0.0, 0.0, 0.0}, {4.0, 0.0}, 0.3, o);
  ASSERT_TRUE(s.route.has_value());
  EXPECT_TRUE(s.route->at_goal);
  for (const RouteNode& n : s.route->nodes) EXPECT_NE(n.move, -1);
  RouteSearchOptions strict = o;
  strict.near_start = 0.0;
  EXPECT_FALSE(SearchOver(*t, {0.0, 0.0, 0.0}, {4.0, 0.0}, 0.3, strict).route.has_value());
}

TEST(RouteSearch, ThroughAGapOnlyAlignedWithIt) {
  // The gap (1.6 m) is wider than the rover (1.16 m) but narrower than it is long (1.5 m):
  // it is crossed heading along x only. The rover starts facing west, away from it.
  const HeightTerrain t = TerrainOf(Blocks(WallWithGap(1.6)));
  const Searched s = SearchOver(t, {0.0, 2.5, 0.5 * kPi}, {4.0, 0.0}, 0.5);
  ASSERT_TRUE(s.route.has_value());
  const Route& r = *s.route;
  EXPECT_TRUE(r.at_goal);
  int turns = 0;
  bool crossed = false;
  for (const RouteNode& n : r.nodes) {
    turns += n.move == 0 ? 1 : 0;
    if (std::abs(n.pose.x - 2.0) <= 0.3) {
      crossed = true;
      EXPECT_LT(std::abs(n.pose.y), 0.4) << "at x " << n.pose.x;
      EXPECT_NEAR(std::abs(std::sin(n.pose.heading)), 0.0, 1e-9) << "heading " << n.pose.heading;
    }
  }
  EXPECT_TRUE(crossed);
  EXPECT_GT(turns, 0);
  EXPECT_GT(r.nodes.back().pose.x, 2.0);
}

// A square ring of 0.5 m blocks about (3, 0), 3 m a side (within the 5 m the test terrain
// sees), open on its west side |y| < gap / 2 less the blocks' half side.
std::vector<Block> Pen(double gap) {
  std::vector<Block> ring;
  for (double t = -1.5; t <= 1.5 + 1e-9; t += 0.1) {
    ring.push_back({3.0 + t, -1.5, 0.1, 0.5});
    ring.push_back({3.0 + t, 1.5, 0.1, 0.5});
    ring.push_back({4.5, t, 0.1, 0.5});
    if (std::abs(t) >= 0.5 * gap + 0.1) ring.push_back({1.5, t, 0.1, 0.5});
  }
  return ring;
}

TEST(RouteSearch, AGapNarrowerThanTheRoverHasNoRoute) {
  // 1.0 m is narrower than the track plus the wheels: every pose the rover can reach is
  // expanded and none is in the pen. 1.6 m lets it in, lined up with the gap.
  RouteSearchOptions all;
  all.max_expansions = 5000000;
  EXPECT_FALSE(SearchOver(TerrainOf(Blocks(Pen(1.0))), {-1.0, 0.0, 0.0}, {3.0, 0.0}, 0.5, all)
                   .route.has_value());
  const Searched in = SearchOver(TerrainOf(Blocks(Pen(1.6))), {-1.0, 0.0, 0.0}, {3.0, 0.0}, 0.5);
  ASSERT_TRUE(in.route.has_value());
  EXPECT_TRUE(in.route->at_goal);
}

TEST(RouteSearch, AStartOnARockOrAnExhaustedBudgetGivesNoRoute) {
  const HeightTerrain t = TerrainOf(Blocks({{0.6, 0.5, 0.1, 0.5}}));  // under the front wheel
  EXPECT_FALSE(SearchOver(t, {0.0, 0.0, 0.0}, {3.0, 0.0}, 0.3).route.has_value());
  const HeightTerrain open = TerrainOf(Blocks({}));
  RouteSearchOptions few;
  few.max_expansions = 5;  // 3 m takes about 30 forward moves
  EXPECT_FALSE(SearchOver(open, {0.0, 0.0, 0.0}, {3.0, 0.0}, 0.3, few).route.has_value());
}

TEST(RouteSearch, BackingIsPricedAgainstTurningInPlace) {
  // The goal 3 m behind on open ground: backing 2.7 m at twice the price (5.4) beats a half
  // turn in place (pi at 1 m/rad) and 2.7 m forward (5.8); at three times the price it turns.
  const HeightTerrain t = TerrainOf(Blocks({}));
  const Searched back = SearchOver(t, {0.0, 0.0, 0.0}, {-3.0, 0.0}, 0.3);
  ASSERT_TRUE(back.route.has_value());
  for (std::size_t k = 1; k < back.route->nodes.size(); ++k) {
    EXPECT_EQ(back.route->nodes[k].move, -1) << "node " << k;
  }
  RouteSearchOptions dear;
  dear.backward_factor = 3.0;
  const Searched turn = SearchOver(t, {0.0, 0.0, 0.0}, {-3.0, 0.0}, 0.3, dear);
  ASSERT_TRUE(turn.route.has_value());
  EXPECT_EQ(turn.route->nodes[1].move, 0);
  EXPECT_EQ(turn.route->nodes.back().move, 1);
}

TEST(RouteSearch, AGoalOffTheMapEndsOnItsBorder) {
  const HeightTerrain t = TerrainOf(Blocks({}));
  const Searched s = SearchOver(t, {0.0, 0.0, 0.0}, {30.0, 0.0}, 0.5);
  ASSERT_TRUE(s.route.has_value());
  EXPECT_FALSE(s.route->at_goal);
  // The 16 m map ends 8 m north of the origin (it is centred on the first scan).
  EXPECT_GT(s.route->nodes.back().pose.x, 7.5);
  EXPECT_TRUE(std::isfinite(s.route->cost));
}

}  // namespace
}  // namespace rover::apl::enav
