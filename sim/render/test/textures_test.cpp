#include "src/textures.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::sim::render::internal {
namespace {

TEST(TexturesTest, DeterministicPerSeed) {
  const auto a = MakeSoilDetailTexture(5, 256), b = MakeSoilDetailTexture(5, 256);
  const auto c = MakeSoilDetailTexture(6, 256);
  EXPECT_EQ(a.rgba, b.rgba);
  EXPECT_NE(a.rgba, c.rgba);
  const auto r1 = MakeRockTextures(5, 128), r2 = MakeRockTextures(5, 128);
  EXPECT_EQ(r1.rgba, r2.rgba);
  EXPECT_EQ(r1.layers, kRockLayers);
}

TEST(TexturesTest, SoilHasGrainAndMeanAlbedoOne) {
  const auto t = MakeSoilDetailTexture(1, 512);
  double sum = 0, sum2 = 0, grad = 0;
  const int n = t.size;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double a = t.Texel(0, x, y)[0] / 127.5;
      sum += a;
      sum2 += a * a;
      grad += std::abs(a - t.Texel(0, (x + 1) % n, y)[0] / 127.5);
    }
  const double m = sum / (n * n), sd = std::sqrt(sum2 / (n * n) - m * m);
  EXPECT_NEAR(m, 1.0, 0.08);
  EXPECT_GT(sd, 0.10);                 // albedo variation
  EXPECT_GT(grad / (n * n), 0.04);     // texel-to-texel grain (what 7x7 SAD correlation needs)
}

TEST(TexturesTest, FbmTiles) {
  const int n = 128;
  const auto f = PeriodicFbm(3, n, 32, 4, 0.5);
  // The step across the wrap (column n-1 -> 0) is like any other neighbouring step.
  double wrap = 0, inner = 0;
  for (int y = 0; y < n; ++y) {
    wrap += std::abs(f[y * n + 0] - f[y * n + n - 1]);
    inner += std::abs(f[y * n + n / 2] - f[y * n + n / 2 - 1]);
  }
  EXPECT_LT(wrap, 3.0 * inner + 1e-3);
  for (float v : f) EXPECT_LE(std::abs(v), 1.0F + 1e-6F);
}

TEST(TexturesTest, ScienceLayersAreDistinct) {
  const auto t = MakeRockTextures(1, 128);
  const int n = t.size;
  for (int a = kGenericRockLayers; a < kRockLayers; ++a) {
    for (int b = a + 1; b < kRockLayers; ++b) {
      double diff = 0;
      for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) diff += std::abs(t.Texel(a, x, y)[0] - t.Texel(b, x, y)[0]);
      EXPECT_GT(diff / (n * n), 5.0) << "layers " << a << " and " << b;
    }
  }
}

}  // namespace
}  // namespace rover::sim::render::internal
