#include "rover/apl/gestalt/arc_geometry.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>

#include "rover/sim/terrain/random.hpp"

namespace rover::apl::gestalt {
namespace {

TEST(ArcPoint, ForwardBackwardAndStraight) {
  // A quarter circle of radius 1 to the left.
  const Eigen::Vector2d q = ArcPoint(1.0, 1, std::numbers::pi / 2);
  EXPECT_NEAR(q.x(), 1.0, 1e-12);
  EXPECT_NEAR(q.y(), 1.0, 1e-12);
  // Backward mirrors x.
  const Eigen::Vector2d b = ArcPoint(1.0, -1, std::numbers::pi / 2);
  EXPECT_NEAR(b.x(), -1.0, 1e-12);
  EXPECT_NEAR(b.y(), 1.0, 1e-12);
  EXPECT_NEAR(ArcPoint(0.0, 1, 2.0).x(), 2.0, 1e-12);
  EXPECT_NEAR(ArcPoint(1e-12, -1, 2.0).x(), -2.0, 1e-9);
  // The circle through the rover and a goal: k* = 2 y / (x^2 + y^2).
  const Eigen::Vector2d goal(2.0, 1.0);
  const double k = 2.0 * goal.y() / goal.squaredNorm();
  double best = 1e9;
  for (int n = 0; n <= 4000; ++n) best = std::min(best, (ArcPoint(k, 1, 0.001 * n) - goal).norm());
  EXPECT_LT(best, 1e-3);
}

// Nearest point by dense sampling.
ArcProjection SampledProjection(const ArcPath& path, const Eigen::Vector2d& p) {
  ArcProjection best{1e9, 0.0};
  const int n = 20000;
  for (int k = 0; k <= n; ++k) {
    const double s = path.s_min + (path.s_max - path.s_min) * k / n;
    const double d = (ArcPoint(path.curvature, path.direction, s) - p).norm();
    if (d < best.distance) best = {d, s};
  }
  return best;
}

TEST(ProjectOntoArc, MatchesDenseSampling) {
  sim::terrain::Rng rng(21);
  for (double k : {-2.0, -1.0, -0.3, 0.0, 0.45, 1.0}) {
    for (int dir : {1, -1}) {
      const ArcPath path{k, dir, 0.3, 3.0};
      for (int t = 0; t < 60; ++t) {
        const Eigen::Vector2d p(rng.Uniform(-4.0, 4.0), rng.Uniform(-4.0, 4.0));
        const ArcProjection a = ProjectOntoArc(path, p);
        const ArcProjection b = SampledProjection(path, p);
        EXPECT_NEAR(a.distance, b.distance, 2e-4) << "k " << k << " dir " << dir;
        if (std::abs(a.distance - b.distance) < 1e-5 && b.distance > 1e-3) {
          EXPECT_NEAR(a.s, b.s, 5e-3) << "k " << k << " dir " << dir;
        }
      }
    }
  }
}

nav_core::GoodnessMap Geometry(int n, double r) {
  nav_core::GoodnessMap m;
  m.origin_x = -0.5 * n * r;
  m.origin_y = -0.5 * n * r;
  m.resolution = r;
  m.width = m.height = n;
  return m;
}

TEST(SweptCells, AreExactlyTheCellsWithinTheHalfWidth) {
  const nav_core::GoodnessMap map = Geometry(60, 0.2);
  const Pose2 pose{0.13, -0.27, 0.7};
  for (double k : {-1.0, -0.09, 0.0, 0.5, 1.0}) {
    for (int dir : {1, -1}) {
      const ArcPath path{k, dir, 0.3, 3.0};
      std::vector<PathCell> cells;
      SweptCells(map, pose, path, 0.15, &cells);
      std::set<std::pair<int, int>> got;
      for (const auto& c : cells) EXPECT_TRUE(got.insert({c.i, c.j}).second) << "duplicate";
      std::set<std::pair<int, int>> want;
      for (int j = 0; j < map.height; ++j) {
        for (int i = 0; i < map.width; ++i) {
          const Eigen::Vector2d c = map.CellCenter(i, j);
          const double dx = c.x() - pose.x, dy = c.y() - pose.y;
          const Eigen::Vector2d p(std::cos(pose.yaw) * dx + std::sin(pose.yaw) * dy,
                                  -std::sin(pose.yaw) * dx + std::cos(pose.yaw) * dy);
          if (ProjectOntoArc(path, p).distance <= 0.15) want.insert({i, j});
        }
      }
      EXPECT_EQ(got, want) << "k " << k << " dir " << dir;
      EXPECT_GT(want.size(), 12u);
    }
  }
}

TEST(SweptCells, ReachOffTheMap) {
  const nav_core::GoodnessMap map = Geometry(10, 0.2);  // 2 m across
  std::vector<PathCell> cells;
  SweptCells(map, Pose2{}, ArcPath{0.0, 1, 0.3, 3.0}, 0.15, &cells);
  int outside = 0;
  for (const auto& c : cells) outside += map.Contains(c.i, c.j) ? 0 : 1;
  EXPECT_GT(outside, 0);
}

TEST(TurnCells, AreTheCellsAroundTheRoverCentre) {
  const nav_core::GoodnessMap map = Geometry(10, 0.2);
  std::vector<PathCell> cells;
  TurnCells(map, Pose2{0.0, 0.0, 1.0}, 0.15, &cells);
  EXPECT_EQ(cells.size(), 4u);  // the four cells meeting at the origin (centres 0.141 m away)
  TurnCells(map, Pose2{0.1, 0.1, 0.0}, 0.15, &cells);
  EXPECT_EQ(cells.size(), 1u);
}

TEST(PlanarPose, TakesHeadingFromTheProjectedXAxis) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = (Eigen::AngleAxisd(0.8, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  t.translation() = Eigen::Vector3d(1.0, 2.0, 3.0);
  const Pose2 p = PlanarPose(t);
  EXPECT_NEAR(p.yaw, 0.8, 1e-12);
  EXPECT_EQ(p.x, 1.0);
  EXPECT_EQ(p.y, 2.0);
}

}  // namespace
}  // namespace rover::apl::gestalt
