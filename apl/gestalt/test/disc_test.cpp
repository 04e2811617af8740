// Discs, row prefix sums and disc filters against brute force; Grid::Shift (grid.hpp is
// header-only and used by every part of the map, so its scrolling is tested here).
#include "rover/apl/gestalt/disc.hpp"

#include <gtest/gtest.h>

#include <algorithm>

#include "rover/apl/gestalt/moments.hpp"
#include "rover/sim/terrain/random.hpp"

namespace rover::apl::gestalt {
namespace {

TEST(DiscSpans, MersRoverDiscHas137Cells) {
  const DiscSpans d(6.5);  // 2.6 m at 0.2 m cells
  EXPECT_EQ(d.radius(), 6);
  EXPECT_EQ(d.half_width(0), 6);
  EXPECT_EQ(d.half_width(6), 2);  // 6^2 + 2^2 = 40 <= 42.25 < 6^2 + 3^2
  int brute = 0;
  for (int dy = -7; dy <= 7; ++dy) {
    for (int dx = -7; dx <= 7; ++dx) {
      const bool in = dx * dx + dy * dy <= 42.25;
      brute += in ? 1 : 0;
      EXPECT_EQ(d.Contains(dx, dy), in) << dx << "," << dy;
    }
  }
  EXPECT_EQ(d.cell_count(), brute);
  EXPECT_EQ(d.cell_count(), 137);
  EXPECT_EQ(DiscSpans(0.0).cell_count(), 1);
  EXPECT_EQ(DiscSpans(2.0).cell_count(), 13);  // exact radius: (0, 2) inside
}

Grid<double> RandomGrid(int w, int h, std::uint64_t seed) {
  sim::terrain::Rng rng(seed);
  Grid<double> g(w, h);
  for (auto& v : g.cells()) v = rng.Uniform(-1.0, 1.0);
  return g;
}

TEST(RowPrefix, DiscSumsEqualBruteForceIncludingAtTheBorder) {
  const Grid<double> g = RandomGrid(23, 17, 3);
  RowPrefix<double> p;
  p.Build(g);
  for (double r : {0.0, 1.0, 2.5, 6.5}) {
    const DiscSpans d(r);
    for (int j = 0; j < g.height(); ++j) {
      for (int i = 0; i < g.width(); ++i) {
        double brute = 0.0;
        for (int dy = -d.radius(); dy <= d.radius(); ++dy) {
          for (int dx = -d.radius(); dx <= d.radius(); ++dx) {
            if (d.Contains(dx, dy) && g.Contains(i + dx, j + dy)) brute += g.at(i + dx, j + dy);
          }
        }
        EXPECT_NEAR(p.DiscSum(i, j, d), brute, 1e-12) << "r " << r << " at " << i << "," << j;
      }
    }
  }
}

TEST(RowPrefix, SumsMoments) {
  Grid<Moments> g(5, 5);
  g.at(1, 1).Add(1, 2, 3);
  g.at(4, 4).Add(0, 0, 1);
  RowPrefix<Moments> p;
  p.Build(g);
  const Moments s = p.DiscSum(2, 2, DiscSpans(1.5));
  EXPECT_EQ(s.n, 1.0);  // (1, 1) is in the disc, (4, 4) is not
  EXPECT_EQ(s.sz, 3.0);
  EXPECT_EQ(p.DiscSum(2, 2, DiscSpans(3.0)).n, 2.0);
}

Grid<std::int16_t> RandomGoodness(int w, int h, std::uint64_t seed) {
  sim::terrain::Rng rng(seed);
  Grid<std::int16_t> g(w, h);
  for (auto& v : g.cells()) {
    v = rng.Uniform() < 0.2 ? std::int16_t{-1} : static_cast<std::int16_t>(rng.UniformInt(256));
  }
  return g;
}

TEST(DiscFilters, MaxAndMinEqualBruteForceSkippingAbsentCells) {
  const Grid<std::int16_t> g = RandomGoodness(31, 19, 11);
  for (double r : {0.0, 1.0, 3.0, 6.0}) {
    const DiscSpans d(r);
    Grid<std::int16_t> mx, mn;
    DiscMax(g, d, -1, &mx);
    DiscMin(g, d, -1, &mn);
    for (int j = 0; j < g.height(); ++j) {
      for (int i = 0; i < g.width(); ++i) {
        int bmax = -1, bmin = 1000;
        for (int dy = -d.radius(); dy <= d.radius(); ++dy) {
          for (int dx = -d.radius(); dx <= d.radius(); ++dx) {
            if (!d.Contains(dx, dy) || !g.Contains(i + dx, j + dy)) continue;
            const int v = g.at(i + dx, j + dy);
            if (v < 0) continue;
            bmax = std::max(bmax, v);
            bmin = std::min(bmin, v);
          }
        }
        EXPECT_EQ(mx.at(i, j), bmax) << "r " << r << " at " << i << "," << j;
        EXPECT_EQ(mn.at(i, j), bmin == 1000 ? -1 : bmin) << "r " << r << " at " << i << "," << j;
      }
    }
  }
}

TEST(DilateMask, MarksEveryCellWithinTheDisc) {
  Grid<std::uint8_t> m(15, 15, 0);
  m.at(7, 7) = 1;
  Grid<std::uint8_t> out;
  DilateMask(m, DiscSpans(3.0), &out);
  int n = 0;
  for (std::uint8_t v : out.cells()) n += v;
  EXPECT_EQ(n, DiscSpans(3.0).cell_count());
  EXPECT_EQ(out.at(10, 7), 1);
  EXPECT_EQ(out.at(10, 9), 0);  // 9 + 4 > 9
}

TEST(Grid, ShiftScrollsAndFillsWhatMovesIn) {
  Grid<int> g(4, 3);
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 4; ++i) g.at(i, j) = 10 * j + i;
  }
  Grid<int> a = g;
  a.Shift(1, 0, -1);  // origin moved one cell along +x: cell i holds old i + 1
  EXPECT_EQ(a.at(0, 0), 1);
  EXPECT_EQ(a.at(2, 2), 23);
  EXPECT_EQ(a.at(3, 1), -1);
  Grid<int> b = g;
  b.Shift(-1, 2, -1);
  EXPECT_EQ(b.at(1, 0), 20);
  EXPECT_EQ(b.at(0, 0), -1);
  EXPECT_EQ(b.at(1, 1), -1);
  Grid<int> c = g;
  c.Shift(5, 0, 7);
  EXPECT_EQ(c.at(0, 0), 7);
  Grid<int> d = g;
  d.Shift(0, 0, 7);
  EXPECT_EQ(d.cells(), g.cells());
}

}  // namespace
}  // namespace rover::apl::gestalt
