// The road map: medial axis per row, the virtual drive, and the depth-first search.
#include "rover/apl/roaman/road_map.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "rover/apl/roaman/waypoint_fit.hpp"
#include "scenes.hpp"

namespace rover::apl::roaman {
namespace {

using testing::ClassMap;
using testing::Paint;

// A corridor along +x of half-width `half` (hazard beyond it, out to |y| = 4).
TraversabilityMap Corridor(double half) {
  TraversabilityMap t = ClassMap(-5, -5, 20, 5, 0.05, CellClass::kSafe);
  const double mid = 0.5 * (half + 4.0), w = 0.5 * (4.0 - half);
  Paint(&t, {-5.0, mid}, {20.0, mid}, w, CellClass::kStep);
  Paint(&t, {-5.0, -mid}, {20.0, -mid}, w, CellClass::kStep);
  return t;
}

PlanProblem Prepare(const TraversabilityMap& t, Eigen::Vector2d goal, bool partial = false) {
  nav_core::PlanRequest r;
  r.goal = goal;
  r.allow_partial = partial;
  PlanFailure f = PlanFailure::kNone;
  auto p = PreparePlan(t, r, RoamanOptions{}, &f);
  EXPECT_TRUE(p.ok()) << p.status().message();
  return std::move(p).value();
}

TEST(RoadMap, TheMedialAxisOfAStraightCorridorIsItsCentreLine) {
  const PlanProblem p = Prepare(Corridor(1.5), {8.0, 0.0});
  const RoadMap road = BuildRoadMap(p.grid, RoamanOptions{});
  ASSERT_EQ(static_cast<int>(road.row_first.size()), p.grid.height + 1);
  for (int j = 0; j < p.grid.height; ++j) {
    ASSERT_EQ(road.row_first[j + 1] - road.row_first[j], 1) << "row " << j;
    const AxisRun& r = road.runs[static_cast<std::size_t>(road.row_first[j])];
    EXPECT_EQ(r.axis, (r.i0 + r.i1) / 2);
    const Eigen::Vector2d c = p.grid.Center(r.axis, j);
    EXPECT_NEAR(c.y(), 0.0, 0.05) << "row " << j;
    EXPECT_NEAR(p.grid.Center(r.i0, j).y(), -1.45, 0.06);
    EXPECT_NEAR(p.grid.Center(r.i1, j).y(), 1.45, 0.06);
  }
  // All kept but the rows near the grid's far and back edges (too near the unknown beyond).
  EXPECT_GT(road.nodes(), p.grid.height - 2 * 20);
  // Every connection goes toward the goal, at most lookahead / cell rows ahead.
  for (int k = 0; k < road.nodes(); ++k) {
    for (int e = road.edge_first[k]; e < road.edge_first[k + 1]; ++e) {
      const int dj =
          road.NodeCell(road.edge_to[static_cast<std::size_t>(e)]).y() - road.NodeCell(k).y();
      EXPECT_GE(dj, 1);
      EXPECT_LE(dj, 40);
    }
  }
}

TEST(RoadMap, TheVirtualDriveDropsCellsTooNarrowForTheFootprint) {
  TraversabilityMap t = Corridor(1.5);
  // A 1.0 m gap between x = 4 and 5: narrower than the 1.16 m rover.
  Paint(&t, {4.0, 1.0}, {5.0, 1.0}, 0.5, CellClass::kStep);
  Paint(&t, {4.0, -1.0}, {5.0, -1.0}, 0.5, CellClass::kStep);
  const PlanProblem p = Prepare(t, {8.0, 0.0});
  const RoadMap road = BuildRoadMap(p.grid, RoamanOptions{});
  int dropped_in_gap = 0;
  for (const AxisRun& r : road.runs) {
    const double x = p.grid.Center(r.axis, r.j).x();
    if (x > 4.0 && x < 5.0) {
      EXPECT_FALSE(r.kept);
      ++dropped_in_gap;
    }
  }
  EXPECT_GE(dropped_in_gap, 19);
  EXPECT_GE(road.dropped, dropped_in_gap);
  auto path = LongestRoadPath(road, p, RoamanOptions{});
  ASSERT_FALSE(path.ok());
  EXPECT_EQ(path.status().code(), StatusCode::kNotFound);
  EXPECT_NE(path.status().message().find("no connected path reaches the goal anchor (8, 0)"),
            std::string::npos);
}

TEST(RoadMap, ThePathTurnsOnlyWhereTheTurnIsSafe) {
  // A 1.6 m gap (x = 2 to 5) the rover fits through driving straight but could not turn in
  // (turn radius 0.95 m), then open ground; the goal lies off to the left beyond it.
  TraversabilityMap t = ClassMap(-5, -5, 20, 5, 0.05, CellClass::kSafe);
  Paint(&t, {2.0, 1.8}, {5.0, 1.8}, 1.0, CellClass::kStep);
  Paint(&t, {2.0, -1.8}, {5.0, -1.8}, 1.0, CellClass::kStep);
  const PlanProblem p = Prepare(t, {9.0, 2.5});
  const RoamanOptions o;
  auto path = LongestRoadPath(BuildRoadMap(p.grid, o), p, o);
  ASSERT_TRUE(path.ok()) << path.status().message();
  EXPECT_TRUE(path->reaches_goal);
  const std::vector<Eigen::Vector2d>& v = path->vertices;
  int cramped = 0;
  for (std::size_t k = 1; k + 1 < v.size(); ++k) {
    EXPECT_TRUE(TurnSafe(p.grid, p.footprint, v[k - 1], v[k], v[k + 1])) << v[k].transpose();
    cramped += p.grid.ClearanceAt(v[k]) < p.turn_clearance;
  }
  EXPECT_GT(cramped, 0);  // it did pass where a sharp turn would not have been safe
}

TEST(RoadMap, DepthFirstSearchTakesTheBranchThatReachesTheGoal) {
  // An island splits the corridor at x = 3..9; the left branch (y > 0) is closed at x = 7.
  TraversabilityMap t = Corridor(3.0);
  Paint(&t, {3.0, 0.0}, {9.0, 0.0}, 0.4, CellClass::kStep);
  Paint(&t, {7.0, 0.4}, {7.0, 3.0}, 0.2, CellClass::kStep);
  const PlanProblem p = Prepare(t, {10.5, 0.0});
  const RoamanOptions o;
  const RoadMap road = BuildRoadMap(p.grid, o);
  auto path = LongestRoadPath(road, p, o);
  ASSERT_TRUE(path.ok()) << path.status().message();
  EXPECT_TRUE(path->reaches_goal);
  EXPECT_EQ(path->vertices.back(), Eigen::Vector2d(10.5, 0.0));
  EXPECT_NEAR(path->goal_distance, 0.0, 1e-12);
  EXPECT_GT(path->expanded, 0u);
  // Every vertex along the island is on the right (y < 0) branch.
  for (const Eigen::Vector2d& v : path->vertices) {
    if (v.x() > 4.0 && v.x() < 8.0) {
      EXPECT_LT(v.y(), -0.5) << v.transpose();
    }
  }
  double length = 0.0;
  for (std::size_t k = 1; k < path->vertices.size(); ++k) {
    length += (path->vertices[k] - path->vertices[k - 1]).norm();
  }
  EXPECT_NEAR(path->length, length, 1e-9);
}

TEST(RoadMap, APartialPathEndsAsNearTheGoalAsTheMapAllows) {
  TraversabilityMap t = Corridor(2.0);
  const PlanProblem p = Prepare(t, {30.0, 0.0}, true);
  ASSERT_FALSE(p.goal_on_grid);
  const RoamanOptions o;
  auto path = LongestRoadPath(BuildRoadMap(p.grid, o), p, o);
  ASSERT_TRUE(path.ok()) << path.status().message();
  EXPECT_FALSE(path->reaches_goal);
  // The grid ends 12 m out; the last row the rover can turn on is a turn radius before it.
  EXPECT_GT(path->vertices.back().x(), 12.0 - 1.2);
  EXPECT_NEAR(path->goal_distance, 30.0 - path->vertices.back().x(), 0.06);
  // A wall across the corridor 0.5 m ahead: no progress is possible.
  Paint(&t, {0.9, -2.0}, {0.9, 2.0}, 0.1, CellClass::kStep);
  const PlanProblem q = Prepare(t, {30.0, 0.0}, true);
  auto none = LongestRoadPath(BuildRoadMap(q.grid, o), q, o);
  ASSERT_FALSE(none.ok());
  EXPECT_NE(none.status().message().find("no connected path gets 0.5 m nearer the goal (30, 0)"),
            std::string::npos);
}

}  // namespace
}  // namespace rover::apl::roaman
