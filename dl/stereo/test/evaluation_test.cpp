#include "rover/dl/stereo/evaluation.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::dl::stereo {
namespace {

TEST(ScoreDisparityTest, CountsBadPixelsOnNonOccludedKnownTruth) {
  const float nan = std::nanf("");
  cv::Mat est = (cv::Mat_<float>(2, 4) << 10.0f, 11.5f, 14.0f, nan,  //
                 10.0f, 10.0f, 10.0f, 10.0f);
  cv::Mat gt = (cv::Mat_<float>(2, 4) << 10.0f, 10.0f, 10.0f, 10.0f,  //
                0.0f, 10.0f, 10.0f, 10.0f);                           // 0 = unknown
  cv::Mat noc = (cv::Mat_<std::uint8_t>(2, 4) << 255, 255, 255, 255,  //
                 255, 255, 255, 0);                                   // last pixel occluded
  auto s = ScoreDisparity(est, gt, noc);
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  EXPECT_EQ(s->pixels, 8);
  EXPECT_EQ(s->nonoccluded, 6);           // known truth and visible
  EXPECT_EQ(s->evaluated, 5);             // minus the NaN
  EXPECT_DOUBLE_EQ(s->bad_1px, 2.0 / 5);  // 1.5 and 4.0 errors
  EXPECT_DOUBLE_EQ(s->bad_2px, 1.0 / 5);
  EXPECT_DOUBLE_EQ(s->mean_abs_error, 5.5 / 5);
  EXPECT_DOUBLE_EQ(s->density, 7.0 / 8);
  EXPECT_DOUBLE_EQ(s->density_nonocc, 5.0 / 6);
  // A level-1 estimate scaled by 2.
  auto half = ScoreDisparity(est / 2, gt, noc, 2.0);
  ASSERT_TRUE(half.ok());
  EXPECT_DOUBLE_EQ(half->bad_1px, s->bad_1px);
}

TEST(ScoreDisparityTest, RejectsBadInputs) {
  const cv::Mat f(3, 3, CV_32FC1, cv::Scalar(1));
  EXPECT_FALSE(ScoreDisparity(cv::Mat(), f, cv::Mat()).ok());
  EXPECT_FALSE(ScoreDisparity(cv::Mat(3, 3, CV_16SC1), f, cv::Mat()).ok());
  EXPECT_FALSE(ScoreDisparity(f, cv::Mat(3, 4, CV_32FC1), cv::Mat()).ok());
  EXPECT_FALSE(ScoreDisparity(f, f, cv::Mat(3, 3, CV_32FC1)).ok());
  EXPECT_TRUE(ScoreDisparity(f, f, cv::Mat()).ok());
}

TEST(FromOpenCvDisparityTest, ConvertsFixedPointAndInvalid) {
  cv::Mat fixed = (cv::Mat_<std::int16_t>(1, 3) << 160, -16, 8);
  auto f = FromOpenCvDisparity(fixed, 0);
  ASSERT_TRUE(f.ok());
  EXPECT_FLOAT_EQ(f->at<float>(0, 0), 10.0f);
  EXPECT_TRUE(std::isnan(f->at<float>(0, 1)));
  EXPECT_FLOAT_EQ(f->at<float>(0, 2), 0.5f);
  EXPECT_FALSE(FromOpenCvDisparity(cv::Mat(1, 1, CV_32FC1), 0).ok());
  EXPECT_FALSE(FromOpenCvDisparity(cv::Mat(), 0).ok());
}

}  // namespace
}  // namespace rover::dl::stereo
