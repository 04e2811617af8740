#include "rover/dl/stereo/filters.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace rover::dl::stereo {
namespace {

DisparityImage AllValid(cv::Size size, float d) {
  DisparityImage img;
  img.Reset(size, PixelStatus::kValid);
  img.disparity.setTo(cv::Scalar(d));
  return img;
}

PixelStatus At(const DisparityImage& d, int v, int u) {
  return static_cast<PixelStatus>(d.status.at<std::uint8_t>(v, u));
}

TEST(FilterOptionsTest, Validate) {
  FilterOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.blob_max_step = 0;
  EXPECT_NE(o.Validate().message().find("blob_max_step"), std::string::npos);
  o = FilterOptions();
  o.overhang_search_rows = 0;
  EXPECT_FALSE(o.Validate().ok());
  o = FilterOptions();
  o.border_px = -1;
  EXPECT_FALSE(o.Validate().ok());
  o = FilterOptions();
  o.overhang_ratio = 2;
  EXPECT_FALSE(o.Validate().ok());
}

TEST(BorderFilterTest, RejectsMarginOnly) {
  DisparityImage d = AllValid({10, 8}, 4.0f);
  ASSERT_TRUE(ApplyBorderFilter(2, &d).ok());
  for (int v = 0; v < 8; ++v) {
    for (int u = 0; u < 10; ++u) {
      const bool border = v < 2 || v >= 6 || u < 2 || u >= 8;
      EXPECT_EQ(At(d, v, u), border ? PixelStatus::kBorder : PixelStatus::kValid) << v << "," << u;
      EXPECT_EQ(std::isnan(d.disparity.at<float>(v, u)), border);
    }
  }
  EXPECT_FALSE(ApplyBorderFilter(-1, &d).ok());
  DisparityImage empty;
  EXPECT_FALSE(ApplyBorderFilter(1, &empty).ok());
}

TEST(BlobFilterTest, RemovesAThreePixelBlobAndKeepsLargeRegions) {
  DisparityImage d;
  d.Reset({20, 12}, PixelStatus::kFlat);
  // A 10x6 region at disparity 5 and an isolated L-shaped blob of 3 pixels at disparity 9.
  for (int v = 1; v < 7; ++v) {
    for (int u = 1; u < 11; ++u) {
      d.status.at<std::uint8_t>(v, u) = 0;
      d.disparity.at<float>(v, u) = 5.0f + 0.1f * u;  // smooth slope: one region
    }
  }
  const cv::Point blob[] = {{15, 9}, {16, 9}, {16, 10}};
  for (const auto& p : blob) {
    d.status.at<std::uint8_t>(p) = 0;
    d.disparity.at<float>(p) = 9.0f;
  }
  ASSERT_TRUE(ApplyBlobFilter(4, 1.0, &d).ok());
  for (const auto& p : blob) EXPECT_EQ(At(d, p.y, p.x), PixelStatus::kBlob);
  EXPECT_EQ(d.CountValid(), 60);
  EXPECT_EQ(At(d, 0, 0), PixelStatus::kFlat);  // other reasons untouched
  // With min_area 3 the blob survives.
  DisparityImage d2;
  d2.Reset({5, 5}, PixelStatus::kFlat);
  for (const auto& p : {cv::Point(1, 1), cv::Point(2, 1), cv::Point(2, 2)}) {
    d2.status.at<std::uint8_t>(p) = 0;
    d2.disparity.at<float>(p) = 1.0f;
  }
  ASSERT_TRUE(ApplyBlobFilter(3, 1.0, &d2).ok());
  EXPECT_EQ(d2.CountValid(), 3);
}

TEST(BlobFilterTest, DisparityStepSplitsRegions) {
  // Two 4x4 halves touching, disparities 2 and 6: with max_step 1 they are two regions of 16.
  DisparityImage d = AllValid({8, 4}, 2.0f);
  d.disparity(cv::Rect(4, 0, 4, 4)).setTo(6.0f);
  DisparityImage a = d;
  a.disparity = d.disparity.clone();
  a.status = d.status.clone();
  ASSERT_TRUE(ApplyBlobFilter(20, 1.0, &a).ok());
  EXPECT_EQ(a.CountValid(), 0);  // both halves (16 px each) are below 20
  ASSERT_TRUE(ApplyBlobFilter(20, 5.0, &d).ok());
  EXPECT_EQ(d.CountValid(), 32);  // joined: 32 px
  EXPECT_FALSE(ApplyBlobFilter(5, 0.0, &d).ok());
  EXPECT_FALSE(ApplyBlobFilter(-1, 1.0, &d).ok());
}

TEST(BlobFilterTest, SpiralRegionIsOneComponent) {
  // A region whose connectivity needs label merging (U shape opened upwards).
  DisparityImage d;
  d.Reset({7, 5}, PixelStatus::kFlat);
  const char* rows[] = {"X.X.X.X", "X.X.X.X", "X.X.X.X", "XXXXXXX", "......."};
  for (int v = 0; v < 5; ++v) {
    for (int u = 0; u < 7; ++u) {
      if (rows[v][u] == 'X') {
        d.status.at<std::uint8_t>(v, u) = 0;
        d.disparity.at<float>(v, u) = 3.0f;
      }
    }
  }
  ASSERT_TRUE(ApplyBlobFilter(19, 1.0, &d).ok());
  EXPECT_EQ(d.CountValid(), 19);
  ASSERT_TRUE(ApplyBlobFilter(20, 1.0, &d).ok());
  EXPECT_EQ(d.CountValid(), 0);
}

TEST(OverhangFilterTest, RejectsDisparityThatGrowsUpTheImage) {
  // Natural terrain: disparity falls from bottom (20) to top (5).
  DisparityImage d = AllValid({6, 16}, 0.0f);
  for (int v = 0; v < 16; ++v) d.disparity.row(v).setTo(5.0f + v);
  // Column 2 has a looming run in rows 3..5 (disparity 30 above terrain at ~9).
  for (int v = 3; v <= 5; ++v) d.disparity.at<float>(v, 2) = 30.0f;
  ASSERT_TRUE(ApplyOverhangFilter(2.0, 0.1, 8, &d).ok());
  for (int v = 3; v <= 5; ++v) EXPECT_EQ(At(d, v, 2), PixelStatus::kOverhang) << v;
  EXPECT_EQ(d.CountValid(), 16 * 6 - 3);
  // A small rise within tolerance is kept.
  DisparityImage e = AllValid({3, 10}, 10.0f);
  e.disparity.at<float>(4, 1) = 11.5f;
  ASSERT_TRUE(ApplyOverhangFilter(2.0, 0.1, 8, &e).ok());
  EXPECT_EQ(e.CountValid(), 30);
  // Beyond `search_rows` rows there is no reference: kept.
  DisparityImage f = AllValid({1, 12}, kInvalidDisparity);
  f.status.setTo(static_cast<int>(PixelStatus::kFlat));
  f.status.at<std::uint8_t>(11, 0) = 0;
  f.disparity.at<float>(11, 0) = 5.0f;
  f.status.at<std::uint8_t>(0, 0) = 0;
  f.disparity.at<float>(0, 0) = 40.0f;
  ASSERT_TRUE(ApplyOverhangFilter(2.0, 0.1, 4, &f).ok());
  EXPECT_EQ(f.CountValid(), 2);
  ASSERT_TRUE(ApplyOverhangFilter(2.0, 0.1, 12, &f).ok());
  EXPECT_EQ(At(f, 0, 0), PixelStatus::kOverhang);
  EXPECT_FALSE(ApplyOverhangFilter(-1, 0.1, 4, &f).ok());
}

// The sliding-window implementation against a direct reading of the rule (filters.hpp).
TEST(OverhangFilterTest, MatchesDirectImplementationOnRandomData) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<float> disp(0.0f, 30.0f);
  std::uniform_int_distribution<int> coin(0, 3);
  for (const int rows : {1, 3, 8, 11}) {
    DisparityImage d;
    d.Reset({37, 50}, PixelStatus::kFlat);
    for (int v = 0; v < 50; ++v) {
      for (int u = 0; u < 37; ++u) {
        if (coin(rng) == 0) continue;  // a quarter invalid
        d.status.at<std::uint8_t>(v, u) = 0;
        d.disparity.at<float>(v, u) = disp(rng) + 0.3f * (50 - v);  // mostly receding upwards
      }
    }
    DisparityImage ref;
    ref.disparity = d.disparity.clone();
    ref.status = d.status.clone();
    for (int u = 0; u < 37; ++u) {
      for (int v = 49; v >= 0; --v) {
        if (ref.status.at<std::uint8_t>(v, u) != 0) continue;
        float best = -std::numeric_limits<float>::infinity();
        for (int r = v + 1; r <= std::min(49, v + rows); ++r) {
          if (ref.status.at<std::uint8_t>(r, u) == 0)
            best = std::max(best, ref.disparity.at<float>(r, u));
        }
        if (std::isfinite(best) &&
            ref.disparity.at<float>(v, u) > best + std::max(2.0f, 0.1f * std::abs(best))) {
          ref.Reject(v, u, PixelStatus::kOverhang);
        }
      }
    }
    ASSERT_TRUE(ApplyOverhangFilter(2.0, 0.1, rows, &d).ok());
    EXPECT_EQ(cv::norm(d.status, ref.status, cv::NORM_INF), 0.0) << "rows " << rows;
    EXPECT_GT(d.CountStatus()[static_cast<int>(PixelStatus::kOverhang)], 0) << "rows " << rows;
  }
}

