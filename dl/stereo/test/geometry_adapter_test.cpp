#include "rover/dl/stereo/geometry_adapter.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "rover/base/units.hpp"
#include "rover/dl/stereo/pipeline.hpp"
#include "test_images.hpp"

namespace rover::dl::stereo {
namespace {

// Camera (x right, y down, z forward) at `position` in the rover frame, pitched down by `pitch`
// and turned left by `yaw`.
Eigen::Isometry3d CameraPose(double pitch, double yaw, const Eigen::Vector3d& position) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d z(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw),
                          -std::sin(pitch));
  const Eigen::Vector3d x(std::sin(yaw), -std::cos(yaw), 0.0);
  t.linear().col(0) = x;
  t.linear().col(1) = z.cross(x);
  t.linear().col(2) = z;
  t.translation() = position;
  return t;
}

geometry::CameraModel Pinhole(const Eigen::Isometry3d& pose, double k1) {
  geometry::PinholeRadial p;
  p.fx = p.fy = 200.0;
  p.cx = 99.5;
  p.cy = 74.5;
  p.k1 = k1;
  p.pose = pose;
  p.width = 200;
  p.height = 150;
  auto m = geometry::CameraModel::Create(p);
  EXPECT_TRUE(m.ok()) << m.status().ToString();
  return *m;
}

// Raw image of the textured ground z = 0 through a calibrated camera (3x3 supersampling).
cv::Mat RenderGround(const geometry::CameraModel& cam) {
  const testing::Texture tex(33, 6.0, 40.0);
  cv::Mat img(cam.height(), cam.width(), CV_8UC1);
  for (int v = 0; v < img.rows; ++v) {
    for (int u = 0; u < img.cols; ++u) {
      double sum = 0.0;
      for (int i = -1; i <= 1; ++i) {
        for (int j = -1; j <= 1; ++j) {
          const auto ray = cam.Unproject(Eigen::Vector2d(u + i / 3.0, v + j / 3.0));
          if (!ray || ray->direction.z() >= -1e-9) {
            sum += 128.0;
            continue;
          }
          const Eigen::Vector3d p = ray->origin + (-ray->origin.z() / ray->direction.z()) *
                                                      ray->direction;
          sum += tex(100.0 * p.x(), 100.0 * p.y());
        }
      }
      img.at<std::uint8_t>(v, u) = testing::Texture::Quantise(sum / 9.0);
    }
  }
  return img;
}

TEST(GeometryAdapterTest, ParallelPairGivesItsOwnModelAndPose) {
  const Eigen::Isometry3d left_pose = CameraPose(30 * kDegree, 0.0, {0.0, 0.1, 1.0});
  const Eigen::Isometry3d right_pose = CameraPose(30 * kDegree, 0.0, {0.0, -0.1, 1.0});
  auto setup = MakeStereoSetup(Pinhole(left_pose, 0.0), Pinhole(right_pose, 0.0));
  ASSERT_TRUE(setup.ok()) << setup.status().ToString();
  const RectifiedStereoModel& m = setup->camera.model;
  EXPECT_NEAR(m.focal_px, 200.0, 1e-9);
  EXPECT_NEAR(m.cx, 99.5, 1e-9);
  EXPECT_NEAR(m.cy, 74.5, 1e-9);
  EXPECT_NEAR(m.baseline_m, 0.2, 1e-12);
  EXPECT_NEAR(m.doffs_px, 0.0, 1e-9);
  EXPECT_TRUE(setup->camera.rover_from_camera.isApprox(left_pose, 1e-9));
  // Already rectified: the maps are the identity.
  EXPECT_NEAR(setup->maps.left_x.at<float>(40, 30), 30.0f, 1e-3);
  EXPECT_NEAR(setup->maps.right_y.at<float>(40, 30), 40.0f, 1e-3);
  EXPECT_EQ(setup->maps.raw_size, cv::Size(200, 150));
}

// Toed-in cameras with barrel distortion: rectify through core/geometry's maps, correlate, and
// the points land on the ground (z = 0 in the rover frame).
TEST(GeometryAdapterTest, DistortedToedInPairRangesTheGround) {
  const auto left = Pinhole(CameraPose(30 * kDegree, -1.5 * kDegree, {0.0, 0.1, 1.0}), -0.08);
  const auto right = Pinhole(CameraPose(30 * kDegree, 1.5 * kDegree, {0.0, -0.1, 1.0}), -0.08);
  auto setup = MakeStereoSetup(left, right);
  ASSERT_TRUE(setup.ok()) << setup.status().ToString();
  StereoOptions o;
  o.correlator.num_disparities = 48;
  auto pipe = StereoPipeline::Create(o, setup->camera);
  ASSERT_TRUE(pipe.ok()) << pipe.status().ToString();
  StereoInput in;
  in.left = RenderGround(left);
  in.right = RenderGround(right);
  in.rectification = &setup->maps;
  StereoOutput out;
  ASSERT_TRUE(pipe->Process(in, &out).ok());
  std::vector<double> height;
  for (int v = 0; v < out.xyz_rover.rows; ++v) {
    for (int u = 0; u < out.xyz_rover.cols; ++u) {
      const float z = out.xyz_rover.at<cv::Vec3f>(v, u)[2];
      if (std::isfinite(z)) height.push_back(std::abs(z));
    }
  }
  ASSERT_GT(height.size(), 0.6 * 200 * 150);
  std::nth_element(height.begin(), height.begin() + height.size() * 95 / 100, height.end());
  EXPECT_LT(height[height.size() * 95 / 100], 0.03);
}

TEST(GeometryAdapterTest, Errors) {
  const auto left = Pinhole(CameraPose(30 * kDegree, 0.0, {0.0, 0.1, 1.0}), 0.0);
  const auto right = Pinhole(CameraPose(30 * kDegree, 0.0, {0.0, -0.1, 1.0}), 0.0);
  geometry::RectifyOptions no_maps;
  no_maps.compute_maps = false;
  auto pair = geometry::RectifyStereoPair(left, right, no_maps);
  ASSERT_TRUE(pair.ok());
  auto s = StereoSetupFromGeometry(*pair, cv::Size(200, 150));
  EXPECT_NE(s.status().message().find("no remap tables"), std::string::npos)
      << s.status().message();
  geometry::RectifiedPair swapped = *pair;
  swapped.left = left;  // a pinhole, not the rectified CAHV
  EXPECT_FALSE(StereoSetupFromGeometry(swapped, cv::Size(200, 150)).ok());
  geometry::PinholeRadial small;
  small.fx = small.fy = 100;
  small.width = 100;
  small.height = 75;
  auto other = geometry::CameraModel::Create(small);
  ASSERT_TRUE(other.ok());
  auto e = MakeStereoSetup(left, *other);
  EXPECT_NE(e.status().message().find("one size"), std::string::npos) << e.status().message();
  // Cameras at the same place cannot be rectified.
  EXPECT_FALSE(MakeStereoSetup(left, left).ok());
}

}  // namespace
}  // namespace rover::dl::stereo
