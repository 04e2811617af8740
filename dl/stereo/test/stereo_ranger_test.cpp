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

constexpr double kRangerFocal = 100.0;    // [px]
constexpr double kRangerBaseline = 0.2;   // [m]
constexpr double kRangerDisparity = 8.0;  // [px] of the synthetic pair: range f B / d = 2.5 m

msg::CameraModelFields RangerCamera(double y) { return testing::ForwardCamera(y, kRangerFocal); }

// A rectified pair of constant disparity with the rig's models; keeps the pixels.
struct Frame {
  Frame() {
    testing::ConstantDisparityPair(testing::Texture(3), cv::Size(128, 96), kRangerDisparity, &left,
                                   &right);
    msg.stamp = Time::FromSeconds(4.0);
    msg.camera = msg::CameraId::kFrontHazcam;
    msg.width = 128;
    msg.height = 96;
    msg.left_model = RangerCamera(kRangerBaseline / 2);
    msg.right_model = RangerCamera(-kRangerBaseline / 2);
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
    EXPECT_NEAR(image->disparity[i], kRangerDisparity, 0.5);
    x.push_back(image->xyz[3 * i]);
  }
  EXPECT_GT(valid, static_cast<int>(image->valid.size() / 2));
  std::nth_element(x.begin(), x.begin() + static_cast<long>(x.size() / 2), x.end());
  // Range f B / d = 2.5 m ahead of the camera at rover x = 0.5.
  EXPECT_NEAR(x[x.size() / 2], 0.5 + kRangerFocal * kRangerBaseline / kRangerDisparity, 0.05);
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

TEST(StereoRanger, VehicleMaskRemovesPointsBehindTheRover) {
  // A "body" between the camera (rover (0.5, +-0.1, 1.0), looking along x) and the wall at x = 3
  // hides the left part of the wall.
  hwconfig::RoverDescription rover;
  rover.body_centre = Eigen::Vector3d(1.5, 0.8, 1.0);
  rover.body_size = Eigen::Vector3d(0.4, 0.8, 3.0);
  StereoRanger plain(Options());
  StereoRanger masked(Options(), VehicleMask(rover, VehicleMaskOptions()));
  const Frame f;
  const msg::PoseHistory poses = PosesAround(4.0);
  auto all = plain.Range(f.msg, 1, {&poses, Seconds(0.5), true});
  auto kept = masked.Range(f.msg, 1, {&poses, Seconds(0.5), true});
  ASSERT_TRUE(all.ok() && kept.ok());
  const auto n_all = std::count(all->valid.begin(), all->valid.end(), 1);
  const auto n_kept = std::count(kept->valid.begin(), kept->valid.end(), 1);
  EXPECT_GT(masked.last_masked(), 500);
  EXPECT_EQ(n_kept + masked.last_masked(), n_all);
  EXPECT_EQ(plain.last_masked(), 0);
  const Eigen::Vector3d eye(0.5, kRangerBaseline / 2, 1.0);
  const Eigen::AlignedBox3d body = VehicleMask(rover, VehicleMaskOptions()).volumes().back().box;
  for (std::size_t i = 0; i < kept->valid.size(); ++i) {
    if (kept->valid[i] == 0) continue;
    const Eigen::Vector3d p(kept->xyz[3 * i], kept->xyz[3 * i + 1], kept->xyz[3 * i + 2]);
    ASSERT_FALSE(SegmentMeetsBox(eye, p, body)) << p.transpose();
  }
}

TEST(StereoRanger, FixedPixelMaskRemovesItsPixels) {
  StereoRanger ranger(Options());
  cv::Mat left_half(3, 4, CV_8UC1, cv::Scalar(0));  // any size: scaled to 128 x 96
  left_half.colRange(0, 2).setTo(255);
  ASSERT_TRUE(ranger.SetPixelMask(msg::CameraId::kFrontHazcam, left_half).ok());
  EXPECT_FALSE(ranger.SetPixelMask(msg::CameraId::kRearHazcam, cv::Mat(2, 2, CV_32FC1)).ok());
  EXPECT_FALSE(ranger.SetPixelMask(static_cast<msg::CameraId>(7), left_half).ok());
  const Frame f;
  const msg::PoseHistory poses = PosesAround(4.0);
  auto image = ranger.Range(f.msg, 1, {&poses, Seconds(0.5), true});
  ASSERT_TRUE(image.ok()) << image.status().ToString();
  int left_valid = 0, right_valid = 0;
  for (int v = 0; v < image->height; ++v) {
    for (int u = 0; u < image->width; ++u) {
      const bool ok = image->valid[static_cast<std::size_t>(v * image->width + u)] != 0;
      (u < image->width / 2 ? left_valid : right_valid) += ok ? 1 : 0;
    }
  }
  EXPECT_EQ(left_valid, 0);
  EXPECT_GT(right_valid, 128 * 96 / 4);
  EXPECT_GT(ranger.last_masked(), 128 * 96 / 4);  // most of the left half
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
