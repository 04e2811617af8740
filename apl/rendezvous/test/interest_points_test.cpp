// Förstner interest points on drawn images: a checkerboard's inner corners are found (and only
// they), an edge and a flat image give none, bad input is named.
#include "rover/apl/rendezvous/interest_points.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

namespace rover::apl::rendezvous {
namespace {

cv::Mat Checkerboard(int cells, int cell_px) {
  cv::Mat im(cells * cell_px, cells * cell_px, CV_8UC1);
  for (int r = 0; r < im.rows; ++r) {
    for (int c = 0; c < im.cols; ++c) {
      im.at<std::uint8_t>(r, c) = ((r / cell_px + c / cell_px) % 2) ? 200 : 40;
    }
  }
  return im;
}

TEST(ForstnerPointsTest, FindsTheCheckerboardsInnerCornersOnly) {
  const int cell = 16;
  const cv::Mat im = Checkerboard(8, cell);
  ForstnerOptions o;
  o.max_points = 100;
  auto pts = ForstnerPoints(im, cv::Rect(0, 0, im.cols, im.rows), o);
  ASSERT_TRUE(pts.ok()) << pts.status().message();
  // Inner corners lie between pixels (cell * k - 0.5); the operator answers a pixel of the
  // window's plateau about it (no sub-pixel estimate), within 2 px.
  int inner = 0;
  for (const InterestPoint& p : *pts) {
    const double kx = (p.pixel.x() + 0.5) / cell, ky = (p.pixel.y() + 0.5) / cell;
    EXPECT_LT(std::abs(kx - std::round(kx)) * cell, 2.01) << p.pixel.transpose();
    EXPECT_LT(std::abs(ky - std::round(ky)) * cell, 2.01) << p.pixel.transpose();
    EXPECT_GE(p.roundness, o.min_roundness);
    inner += (std::round(kx) >= 1 && std::round(kx) <= 7 && std::round(ky) >= 1 && std::round(ky) <= 7);
  }
  EXPECT_EQ(inner, 49);
  EXPECT_EQ(static_cast<int>(pts->size()), 49);
  for (std::size_t i = 1; i < pts->size(); ++i) EXPECT_GE((*pts)[i - 1].weight, (*pts)[i].weight);
}

TEST(ForstnerPointsTest, AnEdgeOrAFlatImageHasNoPoints) {
  cv::Mat edge(64, 64, CV_8UC1, cv::Scalar(40));
  edge(cv::Rect(32, 0, 32, 64)).setTo(200);
  auto pts = ForstnerPoints(edge, cv::Rect(0, 0, 64, 64));
  ASSERT_TRUE(pts.ok());
  EXPECT_TRUE(pts->empty()) << pts->size() << " points on a straight edge";
  const cv::Mat flat(64, 64, CV_8UC1, cv::Scalar(90));
  pts = ForstnerPoints(flat, cv::Rect(0, 0, 64, 64));
  ASSERT_TRUE(pts.ok());
  EXPECT_TRUE(pts->empty());
}

TEST(ForstnerPointsTest, TheRegionLimitsThePointsAndMaxPointsKeepsTheStrongest) {
  const cv::Mat im = Checkerboard(8, 16);
  ForstnerOptions o;
  o.max_points = 3;
  auto pts = ForstnerPoints(im, cv::Rect(10, 10, 30, 30), o);
  ASSERT_TRUE(pts.ok());
  ASSERT_EQ(pts->size(), 3u);
  for (const InterestPoint& p : *pts) {
    EXPECT_GE(p.pixel.x(), 10);
    EXPECT_LT(p.pixel.x(), 40);
  }
}

TEST(ForstnerPointsTest, BadInputIsNamed) {
  const cv::Mat im = Checkerboard(4, 16);
  ForstnerOptions o;
  o.min_roundness = 1.5;
  auto pts = ForstnerPoints(im, cv::Rect(0, 0, 64, 64), o);
  ASSERT_FALSE(pts.ok());
  EXPECT_NE(pts.status().message().find("forstner.min_roundness"), std::string::npos);
  pts = ForstnerPoints(cv::Mat(), cv::Rect(0, 0, 64, 64));
  EXPECT_FALSE(pts.ok());
  pts = ForstnerPoints(im, cv::Rect(500, 500, 20, 20));
  ASSERT_FALSE(pts.ok());
  EXPECT_NE(pts.status().message().find("region"), std::string::npos) << pts.status().message();
  cv::Mat colour(64, 64, CV_8UC3);
  EXPECT_FALSE(ForstnerPoints(colour, cv::Rect(0, 0, 64, 64)).ok());
}

}  // namespace
}  // namespace rover::apl::rendezvous
