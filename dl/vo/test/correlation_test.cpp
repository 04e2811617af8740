#include "rover/dl/vo/correlation.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "synthetic_scene.hpp"

namespace rover::dl::vo {
namespace {

// A smooth-but-rich float image I(x - sx, y - sy): shifting it by a sub-pixel amount is exact.
cv::Mat ShiftedTexture(int w, int h, double sx, double sy, double gain = 1.0, double offset = 0.0) {
  cv::Mat img(h, w, CV_32F);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double v = testing::Texture((x - sx) / 60.0, (y - sy) / 60.0, 3);
      img.at<float>(y, x) = static_cast<float>(offset + gain * (30.0 + 200.0 * v));
    }
  }
  return img;
}

TEST(Correlation, IdenticalPatchScoresOneAndOffsetInvariant) {
  const CorrelationImage a(ShiftedTexture(64, 64, 0, 0));
  const CorrelationImage b(ShiftedTexture(64, 64, 0, 0, 1.0, 17.0));  // brighter, same contrast
  Template t;
  ASSERT_TRUE(ExtractTemplate(a, 30, 30, 5, &t));
  EXPECT_NEAR(CorrelationScore(t, a, 30, 30), 1.0, 1e-6);
  EXPECT_NEAR(CorrelationScore(t, b, 30, 30), 1.0, 1e-5);
  EXPECT_LT(CorrelationScore(t, a, 36, 30), 0.9);
}

TEST(Correlation, PenalisesContrastChangeUnlikeNcc) {
  const CorrelationImage a(ShiftedTexture(64, 64, 0, 0));
  const CorrelationImage half(ShiftedTexture(64, 64, 0, 0, 0.5));
  Template t;
  ASSERT_TRUE(ExtractTemplate(a, 30, 30, 5, &t));
  // 2 s / (1 + s^2) with s = 0.5 gives 0.8.
  EXPECT_NEAR(CorrelationScore(t, half, 30, 30), 0.8, 1e-4);
  const CorrelationImage flat(cv::Mat(64, 64, CV_32F, cv::Scalar(100)));
  EXPECT_NEAR(CorrelationScore(t, flat, 30, 30), 0.0, 1e-6);
}

TEST(Correlation, OutsideImageIsInvalid) {
  const CorrelationImage a(ShiftedTexture(32, 32, 0, 0));
  Template t;
  EXPECT_FALSE(ExtractTemplate(a, 2, 10, 5, &t));
  ASSERT_TRUE(ExtractTemplate(a, 10, 10, 5, &t));
  EXPECT_EQ(CorrelationScore(t, a, 28, 10), -2.0);
}

TEST(Biquadratic, RecoversPeakOfAQuadraticSurface) {
  const double px = 0.3, py = -0.2;
  std::array<double, 9> s{};
  for (int j = -1; j <= 1; ++j) {
    for (int i = -1; i <= 1; ++i) {
      const double dx = i - px, dy = j - py;
      s[static_cast<std::size_t>((j + 1) * 3 + i + 1)] =
          0.95 - 0.2 * dx * dx - 0.1 * dx * dy - 0.15 * dy * dy;
    }
  }
  const SubpixelPeak p = FitBiquadratic(s);
  ASSERT_TRUE(p.ok);
  EXPECT_NEAR(p.dx, px, 1e-9);
  EXPECT_NEAR(p.dy, py, 1e-9);
  // -Hessian = [0.4 0.1; 0.1 0.3]: smaller eigenvalue 0.35 - sqrt(0.0025 + 0.01).
  EXPECT_NEAR(p.curvature, 0.35 - std::sqrt(0.0125), 1e-9);
}

TEST(Biquadratic, RejectsSaddleAndFlat) {
  std::array<double, 9> saddle{};
  for (int j = -1; j <= 1; ++j) {
    for (int i = -1; i <= 1; ++i)
      saddle[static_cast<std::size_t>((j + 1) * 3 + i + 1)] = i * i - j * j;
  }
  EXPECT_FALSE(FitBiquadratic(saddle).ok);
  std::array<double, 9> flat{};
  flat.fill(0.5);
  EXPECT_FALSE(FitBiquadratic(flat).ok);
}

TEST(SearchWindow, FindsSubpixelShift) {
  const CorrelationImage a(ShiftedTexture(120, 120, 0, 0));
  for (const auto& [sx, sy] : {std::pair{3.3, -2.6}, std::pair{-5.5, 0.25}, std::pair{0.0, 4.8}}) {
    const CorrelationImage b(ShiftedTexture(120, 120, sx, sy));
    Template t;
    ASSERT_TRUE(ExtractTemplate(a, 60, 60, 5, &t));
    const WindowMatch m = SearchWindow(t, b, 60, 60, 8, 8);
    ASSERT_TRUE(m.ok) << m.failure;
    EXPECT_NEAR(m.position.x(), 60 + sx, 0.15);
    EXPECT_NEAR(m.position.y(), 60 + sy, 0.15);
    EXPECT_GT(m.score, 0.9);
    EXPECT_GT(m.curvature, 0.02);
  }
}

TEST(SearchWindow, PeakOutsideWindowIsReported) {
  const CorrelationImage a(ShiftedTexture(120, 120, 0, 0));
  const CorrelationImage b(ShiftedTexture(120, 120, 9, 0));
  Template t;
  ASSERT_TRUE(ExtractTemplate(a, 60, 60, 5, &t));
  const WindowMatch m = SearchWindow(t, b, 60, 60, 3, 3);  // true peak 9 px away
  EXPECT_FALSE(m.ok && std::abs(m.position.x() - 69) < 0.5);
}

TEST(WarpedTemplate, IdentityAtIntegerCentreEqualsPlainTemplate) {
  const CorrelationImage a(ShiftedTexture(64, 64, 0, 0));
  Template t1, t2;
  ASSERT_TRUE(ExtractTemplate(a, 20, 25, 4, &t1));
  ASSERT_TRUE(ExtractWarpedTemplate(a, {20, 25}, Eigen::Matrix2d::Identity(), 4, &t2));
  ASSERT_EQ(t1.values.size(), t2.values.size());
  for (std::size_t i = 0; i < t1.values.size(); ++i) EXPECT_NEAR(t1.values[i], t2.values[i], 1e-3);
  EXPECT_FALSE(ExtractWarpedTemplate(a, {2, 25}, Eigen::Matrix2d::Identity(), 4, &t2));
}

}  // namespace
}  // namespace rover::dl::vo
