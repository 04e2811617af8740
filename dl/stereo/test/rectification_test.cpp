#include "rover/dl/stereo/rectification.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "test_images.hpp"

namespace rover::dl::stereo {
namespace {

RectifiedStereoModel Model() {
  RectifiedStereoModel m;
  m.focal_px = 400;
  m.cx = 160.5;
  m.cy = 120.25;
  m.baseline_m = 0.3;
  m.doffs_px = 2.0;
  return m;
}

TEST(RectifiedStereoModelTest, ValidateNamesTheField) {
  RectifiedStereoModel m = Model();
  EXPECT_TRUE(m.Validate().ok());
  m.focal_px = 0;
  EXPECT_NE(m.Validate().message().find("focal_px"), std::string::npos);
  m = Model();
  m.baseline_m = -0.1;
  EXPECT_NE(m.Validate().message().find("baseline_m"), std::string::npos);
  m = Model();
  m.cx = std::nan("");
  EXPECT_FALSE(m.Validate().ok());
}

TEST(RectifiedStereoModelTest, DepthAndDisparityAreInverse) {
  const RectifiedStereoModel m = Model();
  EXPECT_NEAR(m.DepthFromDisparity(m.DisparityFromDepth(3.7)), 3.7, 1e-12);
  EXPECT_NEAR(m.DepthFromDisparity(10.0), 400 * 0.3 / 12.0, 1e-12);
  EXPECT_TRUE(std::isinf(m.DepthFromDisparity(-2.0)));
}

TEST(RectifiedStereoModelTest, QRoundTripAndAgreesWithOpenCv) {
  const RectifiedStereoModel m = Model();
  auto back = RectifiedStereoModel::FromQ(m.ToQ());
  ASSERT_TRUE(back.ok()) << back.status().ToString();
  EXPECT_NEAR(back->focal_px, m.focal_px, 1e-9);
  EXPECT_NEAR(back->cx, m.cx, 1e-9);
  EXPECT_NEAR(back->cy, m.cy, 1e-9);
  EXPECT_NEAR(back->baseline_m, m.baseline_m, 1e-9);
  EXPECT_NEAR(back->doffs_px, m.doffs_px, 1e-9);
  // OpenCV's reprojectImageTo3D with our Q gives Z = f B / (d + doffs), X = (u - cx) Z / f.
  cv::Mat disp(3, 4, CV_32FC1, cv::Scalar(10.0f)), xyz;
  cv::reprojectImageTo3D(disp, xyz, cv::Mat(m.ToQ()));
  const cv::Vec3f p = xyz.at<cv::Vec3f>(2, 3);
  const double z = m.DepthFromDisparity(10.0);
  EXPECT_NEAR(p[2], z, 1e-4);
  EXPECT_NEAR(p[0], (3 - m.cx) * z / m.focal_px, 1e-4);
  EXPECT_NEAR(p[1], (2 - m.cy) * z / m.focal_px, 1e-4);
}

TEST(RectifiedStereoModelTest, FromQRejectsOtherMatrices) {
  cv::Matx44d q = Model().ToQ();
  q(3, 2) = -q(3, 2);
  EXPECT_FALSE(RectifiedStereoModel::FromQ(q).ok());
  q = Model().ToQ();
  q(0, 1) = 0.5;
  EXPECT_FALSE(RectifiedStereoModel::FromQ(q).ok());
  EXPECT_FALSE(RectifiedStereoModel::FromQ(cv::Matx44d::zeros()).ok());
}

TEST(RectifiedStereoModelTest, DownsampledFollowsBlockCentres) {
  const RectifiedStereoModel m = Model();
  const RectifiedStereoModel d = m.Downsampled(2);
  EXPECT_DOUBLE_EQ(d.focal_px, 100.0);
  EXPECT_DOUBLE_EQ(d.doffs_px, 0.5);
  // Full-resolution pixel centre u maps to (u + 0.5) / 4 - 0.5 at level 2.
  EXPECT_DOUBLE_EQ(d.cx, (m.cx + 0.5) / 4 - 0.5);
  EXPECT_DOUBLE_EQ(d.cy, (m.cy + 0.5) / 4 - 0.5);
  // Depth is level independent.
  EXPECT_NEAR(d.DepthFromDisparity(m.DisparityFromDepth(5.0) / 4), 5.0, 1e-12);
}

RectificationMaps ShiftMaps(cv::Size rect, cv::Size raw, float dx_l, float dx_r, float dy) {
  RectificationMaps maps;
  maps.raw_size = raw;
  maps.left_x.create(rect, CV_32FC1);
  maps.left_y.create(rect, CV_32FC1);
  maps.right_x.create(rect, CV_32FC1);
  maps.right_y.create(rect, CV_32FC1);
  for (int v = 0; v < rect.height; ++v) {
    for (int u = 0; u < rect.width; ++u) {
      maps.left_x.at<float>(v, u) = static_cast<float>(u) + dx_l;
      maps.right_x.at<float>(v, u) = static_cast<float>(u) + dx_r;
      maps.left_y.at<float>(v, u) = maps.right_y.at<float>(v, u) = static_cast<float>(v) + dy;
    }
  }
  return maps;
}

TEST(RectifyTest, UndoesAKnownShift) {
  const testing::Texture tex(3);
  const cv::Size raw_size(40, 30), rect_size(30, 20);
  cv::Mat raw(raw_size, CV_8UC1);
  for (int v = 0; v < raw.rows; ++v) {
    for (int u = 0; u < raw.cols; ++u)
      raw.at<std::uint8_t>(v, u) = testing::Texture::Quantise(tex(u, v));
  }
  const RectificationMaps maps = ShiftMaps(rect_size, raw_size, 5, 2, 3);
  ASSERT_TRUE(maps.Validate().ok());
  cv::Mat l, r;
  ASSERT_TRUE(Rectify(maps, raw, raw, &l, &r).ok());
  ASSERT_EQ(l.size(), rect_size);
  EXPECT_EQ(cv::norm(l, raw(cv::Rect(5, 3, 30, 20)), cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(r, raw(cv::Rect(2, 3, 30, 20)), cv::NORM_INF), 0.0);
  // Fixed-point maps from cv::convertMaps work the same.
  RectificationMaps fixed = maps;
  cv::convertMaps(maps.left_x, maps.left_y, fixed.left_x, fixed.left_y, CV_16SC2);
  cv::convertMaps(maps.right_x, maps.right_y, fixed.right_x, fixed.right_y, CV_16SC2);
  ASSERT_TRUE(fixed.Validate().ok());
  ASSERT_TRUE(Rectify(fixed, raw, raw, &l, &r).ok());
  EXPECT_EQ(cv::norm(l, raw(cv::Rect(5, 3, 30, 20)), cv::NORM_INF), 0.0);
}

TEST(RectifyTest, ErrorsNameTheProblem) {
  const RectificationMaps maps = ShiftMaps({30, 20}, {40, 30}, 0, 0, 0);
  cv::Mat raw(30, 40, CV_8UC1, cv::Scalar(0)), l, r;
  Status s = Rectify(maps, raw, cv::Mat(31, 40, CV_8UC1), &l, &r);
  EXPECT_NE(s.message().find("right raw image is 40x31"), std::string::npos) << s.message();
  s = Rectify(maps, cv::Mat(), raw, &l, &r);
  EXPECT_NE(s.message().find("left raw image is empty"), std::string::npos) << s.message();
  s = Rectify(maps, cv::Mat(30, 40, CV_32FC1), raw, &l, &r);
  EXPECT_NE(s.message().find("CV_32FC1"), std::string::npos) << s.message();
  RectificationMaps bad = maps;
  bad.right_x = cv::Mat(10, 10, CV_32FC1);
  s = bad.Validate();
  EXPECT_NE(s.message().find("right"), std::string::npos) << s.message();
  bad = maps;
  bad.left_y = cv::Mat(20, 30, CV_64FC1);
  EXPECT_FALSE(bad.Validate().ok());
  bad = maps;
  bad.raw_size = cv::Size();
  EXPECT_FALSE(bad.Validate().ok());
  EXPECT_FALSE(RectificationMaps().Validate().ok());
}

}  // namespace
}  // namespace rover::dl::stereo
