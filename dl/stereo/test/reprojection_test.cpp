#include "rover/dl/stereo/reprojection.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace rover::dl::stereo {
namespace {

RectifiedStereoModel SmallModel() {
  RectifiedStereoModel m;
  m.focal_px = 100;
  m.cx = 10;
  m.cy = 5;
  m.baseline_m = 0.5;
  return m;
}

// Camera looking along the rover's +x: camera z = rover x, camera x = rover -y, camera y =
// rover -z; mounted 1.2 m up and 0.3 m forward.
Eigen::Isometry3d ForwardCamera() {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() << 0, 0, 1,  //
      -1, 0, 0,           //
      0, -1, 0;
  t.translation() = Eigen::Vector3d(0.3, 0.0, 1.2);
  return t;
}

TEST(ReprojectTest, PointsAndRangeInTheRoverFrame) {
  DisparityImage d;
  d.Reset({21, 11}, PixelStatus::kValid);
  d.disparity.setTo(10.0f);  // Z = 100 * 0.5 / 10 = 5 m
  cv::Mat range, xyz;
  ASSERT_TRUE(
      Reproject(SmallModel(), ForwardCamera(), ReprojectionOptions(), &d, &range, &xyz).ok());
  ASSERT_EQ(range.type(), CV_32FC1);
  ASSERT_EQ(xyz.type(), CV_32FC3);
  // Principal point: straight ahead, 5 m in front of the camera.
  const cv::Vec3f p = xyz.at<cv::Vec3f>(5, 10);
  EXPECT_NEAR(p[0], 5.3, 1e-5);
  EXPECT_NEAR(p[1], 0.0, 1e-5);
  EXPECT_NEAR(p[2], 1.2, 1e-5);
  EXPECT_NEAR(range.at<float>(5, 10), 5.0, 1e-5);
  // Pixel to the right (u = 20) and below (v = 10): camera X = 0.5, Y = 0.25.
  const cv::Vec3f q = xyz.at<cv::Vec3f>(10, 20);
  EXPECT_NEAR(q[0], 5.3, 1e-5);
  EXPECT_NEAR(q[1], -0.5, 1e-5);  // right of the camera = rover -y
  EXPECT_NEAR(q[2], 1.2 - 0.25, 1e-5);
  EXPECT_NEAR(range.at<float>(10, 20), std::sqrt(25.0 + 0.25 + 0.0625), 1e-5);
  EXPECT_EQ(d.CountValid(), 21 * 11);
}

TEST(ReprojectTest, InvalidPixelsAndRangeLimits) {
  DisparityImage d;
  d.Reset({3, 1}, PixelStatus::kValid);
  d.disparity.at<float>(0, 0) = 50.0f;  // 1 m
  d.disparity.at<float>(0, 1) = 0.0f;   // at infinity
  d.status.at<std::uint8_t>(0, 2) = static_cast<std::uint8_t>(PixelStatus::kBlob);
  d.disparity.at<float>(0, 2) = kInvalidDisparity;
  ReprojectionOptions o;
  o.min_range_m = 2.0;
  cv::Mat range, xyz;
  ASSERT_TRUE(Reproject(SmallModel(), Eigen::Isometry3d::Identity(), o, &d, &range, &xyz).ok());
  EXPECT_EQ(d.status.at<std::uint8_t>(0, 0), static_cast<int>(PixelStatus::kRangeLimit));
  EXPECT_EQ(d.status.at<std::uint8_t>(0, 1), static_cast<int>(PixelStatus::kRangeLimit));
  EXPECT_EQ(d.status.at<std::uint8_t>(0, 2), static_cast<int>(PixelStatus::kBlob));
  for (int u = 0; u < 3; ++u) {
    EXPECT_TRUE(std::isnan(range.at<float>(0, u)));
    EXPECT_TRUE(std::isnan(xyz.at<cv::Vec3f>(0, u)[0]));
  }
  // doffs shifts the disparity of infinity.
  RectifiedStereoModel m = SmallModel();
  m.doffs_px = 5.0;
  DisparityImage e;
  e.Reset({1, 1}, PixelStatus::kValid);
  e.disparity.setTo(5.0f);  // d + doffs = 10 -> 5 m
  ASSERT_TRUE(
      Reproject(m, Eigen::Isometry3d::Identity(), ReprojectionOptions(), &e, &range, nullptr).ok());
  EXPECT_NEAR(range.at<float>(0, 0), std::hypot(5.0, 5.0 * 10 / 100, 5.0 * 5 / 100), 1e-5);
}

TEST(ReprojectTest, BadInputs) {
  DisparityImage d;
  d.Reset({3, 3}, PixelStatus::kValid);
  cv::Mat range;
  Eigen::Isometry3d bad = Eigen::Isometry3d::Identity();
  bad.linear() *= 2.0;
  Status s = Reproject(SmallModel(), bad, ReprojectionOptions(), &d, &range, nullptr);
  EXPECT_NE(s.message().find("rotation"), std::string::npos) << s.message();
  RectifiedStereoModel m = SmallModel();
  m.baseline_m = 0;
  EXPECT_FALSE(Reproject(m, Eigen::Isometry3d::Identity(), {}, &d, &range, nullptr).ok());
  ReprojectionOptions o;
  o.max_range_m = -1;
  EXPECT_FALSE(o.Validate().ok());
  EXPECT_FALSE(Reproject(SmallModel(), Eigen::Isometry3d::Identity(), o, &d, &range, nullptr).ok());
  DisparityImage empty;
  EXPECT_FALSE(
      Reproject(SmallModel(), Eigen::Isometry3d::Identity(), {}, &empty, &range, nullptr).ok());
  StereoCamera cam;
  cam.model = SmallModel();
  EXPECT_TRUE(cam.Validate().ok());
  cam.rover_from_camera = bad;
  EXPECT_FALSE(cam.Validate().ok());
}

}  // namespace
}  // namespace rover::dl::stereo
