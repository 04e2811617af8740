#include "rover/apl/enav/height_terrain.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "scene.hpp"

namespace rover::apl::enav {
namespace {

using testing::Block;
using testing::Blocks;
using testing::ScanOf;
using testing::TestOptions;

TEST(SquaredDistanceTransform, MatchesBruteForce) {
  std::mt19937 rng(7);
  const int w = 23, h = 17;
  std::vector<std::uint8_t> mask(w * h, 0);
  for (int n = 0; n < 9; ++n) mask[rng() % mask.size()] = 1;
  const std::vector<float> d = SquaredDistanceTransform(mask, w, h);
  for (int j = 0; j < h; ++j) {
    for (int i = 0; i < w; ++i) {
      float best = std::numeric_limits<float>::infinity();
      for (int q = 0; q < h; ++q) {
        for (int p = 0; p < w; ++p) {
          if (mask[q * w + p]) best = std::min(best, float((p - i) * (p - i) + (q - j) * (q - j)));
        }
      }
      EXPECT_FLOAT_EQ(d[j * w + i], best) << i << ", " << j;
    }
  }
  EXPECT_TRUE(std::isinf(SquaredDistanceTransform(std::vector<std::uint8_t>(6, 0), 3, 2)[4]));
}

TEST(HeightTerrain, ClassifiesStepsByThePartsTheyReach) {
  auto t = HeightTerrain::Create(TestOptions());
  ASSERT_TRUE(t.ok());
  // 0.1 m pebble, 0.25 m rock (wheel), 0.29 m (rocker: 0.332 - 0.05 = 0.282), 0.5 m (body).
  const auto f = Blocks({{1.0, 1.0, 0.15, 0.10}, {1.0, -1.0, 0.15, 0.25},
                         {-1.0, 1.0, 0.15, 0.29}, {-1.0, -1.0, 0.15, 0.50}});
  auto stats = t->Update(ScanOf(f, -3, 3, -3, 3));
  ASSERT_TRUE(stats.ok()) << stats.status().message();
  EXPECT_GT(stats->cells_assessed, 3000);
  const nav_core::HeightMap& m = *t->height_map();
  auto bits = [&](double x, double y) {
    int i = 0, j = 0;
    m.CellOf(x, y, &i, &j);
    return m.hazard[m.Index(i, j)];
  };
  EXPECT_EQ(bits(1.0, 1.0), 0);
  EXPECT_EQ(bits(1.0, -1.0), nav_core::kHazardWheel);
  EXPECT_EQ(bits(-1.0, 1.0), nav_core::kHazardWheel | nav_core::kHazardRocker);
  EXPECT_EQ(bits(-1.0, -1.0),
            nav_core::kHazardWheel | nav_core::kHazardRocker | nav_core::kHazardBody);
  EXPECT_EQ(bits(0.0, 0.0), 0);
  // Distances between cell centres: the nearest block cells are centred 0.85-0.95 m out.
  EXPECT_NEAR(t->DistanceAt(HazardLayer::kWheel, {0.0, 0.0}), std::hypot(0.9, 0.9), 0.1);
  EXPECT_NEAR(t->DistanceAt(HazardLayer::kBody, {-1.0, 1.0}), 1.9, 0.11);
  EXPECT_FLOAT_EQ(t->DistanceAt(HazardLayer::kWheel, {1.0, -1.0}), 0.0F);
  // The goodness map: known, zero on the tall block, perfect far from rocks.
  const nav_core::CellValue far = t->GoodnessAt({2.8, 0.0});
  EXPECT_TRUE(far.known());
  EXPECT_EQ(far.goodness, 255);
  EXPECT_EQ(t->GoodnessAt({-1.0, -1.0}).goodness, 0);
  EXPECT_FALSE(t->GoodnessAt({6.0, 0.0}).known());
}

TEST(HeightTerrain, NoisyFarStepsAreNotHazardsUntilSeenClose) {
  EnavOptions o = TestOptions();
  o.stereo_noise_coeff = 0.01;  // sigma 0.16 m at 4 m
  auto t = HeightTerrain::Create(o);
  ASSERT_TRUE(t.ok());
  const auto f = Blocks({{4.0, 0.0, 0.15, 0.25}});
  ASSERT_TRUE(t->Update(ScanOf(f, 3, 4.5, -1, 1)).ok());
  EXPECT_GT(t->DistanceAt(HazardLayer::kWheel, {4.0, 0.0}), 1.0);
  // Seen again from 1 m away: the closer data replace the far ones and the rock appears.
  Eigen::Isometry3d near = Eigen::Isometry3d::Identity();
  near.translation() = Eigen::Vector3d(3.0, 0.0, 0.0);
  ASSERT_TRUE(t->Update(ScanOf(f, 3, 4.5, -1, 1, 0.03, near)).ok());
  EXPECT_FLOAT_EQ(t->DistanceAt(HazardLayer::kWheel, {4.0, 0.0}), 0.0F);
}

// A rock whose far side the scan did not reach: with shadow_reach its hazard grows into the
// unseen cells beside it (up to the reach), never into seen flat ground; without, it stops
// where the data stop.
TEST(HeightTerrain, WithShadowReachAHazardGrowsIntoTheUnseenBesideIt) {
  const auto f = Blocks({{0.9, 0.0, 0.15, 0.25}});  // x 0.75-1.05; the scan ends at x = 1
  for (const double reach : {0.0, 0.3}) {
    EnavOptions o = TestOptions();
    o.shadow_reach = reach;
    auto t = HeightTerrain::Create(o);
    ASSERT_TRUE(t.ok());
    ASSERT_TRUE(t->Update(ScanOf(f, -3, 1.0, -2, 2)).ok());
    const nav_core::HeightMap& m = *t->height_map();
    auto wheel = [&](double x, double y) {
      int i = 0, j = 0;
      m.CellOf(x, y, &i, &j);
      return (m.hazard[m.Index(i, j)] & nav_core::kHazardWheel) != 0;
    };
    EXPECT_TRUE(wheel(0.85, 0.0));
    EXPECT_EQ(wheel(1.15, 0.0), reach > 0.0) << reach;  // unseen, 0.1 m past the rock's cells
    EXPECT_EQ(wheel(1.25, 0.0), reach > 0.0) << reach;
    EXPECT_FALSE(wheel(1.45, 0.0)) << reach;  // beyond the reach
    EXPECT_FALSE(wheel(0.85, 0.45)) << reach;  // seen flat ground beside the rock
    EXPECT_FALSE(wheel(0.5, 0.0)) << reach;
  }
  EnavOptions bad = TestOptions();
  bad.shadow_reach = -0.1;
  EXPECT_FALSE(bad.Validate().ok());
}

TEST(HeightTerrain, AStereoHoleBelowTheGroundDoesNotMakeTheFlatAroundItSteps) {
  // Flat ground with a 0.2 m square "hole" 0.2 m deep 2 m ahead, as a stereo mismatch ranged
  // too far gives it (dl-stereo's HAZCAM images hold such holes at 1.5-3 m), and a real 0.25 m
  // rock 1.5 m to its left.
  const testing::HeightFn f = [](double x, double y) {
    if (std::abs(x - 2.0) <= 0.1 && std::abs(y) <= 0.1) return -0.2;
    return std::abs(x - 2.0) <= 0.15 && std::abs(y - 1.5) <= 0.15 ? 0.25 : 0.0;
  };
  auto wheel_hazard = [&](const EnavOptions& o, double x, double y) {
    auto t = HeightTerrain::Create(o);
    EXPECT_TRUE(t.ok());
    EXPECT_TRUE(t->Update(ScanOf(f, -3, 3, -3, 3)).ok());
    const nav_core::HeightMap& m = *t->height_map();
    int i = 0, j = 0;
    m.CellOf(x, y, &i, &j);
    return (m.hazard[m.Index(i, j)] & nav_core::kHazardWheel) != 0;
  };
  const EnavOptions o = TestOptions();
  EXPECT_FALSE(wheel_hazard(o, 2.35, 0.0));  // flat, 0.25 m beyond the hole
  EXPECT_FALSE(wheel_hazard(o, 1.75, 0.25));
  EXPECT_FALSE(wheel_hazard(o, 2.0, 0.0));   // the hole itself
  EXPECT_TRUE(wheel_hazard(o, 2.0, 1.5));    // the rock
  // With the minimum as the ground (ground_quantile 0) the flat around the hole reads 0.2 m.
  EnavOptions lowest = o;
  lowest.ground_quantile = 0.0;
  EXPECT_TRUE(wheel_hazard(lowest, 2.35, 0.0));
  EXPECT_TRUE(wheel_hazard(lowest, 2.0, 1.5));
}

TEST(HeightTerrain, RemembersAsItScrollsAndForgetsWhatFallsOff) {
  auto t = HeightTerrain::Create(TestOptions());  // 16 m map, recentres beyond 2 m
  ASSERT_TRUE(t.ok());
  ASSERT_TRUE(t->Update(ScanOf(Blocks({{1.0, 0.0, 0.15, 0.3}}), 0, 2, -1, 1)).ok());
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(5.0, 0.0, 0.0);
  t->Follow(pose);  // scrolls by 5 m: the rock 4 m behind is still there
  EXPECT_FLOAT_EQ(t->DistanceAt(HazardLayer::kWheel, {1.0, 0.0}), 0.0F);
  EXPECT_GT(t->height_map()->origin_x, -8.0 + 4.9);
  pose.translation() = Eigen::Vector3d(14.0, 0.0, 0.0);
  t->Follow(pose);  // 13 m on: off the map
  EXPECT_TRUE(std::isinf(t->DistanceAt(HazardLayer::kWheel, {1.0, 0.0})));
}

TEST(HeightTerrain, MalformedScanIsRejectedAndChangesNothing) {
  auto t = HeightTerrain::Create(TestOptions());
  ASSERT_TRUE(t.ok());
  nav_core::RangeScan s = ScanOf(Blocks({}), 0, 1, 0, 1);
  s.valid.pop_back();
  const std::uint64_t rev = t->height_map()->revision;
  auto r = t->Update(s);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("RangeScan.valid"), std::string::npos);
  EXPECT_EQ(t->height_map()->revision, rev);
  // NaN points marked valid are skipped, not merged.
  nav_core::RangeScan n = ScanOf(Blocks({}), 0, 0.5, 0, 0.5);
  n.xyz[2] = std::numeric_limits<float>::quiet_NaN();
  auto ok = t->Update(n);
  ASSERT_TRUE(ok.ok());
  EXPECT_EQ(ok->points_used, ok->points_total - 1);
}

}  // namespace
}  // namespace rover::apl::enav

