#include "rover/apl/roaman/distance_transform.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace rover::apl::roaman {
namespace {

TEST(DistanceTransform, MatchesBruteForceOnRandomMasks) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 20; ++trial) {
    const int w = 5 + static_cast<int>(rng() % 30), h = 5 + static_cast<int>(rng() % 30);
    Layer<std::uint8_t> f(w, h, 0);
    for (std::size_t k = 0; k < f.size(); ++k) f[k] = (rng() % 17 == 0) ? 1 : 0;
    const Layer<float> d = DistanceTransform(f);
    for (int j = 0; j < h; ++j) {
      for (int i = 0; i < w; ++i) {
        double best = std::numeric_limits<double>::infinity();
        for (int q = 0; q < h; ++q) {
          for (int p = 0; p < w; ++p) {
            if (f.at(p, q)) best = std::min(best, std::hypot(p - i, q - j));
          }
        }
        if (std::isinf(best)) {
          EXPECT_TRUE(std::isinf(d.at(i, j)));
        } else {
          EXPECT_NEAR(d.at(i, j), best, 1e-5) << "trial " << trial << " cell " << i << ", " << j;
        }
      }
    }
  }
}

TEST(DistanceTransform, EmptyAndSingleFeature) {
  EXPECT_EQ(DistanceTransform(Layer<std::uint8_t>(0, 0)).size(), 0u);
  Layer<std::uint8_t> f(4, 3, 0);
  EXPECT_TRUE(std::isinf(DistanceTransform(f).at(2, 1)));
  f.at(0, 0) = 1;
  const Layer<float> d = DistanceTransform(f);
  EXPECT_FLOAT_EQ(d.at(0, 0), 0.0f);
  EXPECT_FLOAT_EQ(d.at(3, 2), static_cast<float>(std::hypot(3.0, 2.0)));
}

}  // namespace
}  // namespace rover::apl::roaman
