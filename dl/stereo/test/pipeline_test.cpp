#include "rover/dl/stereo/pipeline.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <vector>

#include "rover/dl/stereo/disparity_io.hpp"
#include "rover/dl/stereo/evaluation.hpp"
#include "test_images.hpp"

namespace rover::dl::stereo {
namespace {

constexpr double kFocal = 200.0, kBaseline = 0.2, kHeight = 1.0, kPitch = 0.5;

// Cones thresholds: measured values (README) plus margin.
constexpr double kConesMaxBad1px = 0.036;  // measured 0.0314
constexpr double kConesMaxBad2px = 0.026;  // measured 0.0219
constexpr double kConesMinDensity = 0.76;  // measured 0.7826

struct GroundScene {
  cv::Mat left, right, truth;
  StereoCamera camera;
};

GroundScene MakeGround(cv::Size size = {200, 150}) {
  GroundScene s;
  s.camera.rover_from_camera = testing::GroundPlanePair(size, kFocal, kBaseline, kHeight, kPitch,
                                                        &s.left, &s.right, &s.truth);
  s.camera.model.focal_px = kFocal;
  s.camera.model.baseline_m = kBaseline;
  s.camera.model.cx = 0.5 * (size.width - 1);
  s.camera.model.cy = 0.5 * (size.height - 1);
  return s;
}

TEST(StereoOptionsTest, ValidateNamesTheField) {
  StereoOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.pyramid_levels = 5;
  EXPECT_NE(o.Validate().message().find("pyramid_levels"), std::string::npos);
  o = StereoOptions();
  o.correlator.window = 4;
  EXPECT_NE(o.Validate().message().find("correlator.window"), std::string::npos);
  o = StereoOptions();
  o.filters.blob_min_area = -3;
  EXPECT_NE(o.Validate().message().find("filters.blob_min_area"), std::string::npos);
  o = StereoOptions();
  o.prefilter.kind = PrefilterKind::kNone;
  o.correlator.window = 13;
  EXPECT_FALSE(o.Validate().ok());  // raw 8-bit values would overflow 16-bit costs
  o = StereoOptions();
  o.gamma = 0;
  EXPECT_FALSE(StereoPipeline::Create(o).ok());
  StereoCamera cam;  // zero focal length
  EXPECT_FALSE(StereoPipeline::Create(StereoOptions(), cam).ok());
}

// Disparity of a ground plane at known geometry matches f B / Z within 0.5 px, and the points
// lie on the ground (z = 0 in the rover frame).
TEST(StereoPipelineTest, GroundPlaneMatchesStereoGeometry) {
  const GroundScene s = MakeGround();
  StereoOptions o;
  o.correlator.num_disparities = 48;
  auto pipe = StereoPipeline::Create(o, s.camera);
  ASSERT_TRUE(pipe.ok()) << pipe.status().ToString();
  StereoInput in;
  in.left = s.left;
  in.right = s.right;
  StereoOutput out;
  ASSERT_TRUE(pipe->Process(in, &out).ok());
  ASSERT_EQ(out.disparity.size(), s.left.size());
  std::vector<double> err, height;
  for (int v = 0; v < s.left.rows; ++v) {
    for (int u = 0; u < s.left.cols; ++u) {
      const float d = out.disparity.disparity.at<float>(v, u);
      if (std::isnan(d)) continue;
      err.push_back(std::abs(d - s.truth.at<float>(v, u)));
      height.push_back(std::abs(out.xyz_rover.at<cv::Vec3f>(v, u)[2]));
    }
  }
  const double total = s.left.rows * s.left.cols;
  EXPECT_GT(err.size(), 0.8 * total);
  const auto within = std::count_if(err.begin(), err.end(), [](double e) { return e < 0.5; });
  EXPECT_GT(within, 0.99 * err.size());
  std::nth_element(err.begin(), err.begin() + err.size() / 2, err.end());
  EXPECT_LT(err[err.size() / 2], 0.1);
  std::nth_element(height.begin(), height.begin() + height.size() * 95 / 100, height.end());
  EXPECT_LT(height[height.size() * 95 / 100], 0.03);  // 95 % within 3 cm of the ground
  EXPECT_EQ(out.counts[0], static_cast<int>(cv::countNonZero(out.valid)));
  ASSERT_TRUE(out.model.has_value());
  EXPECT_EQ(out.range.type(), CV_32FC1);
}

TEST(StereoPipelineTest, PyramidLevelHalvesSizeAndDisparity) {
  const GroundScene s = MakeGround();
  StereoOptions o;
  o.pyramid_levels = 1;
  o.correlator.num_disparities = 24;
  o.filters.blob_min_area = 10;
  auto pipe = StereoPipeline::Create(o, s.camera);
  ASSERT_TRUE(pipe.ok());
  StereoInput in;
  in.left = s.left;
  in.right = s.right;
  StereoOutput out;
  ASSERT_TRUE(pipe->Process(in, &out).ok());
  ASSERT_EQ(out.disparity.size(), cv::Size(100, 75));
  EXPECT_EQ(out.level, 1);
  EXPECT_DOUBLE_EQ(out.model->focal_px, kFocal / 2);
  int n = 0, good = 0;
  for (int v = 0; v < 75; ++v) {
    for (int u = 0; u < 100; ++u) {
      const float d = out.disparity.disparity.at<float>(v, u);
      if (std::isnan(d)) continue;
      // Level-1 pixel (u, v) covers full-resolution centre (2u + 0.5, 2v + 0.5).
      const double t =
          0.5 * (s.truth.at<float>(2 * v, 2 * u) + s.truth.at<float>(2 * v + 1, 2 * u + 1));
      ++n;
      good += std::abs(2 * d - t) < 1.0;
    }
  }
  EXPECT_GT(n, 0.7 * 75 * 100);
  EXPECT_GT(good, 0.97 * n);
}

TEST(StereoPipelineTest, RectificationMapsAreApplied) {
  const GroundScene s = MakeGround();
  // Raw images: the rectified ones shifted by (4, 3) px inside a larger frame.
  const cv::Size raw_size(s.left.cols + 8, s.left.rows + 6);
  cv::Mat raw_l(raw_size, CV_8UC1, cv::Scalar(0)), raw_r(raw_size, CV_8UC1, cv::Scalar(0));
  s.left.copyTo(raw_l(cv::Rect(4, 3, s.left.cols, s.left.rows)));
  s.right.copyTo(raw_r(cv::Rect(4, 3, s.left.cols, s.left.rows)));
  RectificationMaps maps;
  maps.raw_size = raw_size;
  maps.left_x.create(s.left.size(), CV_32FC1);
  maps.left_y.create(s.left.size(), CV_32FC1);
  for (int v = 0; v < s.left.rows; ++v) {
    for (int u = 0; u < s.left.cols; ++u) {
      maps.left_x.at<float>(v, u) = static_cast<float>(u + 4);
      maps.left_y.at<float>(v, u) = static_cast<float>(v + 3);
    }
  }
  maps.right_x = maps.left_x;
  maps.right_y = maps.left_y;
  StereoOptions o;
  o.correlator.num_disparities = 48;
  auto pipe = StereoPipeline::Create(o);
  ASSERT_TRUE(pipe.ok());
  StereoInput direct, via_maps;
  direct.left = s.left;
  direct.right = s.right;
  via_maps.left = raw_l;
  via_maps.right = raw_r;
  via_maps.rectification = &maps;
  StereoOutput a, b;
  ASSERT_TRUE(pipe->Process(direct, &a).ok());
  ASSERT_TRUE(pipe->Process(via_maps, &b).ok());
  EXPECT_EQ(cv::norm(a.disparity.status, b.disparity.status, cv::NORM_INF), 0.0);
  EXPECT_TRUE(a.range.empty());  // no camera, no range
  // Raw images of the wrong size for the maps.
  via_maps.left = s.left;
  via_maps.right = s.right;
  EXPECT_FALSE(pipe->Process(via_maps, &b).ok());
}

TEST(StereoPipelineTest, VehicleAndWheelMasks) {
  const GroundScene s = MakeGround();
  StereoOptions o;
  o.correlator.num_disparities = 48;
  o.pyramid_levels = 1;
  auto pipe = StereoPipeline::Create(o);
  ASSERT_TRUE(pipe.ok());
  StereoInput in;
  in.left = s.left;
  in.right = s.right;
  in.vehicle_mask = cv::Mat::zeros(s.left.size(), CV_8UC1);
  in.vehicle_mask(cv::Rect(0, 120, 200, 30)).setTo(255);  // rover deck across the bottom
  in.wheel_polygons = {{{150.f, 60.f}, {190.f, 60.f}, {190.f, 110.f}, {150.f, 110.f}}};
  StereoOutput out;
  ASSERT_TRUE(pipe->Process(in, &out).ok());
  const auto st = [&](int v, int u) {
    return static_cast<PixelStatus>(out.disparity.status.at<std::uint8_t>(v, u));
  };
  EXPECT_EQ(st(70, 50), PixelStatus::kVehicle);  // full-res row 140
  EXPECT_EQ(st(42, 85), PixelStatus::kWheel);    // full-res (170, 84)
  EXPECT_EQ(st(40, 50), PixelStatus::kValid);
  EXPECT_GT(out.counts[static_cast<int>(PixelStatus::kVehicle)], 100 * 14);
  // Wrong mask size and a degenerate polygon are errors.
  in.vehicle_mask = cv::Mat::zeros(10, 10, CV_8UC1);
  Status e = pipe->Process(in, &out);
  EXPECT_NE(e.message().find("vehicle mask"), std::string::npos) << e.message();
  in.vehicle_mask = cv::Mat();
  in.wheel_polygons = {{{1.f, 1.f}, {2.f, 2.f}}};
  EXPECT_FALSE(pipe->Process(in, &out).ok());
}

TEST(StereoPipelineTest, SixteenBitInputWithGamma) {
  const GroundScene s = MakeGround({120, 90});
  cv::Mat l16, r16;
  s.left.convertTo(l16, CV_16U, 16);  // 12-bit data
  s.right.convertTo(r16, CV_16U, 16);
  StereoOptions o;
  o.white_level = 4095;
  o.gamma = 1.5;
  o.correlator.num_disparities = 32;
  auto pipe = StereoPipeline::Create(o);
  ASSERT_TRUE(pipe.ok());
  StereoInput in;
  in.left = l16;
  in.right = r16;
  StereoOutput out;
  ASSERT_TRUE(pipe->Process(in, &out).ok());
  EXPECT_GT(out.counts[0], 0.5 * 120 * 90);
}

TEST(StereoPipelineTest, BadInputsReturnStatus) {
  auto pipe = StereoPipeline::Create(StereoOptions());
  ASSERT_TRUE(pipe.ok());
  StereoOutput out;
  const cv::Mat img(100, 160, CV_8UC1, cv::Scalar(9));
  const auto run = [&](const cv::Mat& l, const cv::Mat& r) {
    StereoInput in;
    in.left = l;
    in.right = r;
    return pipe->Process(in, &out);
  };
  EXPECT_NE(run(cv::Mat(), img).message().find("left image is empty"), std::string::npos);
  EXPECT_NE(run(img, cv::Mat()).message().find("right image is empty"), std::string::npos);
  EXPECT_NE(run(img, cv::Mat(100, 160, CV_32FC1)).message().find("CV_32FC1"), std::string::npos);
  EXPECT_NE(run(cv::Mat(100, 160, CV_8UC3), img).message().find("single channel"),
            std::string::npos);
  EXPECT_NE(run(img, cv::Mat(100, 161, CV_8UC1)).message().find("equal sizes"), std::string::npos);
  EXPECT_NE(run(img, cv::Mat(100, 160, CV_16UC1)).message().find("equal types"), std::string::npos);
  EXPECT_NE(run(cv::Mat(4, 4, CV_8UC1), cv::Mat(4, 4, CV_8UC1)).message().find("window"),
            std::string::npos);
  EXPECT_FALSE(pipe->Process(StereoInput(), nullptr).ok());
  StereoOptions far;
  far.correlator.min_disparity = 40;  // disparities 40..103 in a 40 px wide image
  auto pfar = StereoPipeline::Create(far);
  ASSERT_TRUE(pfar.ok());
  StereoInput narrow;
  narrow.left = narrow.right = cv::Mat(100, 40, CV_8UC1, cv::Scalar(0));
  const Status e = pfar->Process(narrow, &out);
  EXPECT_NE(e.message().find("disparity range [40, 103]"), std::string::npos) << e.message();
  StereoOptions deep;
  deep.pyramid_levels = 4;
  auto p4 = StereoPipeline::Create(deep);
  ASSERT_TRUE(p4.ok());
  StereoInput in;
  in.left = img;
  in.right = img;
  Status s = p4->Process(in, &out);
  EXPECT_NE(s.message().find("pyramid level 4"), std::string::npos) << s.message();
}

// Middlebury Cones: bad-pixel rate (> 1 px, non-occluded) and density against fixed thresholds
// measured with stereo-bench (see README) plus a margin.
TEST(StereoPipelineTest, MiddleburyConesAccuracy) {
  const std::string dir = testing::SharedDataDir() + "/middlebury-cones";
  if (!std::filesystem::exists(dir + "/left.png")) {
    GTEST_SKIP() << "Middlebury Cones not found under '" << dir << "' (set ROVER_SHARED_DATA_DIR)";
  }
  auto left = LoadGrayImage(dir + "/left.png");
  auto right = LoadGrayImage(dir + "/right.png");
  ASSERT_TRUE(left.ok() && right.ok());
  const cv::Mat gt = cv::imread(dir + "/disp_left.tif", cv::IMREAD_UNCHANGED);
  const cv::Mat nonocc = cv::imread(dir + "/occlusion.png", cv::IMREAD_GRAYSCALE);
  ASSERT_EQ(gt.type(), CV_32FC1);
  StereoOptions o;  // defaults: 7x7 window, disparities [0, 64)
  auto pipe = StereoPipeline::Create(o);
  ASSERT_TRUE(pipe.ok());
  StereoInput in;
  in.left = *left;
  in.right = *right;
  StereoOutput out;
  ASSERT_TRUE(pipe->Process(in, &out).ok());
  auto score = ScoreDisparity(out.disparity.disparity, gt, nonocc);
  ASSERT_TRUE(score.ok());
  RecordProperty("bad_1px", std::to_string(score->bad_1px));
  RecordProperty("density", std::to_string(score->density));
  EXPECT_LT(score->bad_1px, kConesMaxBad1px);
  EXPECT_LT(score->bad_2px, kConesMaxBad2px);
  EXPECT_GT(score->density, kConesMinDensity);
}

}  // namespace
}  // namespace rover::dl::stereo
