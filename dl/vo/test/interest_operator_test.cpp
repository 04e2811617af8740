#include "rover/dl/vo/interest_operator.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>

#include "synthetic_scene.hpp"

namespace rover::dl::vo {
namespace {

cv::Mat RandomTexture(int w, int h, std::uint64_t seed) {
  cv::Mat img(h, w, CV_8UC1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const double v = testing::Texture(x / 40.0, y / 40.0, seed);
      img.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(std::lround(20 + 215 * v));
    }
  }
  return img;
}

TEST(InterestOptions, Validate) {
  InterestOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.cell_size = 2;
  EXPECT_NE(o.Validate().message().find("cell_size"), std::string::npos);
  o = InterestOptions{};
  o.min_roundness = 1.5;
  EXPECT_FALSE(o.Validate().ok());
  o = InterestOptions{};
  o.min_separation = -1;
  EXPECT_FALSE(o.Validate().ok());
  o = InterestOptions{};
  o.min_strength = 0.0;
  EXPECT_FALSE(o.Validate().ok());
}

TEST(Forstner, CornerIsRoundEdgeIsNot) {
  cv::Mat img(64, 64, CV_8UC1, cv::Scalar(50));
  img(cv::Rect(32, 32, 32, 32)).setTo(200);  // a corner at (32, 32)
  img(cv::Rect(0, 0, 16, 64)).setTo(200);    // a straight edge at x = 16
  cv::Mat w, q;
  ForstnerOperator(img, 2, &w, &q);
  EXPECT_GT(w.at<float>(32, 32), 100.0f);
  EXPECT_GT(q.at<float>(32, 32), 0.5f);
  // On the straight edge the tensor is rank one: no strength, no roundness.
  EXPECT_LT(w.at<float>(48, 16), 1e-3f);
  EXPECT_LT(q.at<float>(48, 16), 1e-3f);
}

TEST(DetectInterestPoints, NoneOnConstantImage) {
  const cv::Mat img(240, 320, CV_8UC1, cv::Scalar(128));
  EXPECT_TRUE(DetectInterestPoints(img, InterestOptions{}).empty());
}

TEST(DetectInterestPoints, NoneOnSmoothImage) {
  // Smooth shading and a ramp: gradients of at most ~1 grey level per pixel.
  cv::Mat img(240, 320, CV_8UC1);
  for (int y = 0; y < img.rows; ++y) {
    for (int x = 0; x < img.cols; ++x) {
      img.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(
          std::lround(128 + 40 * std::sin(x / 60.0) * std::cos(y / 45.0) + 0.2 * x - 32));
    }
  }
  EXPECT_TRUE(DetectInterestPoints(img, InterestOptions{}).empty());
}

TEST(DetectInterestPoints, FindsCheckerboardCorners) {
  cv::Mat img(160, 160, CV_8UC1);
  for (int y = 0; y < 160; ++y) {
    for (int x = 0; x < 160; ++x) {
      img.at<std::uint8_t>(y, x) = ((x / 32) + (y / 32)) % 2 ? 220 : 30;
    }
  }
  InterestOptions o;
  o.cell_size = 32;
  o.min_separation = 20;
  const auto pts = DetectInterestPoints(img, o);
  ASSERT_FALSE(pts.empty());
  for (const auto& p : pts) {
    // Every feature sits within a pixel of a board corner (multiples of 32 minus 0.5).
    const double dx = std::abs(std::fmod(p.x + 0.5 + 16.0, 32.0) - 16.0);
    const double dy = std::abs(std::fmod(p.y + 0.5 + 16.0, 32.0) - 16.0);
    EXPECT_LE(dx, 1.5) << p.x << "," << p.y;
    EXPECT_LE(dy, 1.5) << p.x << "," << p.y;
  }
}

class MinSeparation : public ::testing::TestWithParam<double> {};

TEST_P(MinSeparation, RespectedBetweenEveryPair) {
  const cv::Mat img = RandomTexture(400, 300, 11);
  InterestOptions o;
  o.cell_size = 8;  // small cells: many candidates next to each other
  o.min_separation = GetParam();
  const auto pts = DetectInterestPoints(img, o);
  ASSERT_GT(pts.size(), 20u);
  for (std::size_t i = 0; i < pts.size(); ++i) {
    for (std::size_t j = i + 1; j < pts.size(); ++j) {
      const double d = std::hypot(pts[i].x - pts[j].x, pts[i].y - pts[j].y);
      ASSERT_GE(d, GetParam()) << "features " << i << " and " << j;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Separations, MinSeparation, ::testing::Values(0.0, 6.0, 12.0, 25.0));

TEST(DetectInterestPoints, OnePerCellStrongestFirstWithinBorder) {
  const cv::Mat img = RandomTexture(400, 300, 5);
  InterestOptions o;
  o.cell_size = 40;
  o.min_separation = 0;
  o.border = 15;
  const auto pts = DetectInterestPoints(img, o);
  ASSERT_GT(pts.size(), 30u);
  std::set<std::pair<int, int>> cells;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    EXPECT_TRUE(cells.insert({pts[i].x / 40, pts[i].y / 40}).second) << "two in one cell";
    EXPECT_GE(pts[i].x, 15);
    EXPECT_GE(pts[i].y, 15);
    EXPECT_LT(pts[i].x, 400 - 15);
    EXPECT_LT(pts[i].y, 300 - 15);
    if (i > 0) {
      EXPECT_LE(pts[i].strength, pts[i - 1].strength);
    }
  }
  o.max_features = 7;
  const auto capped = DetectInterestPoints(img, o);
  ASSERT_EQ(capped.size(), 7u);
  for (int i = 0; i < 7; ++i)
    EXPECT_EQ(capped[static_cast<std::size_t>(i)].x, pts[static_cast<std::size_t>(i)].x);
}

}  // namespace
}  // namespace rover::dl::vo
