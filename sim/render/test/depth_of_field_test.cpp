#include "rover/sim/render/depth_of_field.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace rover::sim::render {
namespace {

cv::Mat Checkerboard(int size, int cell) {
  cv::Mat m(size, size, CV_32FC1);
  for (int r = 0; r < size; ++r) {
    for (int c = 0; c < size; ++c) m.at<float>(r, c) = ((r / cell + c / cell) % 2) ? 0.4F : 0.1F;
  }
  return m;
}

double Detail(const cv::Mat& m, const cv::Rect& roi) {
  cv::Mat lap;
  cv::Laplacian(m(roi), lap, CV_32F);
  cv::Scalar mean, sd;
  cv::meanStdDev(lap, mean, sd);
  return sd[0];
}

TEST(DepthOfFieldTest, BlurFollowsTheThinLens) {
  DepthOfField dof;  // s = 0.06 m, K = 3 px m
  EXPECT_DOUBLE_EQ(dof.BlurDiameterPx(0.06), 0.0);
  EXPECT_NEAR(dof.BlurDiameterPx(0.066), 3.0 * 0.006 / (0.066 * 0.06), 1e-12);
  EXPECT_NEAR(dof.BlurDiameterPx(0.054), 3.0 * 0.006 / (0.054 * 0.06), 1e-12);
  EXPECT_DOUBLE_EQ(dof.BlurDiameterPx(0.0), 4.0 * dof.max_sigma_px);  // no surface: the cap
}

TEST(DepthOfFieldTest, InFocusStaysSharpAndDefocusBlurs) {
  DepthOfField dof;
  const cv::Mat board = Checkerboard(128, 8);
  cv::Mat depth(board.size(), CV_32FC1, cv::Scalar(0.06));
  const cv::Mat sharp = ApplyDepthOfField(board, depth, dof);
  EXPECT_LT(cv::norm(sharp, board, cv::NORM_INF), 1e-6);  // float depth: a sub-micron blur
  // Left half in focus, right half 1.5 cm beyond: c = 3 * 0.015 / (0.075 * 0.06) = 10 px.
  depth(cv::Rect(64, 0, 64, 128)).setTo(0.075);
  const cv::Mat half = ApplyDepthOfField(board, depth, dof);
  const double left = Detail(half, cv::Rect(8, 8, 40, 112));
  const double right = Detail(half, cv::Rect(80, 8, 40, 112));
  EXPECT_GT(left, 5.0 * right);
  // The blur matches a Gaussian of sigma c / 4 = 2.5 px away from the seam.
  cv::Mat expected;
  cv::GaussianBlur(board, expected, cv::Size(0, 0), 2.5, 2.5, cv::BORDER_REFLECT);
  const cv::Rect inner(84, 16, 32, 96);
  EXPECT_LT(cv::norm(half(inner), expected(inner), cv::NORM_INF), 0.01);
  // Blur grows with defocus, on both sides of the focus.
  double last = 1e9;
  for (double z : {0.06, 0.063, 0.068, 0.08, 0.12}) {
    depth.setTo(z);
    const double d = Detail(ApplyDepthOfField(board, depth, dof), cv::Rect(16, 16, 96, 96));
    EXPECT_LT(d, last) << "z = " << z;
    last = d;
  }
  depth.setTo(0.054);
  EXPECT_LT(Detail(ApplyDepthOfField(board, depth, dof), cv::Rect(16, 16, 96, 96)),
            0.8 * Detail(board, cv::Rect(16, 16, 96, 96)));
}

TEST(DepthOfFieldTest, BadOptionsAreNamed) {
  DepthOfField dof;
  dof.focus_distance = 0.0;
  EXPECT_NE(dof.Validate().message().find("depth_of_field.focus_distance"), std::string::npos);
  dof = {};
  dof.near = 0.07;
  EXPECT_NE(dof.Validate().message().find("depth_of_field.near"), std::string::npos);
  dof = {};
  dof.blur_constant = -1.0;
  EXPECT_NE(dof.Validate().message().find("depth_of_field.blur_constant"), std::string::npos);
  dof = {};
  dof.max_sigma_px = 0.5;
  EXPECT_NE(dof.Validate().message().find("depth_of_field.max_sigma_px"), std::string::npos);
  EXPECT_TRUE(DepthOfField{}.Validate().ok());
}

}  // namespace
}  // namespace rover::sim::render
