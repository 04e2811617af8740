#include "mast_synth.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "scenes.hpp"

namespace rover::apl::roaman::testing {
namespace {

TEST(MastSynth, SeesFlatGroundWhereThePinholeSays) {
  const sim::terrain::HeightField flat = FlatGround(-2, -8, 14, 8, 0.04);
  MastCamera cam;
  cam.width = 41;  // an odd size: the centre pixel looks along the boresight
  cam.height = 31;
  cam.tilt = -30.0 * kDegree;
  const nav_core::RangeScan s = SynthesizeScan(flat, cam, RoverPose(flat, 0, 0, 0));
  ASSERT_TRUE(s.Validate().ok());
  ASSERT_TRUE(s.is_valid(20, 15));
  const Eigen::Vector3d c = s.point(20, 15);
  EXPECT_NEAR(c.x(), 0.35 + 1.5 / std::tan(30.0 * kDegree), 0.01);
  EXPECT_NEAR(c.y(), 0.0, 0.01);
  EXPECT_NEAR(c.z(), 0.0, 0.005);
  // Left pixels (small u) look left (+y), upper pixels (small v) farther.
  EXPECT_GT(s.point(0, 15).y(), 0.3);
  EXPECT_GT(s.point(20, 0).x(), c.x());
  int valid = 0;
  for (int v = 0; v < s.height; ++v) {
    for (int u = 0; u < s.width; ++u) {
      if (!s.is_valid(u, v)) continue;
      ++valid;
      EXPECT_NEAR(s.point(u, v).z(), 0.0, 0.005);
      EXPECT_LE(s.point(u, v).head<2>().norm(), cam.max_range + 1e-6);
    }
  }
  EXPECT_EQ(valid, 41 * 31);
}

TEST(MastSynth, RocksCastShadowsAndTheRangeEnds) {
  sim::terrain::HeightField g = FlatGround(-2, -8, 16, 8, 0.04);
  AddRock(&g, 4.0, 0.0, 0.8, 0.6);
  MastCamera cam;
  cam.width = 120;
  cam.height = 90;
  cam.tilt = -10.0 * kDegree;
  const nav_core::RangeScan s = SynthesizeScan(g, cam, RoverPose(g, 0, 0, 0));
  // No ground point just behind the rock (its shadow from a 1.5 m mast: about 2.5 m long for a
  // 0.6 m rock 3.65 m from the camera), points on the rock itself, none past 12 m.
  int shadow = 0, on_rock = 0, beyond = 0;
  for (int v = 0; v < s.height; ++v) {
    for (int u = 0; u < s.width; ++u) {
      if (!s.is_valid(u, v)) continue;
      const Eigen::Vector3d p = s.point(u, v);
      if (p.x() > 4.5 && p.x() < 6.0 && std::abs(p.y()) < 0.15) ++shadow;
      if (p.z() > 0.3) ++on_rock;
      if (p.head<2>().norm() > 12.0) ++beyond;
    }
  }
  EXPECT_EQ(shadow, 0);
  EXPECT_GT(on_rock, 20);
  EXPECT_EQ(beyond, 0);
}

TEST(MastSynth, IsReproducibleAndNoiseFollowsTheSeed) {
  const sim::terrain::HeightField flat = FlatGround(-2, -8, 14, 8, 0.04);
  MastCamera cam;
  cam.width = 20;
  cam.height = 10;
  cam.noise_at_10m = 0.05;
  const Eigen::Isometry3d pose = RoverPose(flat, 1.0, 2.0, 0.3);
  const nav_core::RangeScan a = SynthesizeScan(flat, cam, pose);
  const nav_core::RangeScan b = SynthesizeScan(flat, cam, pose);
  EXPECT_EQ(a.xyz, b.xyz);
  cam.seed = 2;
  EXPECT_NE(SynthesizeScan(flat, cam, pose).xyz, a.xyz);
  EXPECT_EQ(a.site_from_rover.translation(), pose.translation());
}

TEST(MastSynth, PanoramaPointingsAndOverheadScans) {
  MastCamera cam;
  const auto p = PanoramaPointings(cam, 60.0 * kDegree, 5, {-10.0 * kDegree, -30.0 * kDegree});
  ASSERT_EQ(p.size(), 10u);
  EXPECT_NEAR(p[0].pan, -60.0 * kDegree, 1e-12);
  EXPECT_NEAR(p[4].pan, 60.0 * kDegree, 1e-12);
  EXPECT_NEAR(p[5].tilt, -30.0 * kDegree, 1e-12);
  EXPECT_NE(p[0].seed, p[1].seed);

  sim::terrain::HeightField g = FlatGround(-1, -1, 3, 3, 0.02);
  AddRock(&g, 1.0, 1.0, 0.4, 0.2);
  const nav_core::RangeScan o = OverheadScan(g, 0.0, 0.0, 2.0, 1.0, 0.1, RoverPose(g, 0.5, 0.5, 0.0));
  EXPECT_EQ(o.width, 21);
  EXPECT_EQ(o.height, 11);
  // Pixel (10, 10) is site (1.0, 1.0): the rock top, in the rover frame 0.5 m ahead and left.
  ASSERT_TRUE(o.is_valid(10, 10));
  EXPECT_NEAR(o.point(10, 10).x(), 0.5, 1e-6);
  EXPECT_NEAR(o.point(10, 10).y(), 0.5, 1e-6);
  EXPECT_NEAR(o.point(10, 10).z(), 0.2, 1e-6);
}

}  // namespace
}  // namespace rover::apl::roaman::testing
