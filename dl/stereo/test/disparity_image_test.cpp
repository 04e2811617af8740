#include "rover/dl/stereo/disparity_image.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

namespace rover::dl::stereo {
namespace {

TEST(DisparityImageTest, ResetFillsNanAndStatus) {
  DisparityImage d;
  d.Reset(cv::Size(5, 3), PixelStatus::kBorder);
  ASSERT_EQ(d.size(), cv::Size(5, 3));
  EXPECT_EQ(d.disparity.type(), CV_32FC1);
  EXPECT_EQ(d.status.type(), CV_8UC1);
  EXPECT_TRUE(std::isnan(d.disparity.at<float>(2, 4)));
  EXPECT_EQ(d.CountStatus()[static_cast<int>(PixelStatus::kBorder)], 15);
  EXPECT_EQ(d.CountValid(), 0);
}

TEST(DisparityImageTest, RejectKeepsFirstReason) {
  DisparityImage d;
  d.Reset(cv::Size(4, 4), PixelStatus::kValid);
  d.disparity.setTo(3.0f);
  d.Reject(1, 2, PixelStatus::kBlob);
  d.Reject(1, 2, PixelStatus::kOverhang);  // already invalid: keeps kBlob
  EXPECT_EQ(d.status.at<std::uint8_t>(1, 2), static_cast<int>(PixelStatus::kBlob));
  EXPECT_TRUE(std::isnan(d.disparity.at<float>(1, 2)));
  EXPECT_EQ(d.disparity.at<float>(1, 1), 3.0f);
  EXPECT_EQ(d.CountValid(), 15);
  const cv::Mat mask = d.ValidMask();
  EXPECT_EQ(mask.at<std::uint8_t>(1, 2), 0);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 0), 255);
  EXPECT_EQ(cv::countNonZero(mask), 15);
}

TEST(DisparityImageTest, StatusNamesAreDistinct) {
  std::set<std::string> names;
  for (int i = 0; i < kNumPixelStatus; ++i) {
    names.insert(PixelStatusName(static_cast<PixelStatus>(i)));
  }
  EXPECT_EQ(static_cast<int>(names.size()), kNumPixelStatus);
  EXPECT_STREQ(PixelStatusName(PixelStatus::kLeftRight), "left_right");
  EXPECT_STREQ(PixelStatusName(static_cast<PixelStatus>(200)), "unknown");
}

}  // namespace
}  // namespace rover::dl::stereo