namespace rover::apl::enav {
namespace {

TEST(HeightTerrain, DistanceFieldsAgreeWithTheHazardBits) {
  EnavOptions o = testing::TestOptions();
  auto t = HeightTerrain::Create(o);
  ASSERT_TRUE(t.ok());
  std::vector<testing::Block> rocks;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-3.0, 3.0), hgt(0.1, 0.6);
  for (int n = 0; n < 25; ++n) rocks.push_back({u(rng), u(rng), 0.1, hgt(rng)});
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.translation() = Eigen::Vector3d(0.7, -0.4, 0.0);
  pose.linear() = Eigen::AngleAxisd(-1.2, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  ASSERT_TRUE(t->Update(testing::ScanOf(testing::Blocks(rocks), -3, 3, -3, 3, 0.03, pose)).ok());
  const nav_core::HeightMap& m = *t->height_map();
  static constexpr std::uint8_t kBits[3] = {nav_core::kHazardWheel, nav_core::kHazardRocker,
                                            nav_core::kHazardBody};
  for (int c = 0; c < 3; ++c) {
    const std::vector<float>& d = t->distance(static_cast<HazardLayer>(c));
    for (std::size_t k = 0; k < m.cell_count(); ++k) {
      ASSERT_EQ(d[k] == 0.0F, (m.hazard[k] & kBits[c]) != 0) << "class " << c << " cell " << k;
    }
  }
}

}  // namespace
}  // namespace rover::apl::enav

namespace rover::apl::enav {
namespace {

TEST(HeightTerrain, PointsOnTheRoverItselfAreNotMerged) {
  EnavOptions o = testing::TestOptions();
  o.drop_self_points = true;
  auto t = HeightTerrain::Create(o);
  ASSERT_TRUE(t.ok());
  // A 0.3 m "rock" where the left front wheel stands (points on the wheel, as a leaky stereo mask
  // gives them) and a real one 2 m ahead.
  const auto f = testing::Blocks({{0.625, 0.5, 0.1, 0.3}, {2.5, 0.0, 0.1, 0.3}});
  ASSERT_TRUE(t->Update(testing::ScanOf(f, -3, 3, -3, 3)).ok());
  EXPECT_GT(t->DistanceAt(HazardLayer::kWheel, {0.625, 0.5}), 0.5);
  EXPECT_FLOAT_EQ(t->DistanceAt(HazardLayer::kWheel, {2.5, 0.0}), 0.0F);
  int i = 0, j = 0;
  t->height_map()->CellOf(0.0, 0.0, &i, &j);
  EXPECT_EQ(t->height_map()->count[t->height_map()->Index(i, j)], 0);
}

}  // namespace
}  // namespace rover::apl::enav