TEST(MaskTest, MaskOverridesEveryStatus) {
  DisparityImage d = AllValid({6, 4}, 3.0f);
  d.status.at<std::uint8_t>(0, 0) = static_cast<std::uint8_t>(PixelStatus::kFlat);
  cv::Mat mask = cv::Mat::zeros(4, 6, CV_8UC1);
  mask.at<std::uint8_t>(0, 0) = 1;
  mask.at<std::uint8_t>(2, 3) = 255;
  ASSERT_TRUE(ApplyMask(mask, PixelStatus::kVehicle, &d).ok());
  EXPECT_EQ(At(d, 0, 0), PixelStatus::kVehicle);
  EXPECT_EQ(At(d, 2, 3), PixelStatus::kVehicle);
  EXPECT_TRUE(std::isnan(d.disparity.at<float>(2, 3)));
  EXPECT_EQ(d.CountValid(), 22);
  EXPECT_TRUE(ApplyMask(cv::Mat(), PixelStatus::kVehicle, &d).ok());  // no mask: no-op
  Status s = ApplyMask(cv::Mat::zeros(5, 6, CV_8UC1), PixelStatus::kVehicle, &d);
  EXPECT_NE(s.message().find("mask is 6x5"), std::string::npos) << s.message();
  EXPECT_FALSE(ApplyMask(cv::Mat::zeros(4, 6, CV_16UC1), PixelStatus::kVehicle, &d).ok());
}

