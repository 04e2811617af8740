// From a path to waypoints: Douglas-Peucker with safe legs, the constrained least-squares fit,
// turn-in-place + straight legs.
#include "rover/apl/roaman/waypoint_fit.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "scenes.hpp"

namespace rover::apl::roaman {
namespace {

using testing::ClassMap;
using testing::Paint;

const Footprint kRover = RoamanOptions{}.footprint();

PlanningGrid Grid(const TraversabilityMap& t, Eigen::Vector2d goal = {10.0, 0.0}) {
  RoamanOptions o;
  o.plan_width = 8.0;
  return BuildPlanningGrid(t, {0.0, 0.0}, goal, 11.5, o);
}

TEST(WaypointFit, LegsTurnInPlaceThenDriveStraight) {
  const auto legs = MakeLegs({{0, 0}, {2, 0}, {2, 2}, {0, 2}, {0, 0}});
  ASSERT_EQ(legs.size(), 4u);
  EXPECT_NEAR(legs[0].heading, 0.0, 1e-12);
  EXPECT_NEAR(legs[0].turn, 0.0, 1e-12);  // the first turn depends on the rover's heading
  EXPECT_NEAR(legs[1].heading, 0.5 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(legs[1].turn, 0.5 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(legs[2].turn, 0.5 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(legs[3].turn, 0.5 * std::numbers::pi, 1e-12);  // -pi/2 - pi = -3pi/2 -> +pi/2
  EXPECT_NEAR(legs[3].length, 2.0, 1e-12);
  const auto back = MakeLegs({{0, 0}, {1, 0}, {0, 0}});
  EXPECT_NEAR(back[1].turn, std::numbers::pi, 1e-12);  // (-pi, pi]
}

TEST(WaypointFit, TurnsNeedTheFootprintsReach) {
  // W/2 straight on, W/2 + L/2 sin(turn) for gentle turns, the turn radius for sharp ones.
  EXPECT_DOUBLE_EQ(kRover.TurnClearance(0.0), 0.58);
  EXPECT_NEAR(kRover.TurnClearance(10.0 * kDegree), 0.58 + 0.75 * std::sin(10.0 * kDegree), 1e-12);
  EXPECT_NEAR(kRover.TurnClearance(-10.0 * kDegree), kRover.TurnClearance(10.0 * kDegree), 1e-12);
  EXPECT_DOUBLE_EQ(kRover.TurnClearance(45.0 * kDegree), kRover.turn_radius());
  EXPECT_DOUBLE_EQ(kRover.TurnClearance(3.0), kRover.turn_radius());
  EXPECT_NEAR(TurnAngle({0, 0}, {1, 0}, {1, 1}), 0.5 * std::numbers::pi, 1e-12);
  EXPECT_NEAR(TurnAngle({0, 0}, {1, 0}, {2, -1}), -0.25 * std::numbers::pi, 1e-12);
}

TEST(WaypointFit, SamplesKeepEveryVertex) {
  std::vector<int> index;
  const auto pts = SamplePath({{0, 0}, {1, 0}, {1, 0.5}}, 0.1, &index);
  ASSERT_EQ(index.size(), 3u);
  EXPECT_EQ(index[0], 0);
  EXPECT_EQ(index[1], 10);
  EXPECT_EQ(index[2], 15);
  EXPECT_EQ(pts.size(), 16u);
  EXPECT_EQ(pts[10], Eigen::Vector2d(1, 0));
}

TEST(WaypointFit, DouglasPeuckerKeepsCornersAndNeverCutsAHazard) {
  const TraversabilityMap open = ClassMap(-5, -5, 15, 5, 0.05, CellClass::kSafe);
  const PlanningGrid g = Grid(open);
  // A straight run of vertices: just its ends. An L: the corner too.
  std::vector<Eigen::Vector2d> line;
  for (int k = 0; k <= 20; ++k) line.emplace_back(0.4 * k, 0.01 * (k % 2));
  EXPECT_EQ(SelectWaypoints(g, line, 0.25, kRover), (std::vector<int>{0, 20}));
  std::vector<Eigen::Vector2d> ell;
  for (int k = 0; k <= 10; ++k) ell.emplace_back(0.5 * k, 0.0);
  for (int k = 1; k <= 6; ++k) ell.emplace_back(5.0, -0.5 * k);
  EXPECT_EQ(SelectWaypoints(g, ell, 0.25, kRover), (std::vector<int>{0, 10, 16}));
  // A rock inside the corner: with a huge tolerance the chord would do, but it passes 0.3 m
  // from the rock, less than half the rover's width: the corner stays.
  TraversabilityMap rock = open;
  Paint(&rock, {3.0, -1.5}, {3.0, -1.5}, 0.3, CellClass::kStep);
  const PlanningGrid r = Grid(rock);
  const std::vector<int> keep = SelectWaypoints(r, ell, 10.0, kRover);
  EXPECT_GT(keep.size(), 2u);
  std::vector<Eigen::Vector2d> w;
  for (const int k : keep) w.push_back(ell[static_cast<std::size_t>(k)]);
  for (std::size_t k = 1; k < w.size(); ++k) EXPECT_TRUE(r.SegmentClear(w[k - 1], w[k], 0.58));
}

TEST(WaypointFit, AWaypointWhoseTurnIsNotSafeGetsItsPathBack) {
  // A path that bends gently (8° per vertex, 48° in all) past a rock 0.75 m outside the bend:
  // each small turn is safe there (needs 0.58 + 0.75 sin 8° = 0.68 m), the one sharper turn a
  // chord would make at the corner is not (28° needs 0.93 m).
  TraversabilityMap t = ClassMap(-5, -5, 15, 5, 0.05, CellClass::kSafe);
  std::vector<Eigen::Vector2d> bend{{0, 0}};
  double heading = 0.0;
  for (int k = 0; k < 6; ++k) {
    bend.push_back(bend.back() + 0.5 * Eigen::Vector2d(std::cos(heading), std::sin(heading)));
    heading += 8.0 * kDegree;
  }
  for (int k = 0; k < 4; ++k) {
    bend.push_back(bend.back() + 0.5 * Eigen::Vector2d(std::cos(heading), std::sin(heading)));
  }
  const Eigen::Vector2d corner = bend[5];
  const Eigen::Vector2d out = Eigen::Vector2d(-std::sin(20 * kDegree), std::cos(20 * kDegree));
  const Eigen::Vector2d rock = corner - 0.8 * out;
  Paint(&t, rock, rock, 0.05, CellClass::kStep);
  const PlanningGrid g = Grid(t);
  ASSERT_TRUE(PolylineSafe(g, bend, kRover));  // the path itself is safe
  // Douglas-Peucker alone would keep the corner: a 28° turn there is not safe.
  EXPECT_FALSE(PolylineSafe(g, {bend[0], bend[5], bend[10]}, kRover));
  const std::vector<int> keep = SelectWaypoints(g, bend, 0.1, kRover);
  std::vector<Eigen::Vector2d> w;
  for (const int k : keep) w.push_back(bend[static_cast<std::size_t>(k)]);
  EXPECT_TRUE(PolylineSafe(g, w, kRover));
  EXPECT_GT(keep.size(), 3u);
  // Without the rock the same tolerance needs fewer waypoints.
  const PlanningGrid open = Grid(ClassMap(-5, -5, 15, 5, 0.05, CellClass::kSafe));
  EXPECT_LT(SelectWaypoints(open, bend, 0.1, kRover).size(), keep.size());
}

TEST(WaypointFit, TheLeastSquaresFitImprovesTheFitAndKeepsLegsSafe) {
  // A wavy path (the medial axis wanders) past a rock; three waypoints chosen by hand.
  TraversabilityMap t = ClassMap(-5, -5, 15, 5, 0.05, CellClass::kSafe);
  Paint(&t, {4.0, 1.45}, {4.0, 1.45}, 0.4, CellClass::kStep);
  const PlanningGrid g = Grid(t);
  std::vector<Eigen::Vector2d> path;
  for (int k = 0; k <= 160; ++k) {
    const double x = 0.05 * k;
    path.emplace_back(x, 0.6 * std::sin(std::numbers::pi * x / 8.0) + 0.05 * std::sin(5.0 * x));
  }
  const std::vector<Eigen::Vector2d> initial{{0.0, 0.0}, {2.0, 0.2}, {6.0, 0.2}, {8.0, 0.0}};
  ASSERT_TRUE(PolylineSafe(g, initial, kRover));
  const FitResult fit = FitWaypoints(g, path, initial, kRover, 400);
  EXPECT_LT(fit.error_after, 0.5 * fit.error_before) << fit.outcome;
  EXPECT_NEAR(fit.error_after, FitError(path, fit.waypoints), 1e-12);
  EXPECT_GT(fit.evaluations, 10);
  ASSERT_EQ(fit.waypoints.size(), 4u);
  EXPECT_EQ(fit.waypoints.front(), initial.front());
  EXPECT_EQ(fit.waypoints.back(), initial.back());
  EXPECT_TRUE(PolylineSafe(g, fit.waypoints, kRover));
  // The rock constrains the fit: without it the middle waypoints rise further toward the arc.
  const PlanningGrid free = Grid(ClassMap(-5, -5, 15, 5, 0.05, CellClass::kSafe));
  const FitResult unconstrained = FitWaypoints(free, path, initial, kRover, 400);
  EXPECT_LT(unconstrained.error_after, fit.error_after);
  EXPECT_FALSE(PolylineSafe(g, unconstrained.waypoints, kRover));
}

TEST(WaypointFit, NothingToFitOrFitDisabled) {
  const PlanningGrid g = Grid(ClassMap(-5, -5, 15, 5, 0.05, CellClass::kSafe));
  const std::vector<Eigen::Vector2d> two{{0, 0}, {5, 0}};
  FitResult r = FitWaypoints(g, {{0, 0}, {2.5, 0.1}, {5, 0}}, two, kRover, 100);
  EXPECT_EQ(r.waypoints, two);
  EXPECT_EQ(r.outcome, "no interior waypoint to fit");
  const std::vector<Eigen::Vector2d> three{{0, 0}, {2.5, 0.5}, {5, 0}};
  r = FitWaypoints(g, {{0, 0}, {5, 0}}, three, kRover, 0);
  EXPECT_EQ(r.waypoints, three);
  EXPECT_EQ(r.outcome, "fit disabled (fit_max_evaluations = 0)");
}

}  // namespace
}  // namespace rover::apl::roaman
