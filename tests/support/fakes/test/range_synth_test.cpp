#include "rover/testing/fakes/range_synth.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::testing {
namespace {

TEST(RangeSynth, CentrePixelLooksDownAtFortyFiveDegrees) {
  const sim::terrain::Terrain world = FlatWorld(12.0);
  const PinholeCamera cam = FrontHazcam();
  const auto scan = SynthesizeScan(world.natural, cam, RoverPose(world.natural, 0.0, 0.0, 0.0));
  ASSERT_TRUE(scan.Validate().ok());
  // Pixel (128, 128)'s ray is half a pixel off the boresight, which meets flat ground 0.5 m
  // below the camera 0.5 m ahead of it.
  ASSERT_TRUE(scan.is_valid(128, 128));
  const Eigen::Vector3d p = scan.point(128, 128);
  EXPECT_NEAR(p.x(), 0.52 + 0.5, 0.02);
  EXPECT_NEAR(p.y(), 0.0, 0.01);
  EXPECT_NEAR(p.z(), 0.0, 2e-3);
  // Left of the image is the rover's left (+y).
  ASSERT_TRUE(scan.is_valid(10, 200));
  EXPECT_GT(scan.point(10, 200).y(), 0.3);
  int valid = 0;
  double worst_z = 0.0;
  for (int v = 0; v < scan.height; ++v) {
    for (int u = 0; u < scan.width; ++u) {
      if (!scan.is_valid(u, v)) continue;
      ++valid;
      worst_z = std::max(worst_z, std::abs(scan.point(u, v).z()));
    }
  }
  EXPECT_GT(valid, 30000);      // the ground below the horizon out to max_range
  EXPECT_LT(valid, 256 * 256);  // the rows above the far range edge are empty
  EXPECT_LT(worst_z, 2e-3);
}

TEST(RangeSynth, FollowsTheRoverPose) {
  const sim::terrain::Terrain world = FlatWorld(12.0);
  const PinholeCamera cam = FrontHazcam();
  const Eigen::Isometry3d pose = RoverPose(world.natural, 1.0, -2.0, 0.9);
  const auto scan = SynthesizeScan(world.natural, cam, pose);
  const Eigen::Vector3d site = pose * scan.point(128, 128);
  EXPECT_NEAR(site.x(), 1.0 + 1.02 * std::cos(0.9), 0.02);
  EXPECT_NEAR(site.y(), -2.0 + 1.02 * std::sin(0.9), 0.02);
}

TEST(RangeSynth, RocksStandUpAndCastShadows) {
  sim::terrain::Terrain world = FlatWorld(12.0);
  AddRock(&world, 2.0, 0.0, 0.5, 0.3);
  const auto scan = SynthesizeScan(world.natural, FrontHazcam(), RoverPose(world.natural, 0, 0, 0));
  double top = 0.0;
  int behind = 0;
  for (int v = 0; v < scan.height; ++v) {
    for (int u = 0; u < scan.width; ++u) {
      if (!scan.is_valid(u, v)) continue;
      const Eigen::Vector3d p = scan.point(u, v);
      if (std::abs(p.y()) < 0.1) {
        top = std::max(top, p.z());
        if (p.x() > 2.3 && p.x() < 2.5) ++behind;  // just behind the rock: in its shadow
      }
    }
  }
  EXPECT_NEAR(top, 0.3, 0.01);
  EXPECT_EQ(behind, 0);
}

TEST(RangeSynth, NoiseIsSeededAndGrowsWithRange) {
  const sim::terrain::Terrain world = FlatWorld(12.0);
  PinholeCamera cam = FrontHazcam();
  cam.noise_at_1m = 0.01;
  const Eigen::Isometry3d pose = RoverPose(world.natural, 0, 0, 0);
  const auto a = SynthesizeScan(world.natural, cam, pose);
  const auto b = SynthesizeScan(world.natural, cam, pose);
  EXPECT_EQ(a.xyz, b.xyz);
  cam.seed = 2;
  const auto c = SynthesizeScan(world.natural, cam, pose);
  EXPECT_NE(a.xyz, c.xyz);
  // Height spread near (x < 1.5 m) and far (x > 3.5 m).
  double near2 = 0.0, far2 = 0.0;
  int nn = 0, nf = 0;
  for (std::size_t k = 0; k < a.pixel_count(); ++k) {
    if (!a.valid[k]) continue;
    const double x = a.xyz[3 * k], z = a.xyz[3 * k + 2];
    if (x < 1.5) {
      near2 += z * z;
      ++nn;
    } else if (x > 3.5) {
      far2 += z * z;
      ++nf;
    }
  }
  ASSERT_GT(nn, 100);
  ASSERT_GT(nf, 100);
  EXPECT_GT(std::sqrt(far2 / nf), 4.0 * std::sqrt(near2 / nn));
}

}  // namespace
}  // namespace rover::testing