TEST(MaskTest, RasterizesWheelPolygonsAtPyramidLevels) {
  const std::vector<std::vector<cv::Point2f>> square = {
      {{10.f, 10.f}, {29.f, 10.f}, {29.f, 29.f}, {10.f, 29.f}}};
  auto full = RasterizePolygons(square, {40, 40}, 0);
  ASSERT_TRUE(full.ok()) << full.status().ToString();
  EXPECT_EQ(cv::countNonZero(*full), 400);
  EXPECT_EQ(full->at<std::uint8_t>(10, 10), 255);
  EXPECT_EQ(full->at<std::uint8_t>(9, 10), 0);
  auto half = RasterizePolygons(square, {20, 20}, 1);
  ASSERT_TRUE(half.ok());
  EXPECT_NEAR(cv::countNonZero(*half), 100, 25);
  EXPECT_EQ(half->at<std::uint8_t>(10, 10), 255);
  EXPECT_EQ(half->at<std::uint8_t>(2, 2), 0);
  EXPECT_FALSE(RasterizePolygons({{{0.f, 0.f}, {1.f, 1.f}}}, {10, 10}, 0).ok());
  EXPECT_FALSE(RasterizePolygons({{{0.f, 0.f}, {1.f, NAN}, {2.f, 0.f}}}, {10, 10}, 0).ok());
  EXPECT_FALSE(RasterizePolygons(square, {0, 10}, 0).ok());
  EXPECT_FALSE(RasterizePolygons(square, {10, 10}, -1).ok());
}

TEST(MaskTest, DownsampleMaskIsConservative) {
  cv::Mat mask = cv::Mat::zeros(8, 8, CV_8UC1);
  mask.at<std::uint8_t>(5, 6) = 1;
  auto m1 = DownsampleMask(mask, 1);
  ASSERT_TRUE(m1.ok());
  ASSERT_EQ(m1->size(), cv::Size(4, 4));
  EXPECT_EQ(m1->at<std::uint8_t>(2, 3), 255);
  EXPECT_EQ(cv::countNonZero(*m1), 1);
  auto m2 = DownsampleMask(mask, 2);
  ASSERT_TRUE(m2.ok());
  EXPECT_EQ(m2->at<std::uint8_t>(1, 1), 255);
  EXPECT_FALSE(DownsampleMask(cv::Mat(), 1).ok());
  EXPECT_FALSE(DownsampleMask(mask, -1).ok());
  EXPECT_FALSE(DownsampleMask(cv::Mat::zeros(4, 4, CV_32FC1), 1).ok());
}

}  // namespace
}  // namespace rover::dl::stereo
