// The three filters on point sets sampled densely from known surfaces (terrain_map_test.cpp has
// the same scenes seen through a synthetic HAZCAM).
#include "rover/apl/gestalt/filters.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>

#include "rover/apl/gestalt/disc.hpp"

namespace rover::apl::gestalt {
namespace {

constexpr int kCells = 31;  // 6.2 m square grid of 0.2 m cells, centre cell (15, 15)
constexpr int kCentre = 15;

// Moments of a surface z = f(x, y) sampled on a regular s x s lattice in every cell; x, y are
// metres from the centre cell's centre.
Grid<Moments> Sample(const std::function<double(double, double)>& f, int s = 8) {
  Grid<Moments> g(kCells, kCells);
  const double r = 0.2;
  for (int j = 0; j < kCells; ++j) {
    for (int i = 0; i < kCells; ++i) {
      for (int b = 0; b < s; ++b) {
        for (int a = 0; a < s; ++a) {
          const double x = (i - kCentre - 0.5 + (a + 0.5) / s) * r;
          const double y = (j - kCentre - 0.5 + (b + 0.5) / s) * r;
          g.at(i, j).Add(x, y, f(x, y));
        }
      }
    }
  }
  return g;
}

CellAssessment AssessCentre(const Grid<Moments>& g, const GestaltOptions& o) {
  const DiscAssessor assessor(o);
  Grid<CellStats> stats(g.width(), g.height());
  Grid<int> covered(g.width(), g.height(), 0);
  for (std::size_t k = 0; k < g.size(); ++k) {
    stats[k] = StatsOf(g[k], o.min_cell_points);
    covered[k] = stats[k].covered ? 1 : 0;
  }
  RowPrefix<Moments> sums;
  sums.Build(g);
  RowPrefix<int> counts;
  counts.Build(covered);
  return assessor.Assess(kCentre, kCentre, sums.DiscSum(kCentre, kCentre, assessor.rover_disc()),
                         counts.DiscSum(kCentre, kCentre, assessor.rover_disc()), stats);
}

TEST(RampGoodness, LinearFromSafeToLimit) {
  EXPECT_EQ(RampGoodness(0.0, 0.1, 0.3), 255);
  EXPECT_EQ(RampGoodness(0.1, 0.1, 0.3), 255);
  EXPECT_EQ(RampGoodness(0.15, 0.1, 0.3), 191);  // 191.25
  EXPECT_EQ(RampGoodness(0.19, 0.1, 0.3), 140);  // 140.25
  EXPECT_EQ(RampGoodness(0.25, 0.1, 0.3), 64);   // 63.75
  EXPECT_EQ(RampGoodness(0.3, 0.1, 0.3), 0);
  EXPECT_EQ(RampGoodness(9.0, 0.1, 0.3), 0);
  EXPECT_EQ(RampGoodness(std::numeric_limits<double>::infinity(), 0.1, 0.3), 0);
}

TEST(TiltFilter, FollowsItsRampOverSlopes) {
  const GestaltOptions o;
  for (double deg : {0.0, 3.0, 5.0, 8.0, 12.5, 17.0, 20.0, 26.0}) {
    const double slope = std::tan(deg * kDeg);
    const CellAssessment a = AssessCentre(Sample([&](double x, double) { return slope * x; }), o);
    ASSERT_EQ(a.status, AssessStatus::kAssessed) << deg;
    EXPECT_NEAR(a.tilt, deg * kDeg, 1e-6) << deg;
    EXPECT_NEAR(a.tilt_goodness, RampGoodness(deg * kDeg, o.tilt_safe, o.max_tilt), 1) << deg;
    // A uniform slope is neither rough nor a step.
    EXPECT_NEAR(a.roughness, 0.0, 1e-6);
    EXPECT_NEAR(a.step, 0.0, 1e-6);
    EXPECT_EQ(a.goodness, a.tilt_goodness);
  }
}

TEST(RoughnessFilter, FollowsItsRampOverResiduals) {
  const GestaltOptions o;
  for (double r : {0.0, 0.02, 0.03, 0.05, 0.07, 0.1}) {
    // A checkerboard of +-r at the sample lattice: RMS residual r about the horizontal plane.
    auto f = [&](double x, double y) {
      const long a = std::lround(std::floor(x / 0.025)), b = std::lround(std::floor(y / 0.025));
      return ((a + b) % 2 == 0) ? r : -r;
    };
    GestaltOptions no_step = o;
    no_step.max_step = 10.0;  // isolate the roughness filter
    const CellAssessment a = AssessCentre(Sample(f), no_step);
    ASSERT_EQ(a.status, AssessStatus::kAssessed) << r;
    EXPECT_NEAR(a.roughness, r, 1e-3) << r;
    EXPECT_NEAR(a.roughness_goodness, RampGoodness(r, o.roughness_safe, o.max_roughness), 1) << r;
  }
}

TEST(StepFilter, FollowsItsRampOverStepHeights) {
  GestaltOptions o;
  o.step_sigma_k = 0.0;
  for (double h : {0.03, 0.0667, 0.1, 0.15, 0.2, 0.3}) {
    // Flat ground with one raised cell (a flat-topped block) next to the centre.
    auto f = [&](double x, double y) {
      return (x > 0.1 && x < 0.3 && std::abs(y) < 0.1) ? h : 0.0;
    };
    GestaltOptions no_rough = o;
    no_rough.max_roughness = 10.0;  // isolate the step filter
    no_rough.roughness_safe = 5.0;
    const CellAssessment a = AssessCentre(Sample(f), no_rough);
    ASSERT_EQ(a.status, AssessStatus::kAssessed) << h;
    // The plane sits a little above the ground (the block lifts it): the step is the block's
    // height relative to it less that tilt, within a few millimetres.
    EXPECT_NEAR(a.step, h, 0.01 * h + 1e-3) << h;
    EXPECT_NEAR(a.step_goodness, RampGoodness(h, o.step_safe, o.max_step), 6) << h;
  }
}

TEST(StepFilter, TallThinRocksCountThroughTheCellSpread) {
  // A 0.45 m post 8 cm square in one cell (16 % of it): it barely moves the cell's mean
  // elevation, 0.07 m, but spreads its heights by 0.17 m.
  auto post = [](double x, double y) {
    return (std::abs(x - 0.2) < 0.04 && std::abs(y) < 0.04) ? 0.45 : 0.0;
  };
  GestaltOptions mean_only;
  mean_only.step_sigma_k = 0.0;
  const CellAssessment blind = AssessCentre(Sample(post, 10), mean_only);
  EXPECT_LT(blind.step, 0.08);  // 16 % of 0.45 m
  EXPECT_GT(blind.step_goodness, 200);
  const CellAssessment seen = AssessCentre(Sample(post, 10), GestaltOptions{});  // k = 1
  EXPECT_GT(seen.step, 0.2);
  EXPECT_EQ(seen.step_goodness, 0);
  EXPECT_EQ(seen.goodness, 0);
}

TEST(StepFilter, PitchersMoundIsClimbableWithTheBellyDisc) {
  // A flat-to-hill transition through the centre: z = s max(0, x) with a 19 deg slope. Across
  // the 2.6 m rover disc the ground bends by more than a rock would stand, but never under a
  // belly-sized disc.
  const double s = std::tan(19.0 * kDeg);
  auto mound = [s](double x, double) { return s * std::max(0.0, x); };
  GestaltOptions whole_disc;  // MER's first flight software: steps anywhere in the rover disc
  whole_disc.step_disc_diameter = whole_disc.rover_disc_diameter;
  const CellAssessment old_way = AssessCentre(Sample(mound), whole_disc);
  const CellAssessment belly = AssessCentre(Sample(mound), GestaltOptions{});
  ASSERT_EQ(old_way.status, AssessStatus::kAssessed);
  ASSERT_EQ(belly.status, AssessStatus::kAssessed);
  EXPECT_GT(old_way.step, 0.2);
  EXPECT_EQ(old_way.step_goodness, 0);
  // Relative to the disc's plane (half the slope) a belly disc on the hillside still spans
  // 0.8 m of residual slope, 0.14 m: rough going, but no step.
  EXPECT_LT(belly.step, 0.17);
  EXPECT_GT(belly.step_goodness, 60);
  EXPECT_NEAR(belly.tilt, std::atan(0.5 * s), 0.5 * kDeg);  // the plane takes half the slope
}

TEST(DiscAssessor, TooLittleCoverageIsUnknown) {
  const GestaltOptions o;
  Grid<Moments> g = Sample([](double, double) { return 0.0; });
  // Keep only the cells with i >= centre + 1: under half of the disc.
  for (int j = 0; j < kCells; ++j) {
    for (int i = 0; i <= kCentre; ++i) g.at(i, j) = Moments{};
  }
  const CellAssessment a = AssessCentre(g, o);
  EXPECT_EQ(a.status, AssessStatus::kUnknown);
  EXPECT_LT(a.coverage, 0.5);
  EXPECT_FALSE(a.known());
}

TEST(DiscAssessor, ChaoticPointsAreNotAPlane) {
  // Spikes of +-0.5 m everywhere: no plane, and far above the roughness limit: an obstacle.
  auto spikes = [](double x, double y) {
    return std::sin(97.0 * x) * std::cos(83.0 * y) > 0.0 ? 3.0 : -3.0;
  };
  const CellAssessment a = AssessCentre(Sample(spikes), GestaltOptions{});
  EXPECT_EQ(a.status, AssessStatus::kNotPlanar);
  EXPECT_EQ(a.goodness, 0);
  EXPECT_TRUE(a.known());
}

}  // namespace
}  // namespace rover::apl::gestalt
