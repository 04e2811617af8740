#include "rover/dl/stereo/setup_cache.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "test_cameras.hpp"

namespace rover::dl::stereo {
namespace {

msg::CameraModelFields Camera(double y, double f = 100.0) { return testing::ForwardCamera(y, f); }

TEST(StereoSetupCache, ComputesOncePerModelPair) {
  StereoSetupCache cache(2);
  const msg::CameraModelFields left = Camera(0.1), right = Camera(-0.1);
  auto a = cache.Get(left, right);
  ASSERT_TRUE(a.ok()) << a.status().ToString();
  EXPECT_NEAR((*a)->camera.model.baseline_m, 0.2, 1e-12);
  EXPECT_NEAR((*a)->camera.model.focal_px, 100.0, 1e-9);
  EXPECT_NEAR((*a)->camera.rover_from_camera.translation().y(), 0.1, 1e-12);
  EXPECT_EQ((*a)->maps.rectified_size(), cv::Size(128, 96));
  auto b = cache.Get(left, right);
  ASSERT_TRUE(b.ok());
  EXPECT_EQ(a->get(), b->get());
  EXPECT_EQ(cache.hits(), 1u);
  EXPECT_EQ(cache.misses(), 1u);

  msg::CameraModelFields nudged = right;
  nudged.c[1] += 1e-6;  // any change in a field is another pair
  nudged.position[1] += 1e-6;
  auto c = cache.Get(left, nudged);
  ASSERT_TRUE(c.ok()) << c.status().ToString();
  EXPECT_NE(c->get(), a->get());
  EXPECT_EQ(cache.misses(), 2u);
  EXPECT_EQ(cache.size(), 2u);
}

TEST(StereoSetupCache, EvictsTheLeastRecentlyUsedButHandedOutSetupsStayValid) {
  StereoSetupCache cache(1);
  auto a = cache.Get(Camera(0.1), Camera(-0.1));
  ASSERT_TRUE(a.ok());
  auto b = cache.Get(Camera(0.1, 90.0), Camera(-0.1, 90.0));
  ASSERT_TRUE(b.ok());
  EXPECT_EQ(cache.size(), 1u);
  EXPECT_NEAR((*a)->camera.model.focal_px, 100.0, 1e-9);  // still alive
  auto again = cache.Get(Camera(0.1), Camera(-0.1));
  ASSERT_TRUE(again.ok());
  EXPECT_NE(again->get(), a->get());  // recomputed after eviction
  EXPECT_EQ(cache.misses(), 3u);
}

TEST(StereoSetupCache, BadModelsAreErrorsAndNotCached) {
  StereoSetupCache cache(4);
  msg::CameraModelFields missing;
  missing.width = 128;
  missing.height = 96;
  auto r = cache.Get(Camera(0.1), missing);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message().rfind("right model: ", 0), 0u) << r.status().message();
  EXPECT_NE(r.status().message().find("missing"), std::string::npos);

  // Both cameras at the same place: no baseline, cannot be rectified.
  r = cache.Get(Camera(0.1), Camera(0.1));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().message().rfind("stereo rectification: ", 0), 0u) << r.status().message();
  EXPECT_EQ(cache.size(), 0u);
}

}  // namespace
}  // namespace rover::dl::stereo
