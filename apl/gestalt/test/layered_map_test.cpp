#include "rover/apl/gestalt/layered_map.hpp"

#include <gtest/gtest.h>

#include "rover/sim/terrain/random.hpp"

namespace rover::apl::gestalt {
namespace {

constexpr std::int16_t kAbsent = LayeredGoodness::kAbsent;

// A configuration-space obstacle: goodness 0 within `radius` cells of (ci, cj), 255 elsewhere.
Grid<std::int16_t> Blob(int n, int ci, int cj, int radius) {
  Grid<std::int16_t> g(n, n, 255);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      if ((i - ci) * (i - ci) + (j - cj) * (j - cj) <= radius * radius) g.at(i, j) = 0;
    }
  }
  return g;
}

TEST(LayeredGoodness, OneScanIntoAnEmptyMapIsTheScan) {
  sim::terrain::Rng rng(9);
  Grid<std::int16_t> fresh(40, 40, kAbsent);
  for (auto& v : fresh.cells()) {
    const double u = rng.Uniform();
    v = u < 0.3 ? kAbsent
                : (u < 0.4 ? std::int16_t{0} : static_cast<std::int16_t>(rng.UniformInt(256)));
  }
  LayeredGoodness map(40, 40, 7);
  map.Merge(fresh, Grid<std::uint8_t>(40, 40, 0));
  EXPECT_EQ(map.combined().cells(), fresh.cells());
  EXPECT_EQ(map.shrink_radius(0), 6);
  EXPECT_EQ(map.shrink_radius(6), 0);
}

// The rover saw a rock's blob whole, then (having turned) sees only cells on one side of it,
// which a partial rover disc now rates safe.
struct PartialView {
  Grid<std::int16_t> first = Blob(40, 20, 20, 6);
  Grid<std::int16_t> second;
  PartialView() : second(40, 40, kAbsent) {
    for (int j = 0; j < 40; ++j) {
      for (int i = 23; i < 40; ++i) second.at(i, j) = 255;
    }
  }
};

TEST(LayeredGoodness, AnObstacleThatLeftTheViewIsNotForgotten) {
  const PartialView v;
  const Grid<std::uint8_t> none(40, 40, 0);
  LayeredGoodness layered(40, 40, 7);
  layered.Merge(v.first, none);
  layered.Merge(v.second, none);
  LayeredGoodness single(40, 40, 1);
  single.Merge(v.first, none);
  single.Merge(v.second, none);
  // Cells of the blob the second view rated safe: a single map forgets them, the layers do not.
  for (int i : {23, 24, 26}) {
    EXPECT_EQ(single.combined().at(i, 20), 255) << i;
    EXPECT_EQ(layered.combined().at(i, 20), 0) << i;
  }
  // The core survives in layer 0 only as the rock itself.
  EXPECT_EQ(layered.layer(0).at(20, 20), 0);
  EXPECT_EQ(layered.layer(0).at(22, 20), 255);
  // Cells outside the old blob are the new view's.
  EXPECT_EQ(layered.combined().at(30, 20), 255);
  EXPECT_EQ(layered.combined().at(27, 20), 255);
}

TEST(LayeredGoodness, ConservativeCellsKeepTheMinimum) {
  Grid<std::int16_t> a(10, 10, 100), b(10, 10, 255);
  Grid<std::uint8_t> edge(10, 10, 0);
  edge.at(3, 3) = 1;
  LayeredGoodness map(10, 10, 1);
  map.Merge(a, edge);
  map.Merge(b, edge);
  EXPECT_EQ(map.combined().at(3, 3), 100);  // at the FOV edge: min(old, new)
  EXPECT_EQ(map.combined().at(4, 3), 255);  // elsewhere: new overrides old
  // A conservative cell with no old value takes the new one.
  LayeredGoodness fresh(10, 10, 1);
  fresh.Merge(b, edge);
  EXPECT_EQ(fresh.combined().at(3, 3), 255);
}

TEST(LayeredGoodness, ShiftAndForget) {
  LayeredGoodness map(20, 20, 3);
  map.Merge(Blob(20, 10, 10, 2), Grid<std::uint8_t>(20, 20, 0));
  map.Shift(2, 0);  // the grid's origin moved two cells along +x
  EXPECT_EQ(map.combined().at(8, 10), 0);
  EXPECT_EQ(map.combined().at(19, 10), kAbsent);
  Grid<std::uint8_t> forget(20, 20, 0);
  forget.at(8, 10) = 1;
  map.Forget(forget);
  EXPECT_EQ(map.combined().at(8, 10), kAbsent);
  for (int l = 0; l < 3; ++l) EXPECT_EQ(map.layer(l).at(8, 10), kAbsent);
  map.Clear();
  EXPECT_EQ(map.combined().at(9, 10), kAbsent);
}

}  // namespace
}  // namespace rover::apl::gestalt
