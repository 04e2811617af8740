// A* against Dijkstra (and Dijkstra against plain relaxation) on small seeded maps.
#include "rover/apl/roaman/astar.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "scenes.hpp"

namespace rover::apl::roaman {
namespace {

// A small planning grid (cell 0.1 m, 3 m x 3 m) with random rocks; clearance as computed.
PlanningGrid RandomGrid(std::uint32_t seed) {
  std::mt19937 rng(seed);
  TraversabilityMap t = testing::ClassMap(-2, -2, 5, 2, 0.1, CellClass::kSafe);
  for (int k = 0; k < 6; ++k) {
    const Eigen::Vector2d c(std::uniform_real_distribution<double>(0.0, 3.0)(rng),
                            std::uniform_real_distribution<double>(-1.5, 1.5)(rng));
    testing::Paint(&t, c, c, std::uniform_real_distribution<double>(0.05, 0.3)(rng),
                   CellClass::kStep);
  }
  RoamanOptions o;
  o.cell_size = 0.1;
  o.normal_window = 0.3;
  o.plan_width = 3.0;
  o.plan_back = 0.0;
  o.start_clear_radius = 0.0;
  return BuildPlanningGrid(t, {0.0, 0.0}, {3.0, 0.0}, 3.0, o);
}

// Bellman-Ford style relaxation to a fixed point: the brute-force reference for Dijkstra.
double BruteForceCost(const PlanningGrid& g, Eigen::Vector2i a, Eigen::Vector2i b,
                      const SearchCost& c) {
  const double inf = std::numeric_limits<double>::infinity();
  Layer<double> d(g.width, g.height, inf);
  d.at(a.x(), a.y()) = 0.0;
  const auto in = [&](int i, int j) {
    return g.Contains(i, j) && g.clearance.at(i, j) >= c.min_clearance;
  };
  const auto pen = [&](int i, int j) {
    return std::max(0.0, 1.0 - g.clearance.at(i, j) / c.clearance_ref);
  };
  bool changed = true;
  while (changed) {
    changed = false;
    for (int j = 0; j < g.height; ++j) {
      for (int i = 0; i < g.width; ++i) {
        if (!in(i, j) || d.at(i, j) == inf) continue;
        for (int dj = -1; dj <= 1; ++dj) {
          for (int di = -1; di <= 1; ++di) {
            if ((di == 0 && dj == 0) || !in(i + di, j + dj)) continue;
            if (di != 0 && dj != 0 && (!in(i + di, j) || !in(i, j + dj))) continue;
            const double step = g.cell * std::hypot(di, dj);
            const double v = d.at(i, j) + step * (1.0 + c.clearance_weight * 0.5 *
                                                            (pen(i, j) + pen(i + di, j + dj)));
            if (v < d.at(i + di, j + dj) - 1e-12) {
              d.at(i + di, j + dj) = v;
              changed = true;
            }
          }
        }
      }
    }
  }
  return d.at(b.x(), b.y());
}

TEST(AStar, IsOptimalOnSmallMapsAgainstDijkstraAndBruteForce) {
  int compared = 0, unreachable = 0;
  for (std::uint32_t seed = 1; seed <= 12; ++seed) {
    const PlanningGrid g = RandomGrid(seed);
    std::mt19937 rng(seed * 7);
    const SearchCost cost{0.15, 1.0, 0.6};
    for (int pair = 0; pair < 4; ++pair) {
      Eigen::Vector2i a, b;
      int tries = 0;
      do {
        a = {static_cast<int>(rng() % g.width), static_cast<int>(rng() % g.height)};
        b = {static_cast<int>(rng() % g.width), static_cast<int>(rng() % g.height)};
      } while ((g.clearance.at(a.x(), a.y()) < cost.min_clearance ||
                g.clearance.at(b.x(), b.y()) < cost.min_clearance) &&
               ++tries < 1000);
      const auto astar = AStarSearch(g, a, b, cost);
      const auto dijkstra = DijkstraSearch(g, a, b, cost);
      const double brute = BruteForceCost(g, a, b, cost);
      ASSERT_EQ(astar.ok(), dijkstra.ok());
      if (!astar.ok()) {
        EXPECT_TRUE(std::isinf(brute));
        EXPECT_EQ(astar.status().code(), StatusCode::kNotFound);
        ++unreachable;
        continue;
      }
      EXPECT_NEAR(astar->cost, dijkstra->cost, 1e-9) << "seed " << seed;
      EXPECT_NEAR(dijkstra->cost, brute, 1e-9) << "seed " << seed;
      EXPECT_LE(astar->expanded, dijkstra->expanded);
      // A connected path of graph cells from a to b whose costs add up.
      ASSERT_EQ(astar->cells.front(), a);
      ASSERT_EQ(astar->cells.back(), b);
      double length = 0.0;
      for (std::size_t k = 1; k < astar->cells.size(); ++k) {
        const Eigen::Vector2i d = astar->cells[k] - astar->cells[k - 1];
        EXPECT_LE(d.cwiseAbs().maxCoeff(), 1);
        EXPECT_GE(g.clearance.at(astar->cells[k].x(), astar->cells[k].y()), cost.min_clearance);
        length += g.cell * d.cast<double>().norm();
      }
      EXPECT_NEAR(astar->length, length, 1e-9);
      ++compared;
    }
  }
  EXPECT_GT(compared, 30);
  (void)unreachable;
}

TEST(AStar, TheClearanceTermKeepsPathsAwayFromHazards) {
  // A rock beside the direct line: the shortest path passes as close as the graph allows, the
  // weighted one swings away from it.
  TraversabilityMap t = testing::ClassMap(-2, -2, 8, 2, 0.05, CellClass::kSafe);
  testing::Paint(&t, {2.5, 0.6}, {2.5, 0.6}, 0.2, CellClass::kStep);
  RoamanOptions o;
  const PlanningGrid g = BuildPlanningGrid(t, {0.0, 0.0}, {5.0, 0.0}, 6.0, o);
  int si = 0, sj = 0, gi = 0, gj = 0;
  g.CellOf({0.0, 0.0}, &si, &sj);
  g.CellOf({5.0, 0.0}, &gi, &gj);
  const SearchCost shortest{0.5, 0.0, 2.0}, weighted{0.5, 3.0, 2.0};
  auto a = AStarSearch(g, {si, sj}, {gi, gj}, shortest);
  auto b = AStarSearch(g, {si, sj}, {gi, gj}, weighted);
  ASSERT_TRUE(a.ok() && b.ok());
  double min_a = 1e9, min_b = 1e9;
  for (const auto& c : a->cells) min_a = std::min<double>(min_a, g.clearance.at(c.x(), c.y()));
  for (const auto& c : b->cells) min_b = std::min<double>(min_b, g.clearance.at(c.x(), c.y()));
  EXPECT_GT(min_b, min_a + 0.1);
  EXPECT_GT(b->length, a->length);
}

TEST(AStar, BadCellsAndReachability) {
  TraversabilityMap t = testing::ClassMap(-2, -2, 8, 2, 0.05, CellClass::kSafe);
  testing::Paint(&t, {3.0, -3.0}, {3.0, 3.0}, 0.1, CellClass::kStep);  // a wall across
  const PlanningGrid g = BuildPlanningGrid(t, {0.0, 0.0}, {5.0, 0.0}, 6.0, RoamanOptions{});
  int si = 0, sj = 0, gi = 0, gj = 0;
  g.CellOf({0.0, 0.0}, &si, &sj);
  g.CellOf({5.0, 0.0}, &gi, &gj);
  const SearchCost c{0.9, 1.0, 2.0};
  auto r = AStarSearch(g, {si, sj}, {gi, gj}, c);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kNotFound);
  EXPECT_EQ(AStarSearch(g, {-1, 0}, {gi, gj}, c).status().code(), StatusCode::kInvalidArgument);
  int wi = 0, wj = 0;
  g.CellOf({3.0, 0.0}, &wi, &wj);
  EXPECT_NE(AStarSearch(g, {wi, wj}, {gi, gj}, c).status().message().find("has clearance 0 m"),
            std::string::npos);
  const Layer<std::uint8_t> reach = ReachableCells(g, {si, sj}, 0.9);
  EXPECT_EQ(reach.at(si, sj), 1);
  EXPECT_EQ(reach.at(gi, gj), 0);
  EXPECT_EQ(ReachableCells(g, {wi, wj}, 0.9).at(wi, wj), 0);
}

TEST(AStar, PullStringMakesStraightLegs) {
  const TraversabilityMap open = testing::ClassMap(-2, -3, 8, 3, 0.05, CellClass::kSafe);
  const PlanningGrid g = BuildPlanningGrid(open, {0.0, 0.0}, {5.0, 0.0}, 6.0, RoamanOptions{});
  std::vector<Eigen::Vector2d> stairs;
  for (int k = 0; k <= 40; ++k) stairs.emplace_back(0.1 * k, 0.05 * (k % 2));  // grid stairs
  const auto pulled = PullString(g, stairs, RoamanOptions{}.footprint());
  ASSERT_EQ(pulled.size(), 2u);
  EXPECT_NEAR(PolylineLength(pulled), 4.0, 1e-9);
  TraversabilityMap rock = open;
  testing::Paint(&rock, {2.0, 1.0}, {2.0, 1.0}, 0.5, CellClass::kStep);
  const PlanningGrid r = BuildPlanningGrid(rock, {0.0, 0.0}, {5.0, 0.0}, 6.0, RoamanOptions{});
  std::vector<Eigen::Vector2d> around;
  for (int k = 0; k <= 20; ++k) around.emplace_back(0.1 * k, 1.0 - 0.1 * k);         // down
  for (int k = 1; k <= 20; ++k) around.emplace_back(2.0 + 0.1 * k, -1.0 + 0.1 * k);  // up
  const auto w = PullString(r, around, RoamanOptions{}.footprint());
  EXPECT_GE(w.size(), 3u);
  for (std::size_t k = 1; k < w.size(); ++k) EXPECT_TRUE(r.SegmentClear(w[k - 1], w[k], 0.58));
  EXPECT_TRUE(PullString(g, {}, RoamanOptions{}.footprint()).empty());
}

}  // namespace
}  // namespace rover::apl::roaman
