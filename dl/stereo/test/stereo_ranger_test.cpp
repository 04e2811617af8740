#include "rover/dl/stereo/stereo_ranger.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "test_cameras.hpp"
#include "test_images.hpp"

namespace rover::dl::stereo {
namespace {

constexpr double kFocal = 100.0;    // [px]
constexpr double kBaseline = 0.2;   // [m]
constexpr double kDisparity = 8.0;  // [px] of the synthetic pair: range f B / d = 2.5 m

msg::CameraModelFields Camera(double y) { return testing::ForwardCamera(y, kFocal); }

// A rectified pair of constant disparity with the rig's models; keeps the pixels.
struct Frame {
  Frame() {
    testing::ConstantDisparityPair(testing::Texture(3), cv::Size(128, 96), kDisparity, &left,
                                   &right);
    msg.stamp = Time::FromSeconds(4.0);
    msg.camera = msg::CameraId::kFrontHazcam;
    msg.width = 128;
    msg.height = 96;
    msg.left_model = Camera(kBaseline / 2);
    msg.right_model = Camera(-kBaseline / 2);
    msg.left = std::span<const std::uint8_t>(left.data, left.total());
    msg.right = std::span<const std::uint8_t>(right.data, right.total());
  }
  cv::Mat left, right;
  msg::StereoFrame msg;
};

StereoRangerOptions Options() {
  StereoRangerOptions o;
  o.num_disparities = 32;
  o.blob_min_area = 0;
  o.num_threads = 1;
  return o;
}

msg::PoseHistory PosesAround(double t) {
  msg::PoseHistory h;
  for (double s : {t - 0.1, t + 0.1}) {
    msg::PoseSample p;
    p.stamp = Time::FromSeconds(s);
    p.site_from_rover.translation() = Eigen::Vector3d(10.0 * s, 0.0, 0.0);
    EXPECT_TRUE(h.Add(p).ok());
  }
  return h;
}

TEST(StereoRanger, RangesAPairIntoTheRoverFrameWithThePoseAtCapture) {
  StereoRanger ranger(Options());
  const Frame f;
  const msg::PoseHistory poses = PosesAround(4.0);
  auto image = ranger.Range(f.msg, 7, {&poses, Seconds(0.5), true});
  ASSERT_TRUE(image.ok()) << image.status().ToString();
  EXPECT_EQ(image->stamp, f.msg.stamp);
  EXPECT_EQ(image->request_id, 7u);
  EXPECT_EQ(image->camera, msg::CameraId::kFrontHazcam);
  EXPECT_EQ(image->width, 128);
  EXPECT_EQ(image->height, 96);
  EXPECT_TRUE(image->CheckSizes().ok());
  EXPECT_NEAR(image->rover_pose.translation().x(), 40.0, 1e-6);  // interpolated at 4.0 s
  std::vector<double> x;
  int valid = 0;
  for (std::size_t i = 0; i < image->valid.size(); ++i) {
    if (image->valid[i] == 0) {
      EXPECT_EQ(image->disparity[i], -1.0F);
      EXPECT_TRUE(std::isnan(image->xyz[3 * i]));
      continue;
    }
    ++valid;
    EXPECT_NEAR(image->disparity[i], kDisparity, 0.5);
    x.push_back(image->xyz[3 * i]);
  }
  EXPECT_GT(valid, static_cast<int>(image->valid.size() / 2));
  std::nth_element(x.begin(), x.begin() + static_cast<long>(x.size() / 2), x.end());
  // Range f B / d = 2.5 m ahead of the camera at rover x = 0.5.
  EXPECT_NEAR(x[x.size() / 2], 0.5 + kFocal * kBaseline / kDisparity, 0.05);
  EXPECT_GT(ranger.last_timings().total_ms, 0.0);
  // The rectification is computed once per model pair.
  ASSERT_TRUE(ranger.Range(f.msg, 8, {&poses, Seconds(0.5), true}).ok());
  EXPECT_EQ(ranger.setup_cache().misses(), 1u);
  EXPECT_EQ(ranger.setup_cache().hits(), 1u);
}

TEST(StereoRanger, WithoutAPoseAtCaptureNoImageUnlessNotRequired) {
  StereoRanger ranger(Options());
  const Frame f;
  const msg::PoseHistory old = PosesAround(1.0);
  auto r = ranger.Range(f.msg, 1, {&old, Seconds(0.5), true});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("rover pose at capture"), std::string::npos)
      << r.status().message();
  auto identity = ranger.Range(f.msg, 1, {&old, Seconds(0.5), false});
  ASSERT_TRUE(identity.ok()) << identity.status().ToString();
  EXPECT_TRUE(identity->rover_pose.isApprox(Eigen::Isometry3d::Identity()));
}

TEST(StereoRanger, BadModelsAreErrorsNamingThem) {
  StereoRanger ranger(Options());
  const msg::PoseHistory poses = PosesAround(4.0);
  Frame missing;
  const int w = missing.msg.left_model.width, h = missing.msg.left_model.height;
  missing.msg.left_model = msg::CameraModelFields{};
  missing.msg.left_model.width = w;
  missing.msg.left_model.height = h;
  auto r = ranger.Range(missing.msg, 1, {&poses, Seconds(0.5), true});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("left model"), std::string::npos) << r.status().message();
  Frame coincident;
  coincident.msg.right_model = coincident.msg.left_model;
  r = ranger.Range(coincident.msg, 1, {&poses, Seconds(0.5), true});
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("stereo rectification"), std::string::npos)
      << r.status().message();
}

TEST(StereoRanger, DerivesTheSearchRangeFromTheNearestRange) {
  StereoRangerOptions o = Options();
  o.num_disparities = 0;
  o.min_range_m = 1.0;  // ceil(f B / 1 m) + 2 = 22 px at full resolution: enough for 8 px
  StereoRanger ranger(o);
  const Frame f;
  const msg::PoseHistory poses = PosesAround(4.0);
  auto image = ranger.Range(f.msg, 1, {&poses, Seconds(0.5), true});
  ASSERT_TRUE(image.ok()) << image.status().ToString();
  EXPECT_GT(std::count(image->valid.begin(), image->valid.end(), 1), 128 * 96 / 2);
}

TEST(StereoRangerOptions, ValidateAndParameters) {
  EXPECT_TRUE(StereoRangerOptions().Validate().ok());
  StereoRangerOptions o;
  o.max_range_m = 0.2;
  EXPECT_NE(o.Validate().message().find("stereo.max_range_m 0.2 must be larger"),
            std::string::npos);
  o = StereoRangerOptions();
  o.window = 8;
  const Status even = o.Validate();
  ASSERT_FALSE(even.ok());
  EXPECT_NE(even.message().find("stereo parameters"), std::string::npos) << even.message();
  ParamSet ps("dl-stereo");
  DeclareParams<StereoRangerOptions>(ps, "");
  EXPECT_EQ(ps.GetString("stereo.prefilter"), "log");
  EXPECT_EQ(ps.GetInt("rectification_cache_size"), 4);
  ASSERT_TRUE(ps.LoadYamlString("stereo:\n  prefilter: dog\n  window: 9\n", "s.yaml").ok());
  auto read = ReadParams<StereoRangerOptions>(ps, "");
  ASSERT_TRUE(read.ok()) << read.status().ToString();
  EXPECT_EQ(read->prefilter, PrefilterKind::kDifferenceOfGaussians);
  EXPECT_EQ(read->Pipeline(40).correlator.window, 9);
  EXPECT_EQ(read->Pipeline(40).correlator.num_disparities, 40);
}

}  // namespace
}  // namespace rover::dl::stereo
