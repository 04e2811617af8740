#include "rover/dl/stereo/image_prep.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/imgproc.hpp>

#include "test_images.hpp"

namespace rover::dl::stereo {
namespace {

TEST(ConvertTo8BitTest, RejectsBadInput) {
  cv::Mat out;
  EXPECT_EQ(ConvertTo8Bit(cv::Mat(), 255, 1, &out).code(), StatusCode::kInvalidArgument);
  const Status s = ConvertTo8Bit(cv::Mat(4, 4, CV_32FC1), 255, 1, &out);
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("CV_32FC1"), std::string::npos) << s.message();
  EXPECT_FALSE(ConvertTo8Bit(cv::Mat(4, 4, CV_8UC3), 255, 1, &out).ok());
  EXPECT_FALSE(ConvertTo8Bit(cv::Mat(4, 4, CV_8UC1), 0, 1, &out).ok());
  EXPECT_FALSE(ConvertTo8Bit(cv::Mat(4, 4, CV_8UC1), 255, 0.0, &out).ok());
}

TEST(ConvertTo8BitTest, ScalesSixteenBitAndAppliesGamma) {
  cv::Mat in16 = (cv::Mat_<std::uint16_t>(1, 4) << 0, 1023, 4095, 65535);
  cv::Mat out;
  ASSERT_TRUE(ConvertTo8Bit(in16, 4095, 1.0, &out).ok());
  ASSERT_EQ(out.type(), CV_8UC1);
  EXPECT_EQ(out.at<std::uint8_t>(0, 0), 0);
  EXPECT_NEAR(out.at<std::uint8_t>(0, 1), 64, 1);
  EXPECT_EQ(out.at<std::uint8_t>(0, 2), 255);
  EXPECT_EQ(out.at<std::uint8_t>(0, 3), 255);  // above the white level: clipped
  cv::Mat in8 = (cv::Mat_<std::uint8_t>(1, 3) << 0, 64, 255);
  ASSERT_TRUE(ConvertTo8Bit(in8, 255, 2.0, &out).ok());
  EXPECT_EQ(out.at<std::uint8_t>(0, 0), 0);
  EXPECT_NEAR(out.at<std::uint8_t>(0, 1), std::lround(255 * std::sqrt(64 / 255.0)), 1);
  EXPECT_EQ(out.at<std::uint8_t>(0, 2), 255);
  ASSERT_TRUE(ConvertTo8Bit(in8, 255, 1.0, &out).ok());
  EXPECT_EQ(cv::norm(out, in8, cv::NORM_INF), 0.0);
}

TEST(Downsample2xTest, AveragesBlocksAndFloorsOddSizes) {
  cv::Mat in = (cv::Mat_<std::uint8_t>(3, 5) << 0, 2, 10, 20, 99,  //
                4, 6, 30, 40, 99,                                  //
                99, 99, 99, 99, 99);
  cv::Mat out;
  ASSERT_TRUE(Downsample2x(in, &out).ok());
  ASSERT_EQ(out.size(), cv::Size(2, 1));
  EXPECT_EQ(out.at<std::uint8_t>(0, 0), 3);
  EXPECT_EQ(out.at<std::uint8_t>(0, 1), 25);
  EXPECT_FALSE(Downsample2x(cv::Mat(1, 8, CV_8UC1), &out).ok());
  EXPECT_FALSE(Downsample2x(cv::Mat(), &out).ok());
  EXPECT_FALSE(Downsample2x(cv::Mat(4, 4, CV_16UC1), &out).ok());
}

TEST(PrefilterTest, OptionsValidate) {
  PrefilterOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.cap = 0;
  EXPECT_FALSE(o.Validate().ok());
  o = PrefilterOptions();
  o.sigma = -1;
  EXPECT_NE(o.Validate().message().find("sigma"), std::string::npos);
  o = PrefilterOptions();
  o.kind = PrefilterKind::kDifferenceOfGaussians;
  o.sigma_outer = 0.5;  // below sigma
  EXPECT_FALSE(o.Validate().ok());
  o.sigma_outer = 2.0;
  EXPECT_TRUE(o.Validate().ok());
  o.gain = 0;
  EXPECT_FALSE(o.Validate().ok());
}

TEST(PrefilterTest, ParsesKindNames) {
  for (auto k : {PrefilterKind::kNone, PrefilterKind::kLaplacianOfGaussian,
                 PrefilterKind::kDifferenceOfGaussians}) {
    auto parsed = ParsePrefilterKind(PrefilterKindName(k));
    ASSERT_TRUE(parsed.ok());
    EXPECT_EQ(*parsed, k);
  }
  EXPECT_FALSE(ParsePrefilterKind("sobel").ok());
}

TEST(PrefilterTest, ConstantImageGivesZeroResponse) {
  for (auto kind : {PrefilterKind::kLaplacianOfGaussian, PrefilterKind::kDifferenceOfGaussians}) {
    PrefilterOptions o;
    o.kind = kind;
    cv::Mat in(20, 30, CV_8UC1, cv::Scalar(173)), out;
    ASSERT_TRUE(Prefilter(in, o, &out).ok());
    double lo, hi;
    cv::minMaxLoc(out, &lo, &hi);
    EXPECT_EQ(lo, o.cap);
    EXPECT_EQ(hi, o.cap);
  }
}

TEST(PrefilterTest, LogMatchesFloatReferenceAndBrightDotIsPositive) {
  const testing::Texture tex(5);
  cv::Mat in(40, 50, CV_8UC1);
  for (int v = 0; v < in.rows; ++v) {
    for (int u = 0; u < in.cols; ++u)
      in.at<std::uint8_t>(v, u) = testing::Texture::Quantise(tex(u, v));
  }
  PrefilterOptions o;
  o.sigma = 1.0;
  o.gain = 2.0;
  o.cap = 31;
  cv::Mat out;
  ASSERT_TRUE(Prefilter(in, o, &out).ok());
  ASSERT_EQ(out.type(), CV_8UC1);
  // Float reference of -gain * Laplacian(G * I), quantised the same way.
  cv::Mat f, blurred, lap;
  in.convertTo(f, CV_32F);
  cv::GaussianBlur(f, blurred, cv::Size(7, 7), 1.0, 1.0, cv::BORDER_REFLECT_101);
  cv::Laplacian(blurred, lap, CV_32F, 1, 1.0, 0.0, cv::BORDER_REFLECT_101);
  int max_diff = 0;
  for (int v = 0; v < in.rows; ++v) {
    for (int u = 0; u < in.cols; ++u) {
      const double ref = std::clamp(std::round(-2.0 * lap.at<float>(v, u)), -31.0, 31.0) + 31.0;
      max_diff = std::max(max_diff, std::abs(out.at<std::uint8_t>(v, u) - static_cast<int>(ref)));
    }
  }
  EXPECT_LE(max_diff, 1);
  double lo, hi;
  cv::minMaxLoc(out, &lo, &hi);
  EXPECT_GE(lo, 0);
  EXPECT_LE(hi, 2 * o.cap);
  cv::Mat dot(15, 15, CV_8UC1, cv::Scalar(50));
  dot.at<std::uint8_t>(7, 7) = 200;
  ASSERT_TRUE(Prefilter(dot, o, &out).ok());
  EXPECT_GT(out.at<std::uint8_t>(7, 7), o.cap);
  EXPECT_EQ(out.at<std::uint8_t>(0, 0), o.cap);
}

TEST(PrefilterTest, NoneCopiesAndBadInputFails) {
  PrefilterOptions o;
  o.kind = PrefilterKind::kNone;
  cv::Mat in(3, 3, CV_8UC1, cv::Scalar(200)), out;
  ASSERT_TRUE(Prefilter(in, o, &out).ok());
  EXPECT_EQ(cv::norm(in, out, cv::NORM_INF), 0.0);
  EXPECT_FALSE(Prefilter(cv::Mat(), o, &out).ok());
  EXPECT_FALSE(Prefilter(cv::Mat(3, 3, CV_16UC1), o, &out).ok());
  o.cap = 100;
  EXPECT_FALSE(Prefilter(in, o, &out).ok());
}

}  // namespace
}  // namespace rover::dl::stereo
