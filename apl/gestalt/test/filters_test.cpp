// The three filters on point sets sampled densely from known surfaces (terrain_map_test.cpp has
// the same scenes seen through a synthetic HAZCAM).
#include "rover/apl/gestalt/filters.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>

#include "rover/apl/gestalt/disc.hpp"

namespace rover::apl::gestalt {
namespace {

constexpr int kCells = 31;  // 6.2 m square grid of 0.2 m cells, centre cell (15, 15)
constexpr int kCentre = 15;

// Moments of a surface z = f(x, y) sampled on a regular s x s lattice in every cell; x, y are
// metres from the centre cell's centre. With sigma > 0 every height gets seeded Gaussian noise
// of that sigma; `model` says whether the points carry that noise variance (the stereo noise
// model) or claim to be exact.
Grid<Moments> SampleNoisy(const std::function<double(double, double)>& f, int s, double sigma,
                          bool model, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0.0, sigma > 0.0 ? sigma : 1.0);
  Grid<Moments> g(kCells, kCells);
  const double r = 0.2;
  for (int j = 0; j < kCells; ++j) {
    for (int i = 0; i < kCells; ++i) {
      for (int b = 0; b < s; ++b) {
        for (int a = 0; a < s; ++a) {
          const double x = (i - kCentre - 0.5 + (a + 0.5) / s) * r;
          const double y = (j - kCentre - 0.5 + (b + 0.5) / s) * r;
          const double z = f(x, y) + (sigma > 0.0 ? noise(rng) : 0.0);
          g.at(i, j).Add(Eigen::Vector3d(x, y, z), model ? sigma * sigma : 0.0);
        }
      }
    }
  }
  return g;
}

Grid<Moments> Sample(const std::function<double(double, double)>& f, int s = 8) {
  return SampleNoisy(f, s, 0.0, false, 0);
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
    const double slope = std::tan(deg * kDegree);
    const CellAssessment a = AssessCentre(Sample([&](double x, double) { return slope * x; }), o);
    ASSERT_EQ(a.status, AssessStatus::kAssessed) << deg;
    EXPECT_NEAR(a.tilt, deg * kDegree, 1e-6) << deg;
    EXPECT_NEAR(a.tilt_goodness, RampGoodness(deg * kDegree, o.tilt_safe, o.max_tilt), 1) << deg;
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
  const double s = std::tan(19.0 * kDegree);
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
  EXPECT_NEAR(belly.tilt, std::atan(0.5 * s), 0.5 * kDegree);  // the plane takes half the slope
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

// Noisy stereo at range (dl-stereo's HAZCAM heights scatter ~6 cm at 4 m, 4 points per cell):
// without the noise model the noise alone reads as a step obstacle; with it flat ground is
// safe, and a 0.3 m rock in the same noise is still an obstacle.
TEST(Filters, NoiseModelSeparatesStereoNoiseFromSteps) {
  const GestaltOptions o;
  const double sigma = 0.06;
  auto flat = [](double, double) { return 0.0; };
  auto rock = [](double x, double y) { return std::hypot(x - 0.4, y) < 0.2 ? 0.3 : 0.0; };
  int flat_exact_obstacles = 0;
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const CellAssessment exact = AssessCentre(SampleNoisy(flat, 2, sigma, false, seed), o);
    ASSERT_TRUE(exact.known());
    if (exact.step_goodness == 0) ++flat_exact_obstacles;
    const CellAssessment modelled = AssessCentre(SampleNoisy(flat, 2, sigma, true, seed), o);
    ASSERT_TRUE(modelled.known());
    EXPECT_GE(modelled.goodness, 200) << "seed " << seed << ": step " << modelled.step
                                      << " m, roughness " << modelled.roughness << " m";
    EXPECT_LE(modelled.roughness, o.roughness_safe) << "seed " << seed;
    const CellAssessment stone = AssessCentre(SampleNoisy(rock, 2, sigma, true, seed), o);
    EXPECT_EQ(stone.step_goodness, 0) << "seed " << seed << ": step " << stone.step << " m";
  }
  EXPECT_GE(flat_exact_obstacles, 4) << "noise alone must read as a step without the model";
}

// Exact data carries no noise variance: the model changes nothing (stereo_noise_coeff 0).
TEST(Filters, NoiseModelIsInertOnExactData) {
  auto bump = [](double x, double y) { return std::hypot(x, y) < 0.3 ? 0.15 : 0.02 * x; };
  const Grid<Moments> g = Sample(bump);
  GestaltOptions o;
  const CellAssessment a = AssessCentre(g, o);
  o.step_noise_sigmas = 5.0;
  const CellAssessment b = AssessCentre(g, o);
  EXPECT_EQ(a.goodness, b.goodness);
  EXPECT_FLOAT_EQ(a.step, b.step);
  EXPECT_FLOAT_EQ(a.roughness, b.roughness);
}

}  // namespace
}  // namespace rover::apl::gestalt
