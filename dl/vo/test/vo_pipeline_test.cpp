#include "rover/dl/vo/vo_pipeline.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <utility>

#include "rover/geometry/camera_model.hpp"
#include "synthetic_scene.hpp"

namespace rover::dl::vo {
namespace {

// The test's site frame is the renderer's world frame (x right, y down, z forward, ground at
// y = 1.5 m) and its rover frame has the same axes: the pipeline's geometry is frame-agnostic.
// The left camera is pitched down on the rover (synthetic_scene.hpp CameraPose); the right one
// sits `baseline` along the left camera's x axis.
StereoCamera Camera() {
  StereoCamera c;
  c.width = 256;
  c.height = 192;
  c.fx = c.fy = 200.0;
  c.cx = 127.5;
  c.cy = 95.5;
  c.baseline = 0.2;
  return c;
}

Eigen::Isometry3d Mount(double pitch) {
  return testing::CameraPose(Eigen::Isometry3d::Identity(), pitch);
}

msg::CameraModelFields Model(const StereoCamera& c, const Eigen::Isometry3d& pose) {
  geometry::PinholeRadial p;
  p.fx = c.fx;
  p.fy = c.fy;
  p.cx = c.cx;
  p.cy = c.cy;
  p.width = c.width;
  p.height = c.height;
  p.pose = pose;
  auto model = geometry::CameraModel::Create(*geometry::ToCahv(p), c.width, c.height);
  EXPECT_TRUE(model.ok()) << model.status().ToString();
  return *msg::CameraModelFieldsFromModel(*model);
}

Eigen::Isometry3d Forward(double z) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() = Eigen::Vector3d(0.0, 0.0, z);
  return t;
}

// A rendered frame at `t` with the rover at `site_from_rover`; keeps the pixels.
struct Frame {
  Frame(double t, const Eigen::Isometry3d& site_from_rover, double pitch = 0.5) {
    const StereoCamera cam = Camera();
    const Eigen::Isometry3d mount = Mount(pitch);
    const testing::SyntheticScene scene;
    const auto seed = static_cast<std::uint64_t>(t * 100);
    left = testing::RenderView(cam, scene, site_from_rover * mount, false, 10 + 2 * seed);
    right = testing::RenderView(cam, scene, site_from_rover * mount, true, 11 + 2 * seed);
    msg.stamp = Time::FromSeconds(t);
    msg.camera = msg::CameraId::kFrontHazcam;
    msg.width = cam.width;
    msg.height = cam.height;
    msg.left_model = Model(cam, mount);
    msg.right_model = Model(cam, mount * Eigen::Translation3d(cam.baseline, 0.0, 0.0));
    msg.left = std::span<const std::uint8_t>(left.data, left.total());
    msg.right = std::span<const std::uint8_t>(right.data, right.total());
  }
  cv::Mat left, right;
  msg::StereoFrame msg;
};

msg::PoseSample Pose(double t, const Eigen::Isometry3d& site_from_rover) {
  msg::PoseSample s;
  s.stamp = Time::FromSeconds(t);
  s.site_from_rover = site_from_rover;
  s.odometer = site_from_rover.translation().norm();
  return s;
}

class VoPipelineTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(poses_.Add(Pose(1.0, Eigen::Isometry3d::Identity())).ok());
    ASSERT_TRUE(poses_.Add(Pose(2.0, Forward(0.3))).ok());
    ASSERT_TRUE(poses_.Add(Pose(3.0, Forward(0.6))).ok());
  }
  const Duration max_age_ = Seconds(0.5);
  msg::PoseHistory poses_;
  VoPipeline pipeline_{VoPipelineOptions()};
};

TEST_F(VoPipelineTest, TheFirstPairIsTheReferenceThenStepsMeasureTheMotion) {
  EXPECT_FALSE(pipeline_.BadInput(Time::FromSeconds(1.0), poses_, max_age_).has_value());
  const Frame a(1.0, Eigen::Isometry3d::Identity());
  auto first = pipeline_.Process(a.msg, poses_, max_age_);
  ASSERT_TRUE(first.ok()) << first.status().ToString();
  EXPECT_EQ(first->estimate.status, MotionStatus::kNoReference);
  EXPECT_FALSE(first->relative_pose.has_value());
  ASSERT_TRUE(first->mark.has_value());
  EXPECT_EQ(first->mark->stamp, Time::FromSeconds(1.0));
  EXPECT_TRUE(pipeline_.has_reference());

  const Frame b(2.0, Forward(0.3));
  auto step = pipeline_.Process(b.msg, poses_, max_age_);
  ASSERT_TRUE(step.ok()) << step.status().ToString();
  ASSERT_TRUE(step->relative_pose.has_value()) << step->estimate.message;
  const msg::RelativePose& r = *step->relative_pose;
  EXPECT_EQ(r.status, msg::RelativePoseStatus::kConverged) << step->estimate.message;
  EXPECT_EQ(r.source, msg::MotionSource::kVisualOdometry);
  EXPECT_EQ(r.t_from, Time::FromSeconds(1.0));
  EXPECT_EQ(r.t_to, Time::FromSeconds(2.0));
  EXPECT_EQ(r.stamp, r.t_to);
  EXPECT_EQ(r.features, static_cast<std::uint32_t>(step->estimate.inliers));
  EXPECT_GT(r.features, 10u);
  // The rover moved 0.3 m along its z (forward here): in the rover frame at t_from.
  EXPECT_LT((r.delta.translation() - Eigen::Vector3d(0, 0, 0.3)).norm(), 0.02)
      << r.delta.translation().transpose();
  EXPECT_LT(RotationAngle(r.delta.linear()), 0.01);
  EXPECT_GT(r.covariance(2, 2), 0.0);
}

TEST_F(VoPipelineTest, ABadFrameKeepsTheReferenceAndReportsThePrior) {
  const Frame a(1.0, Eigen::Isometry3d::Identity());
  ASSERT_TRUE(pipeline_.Process(a.msg, poses_, max_age_).ok());
  Frame bad(2.0, Forward(0.3));
  bad.msg.right_model = bad.msg.left_model;  // coincident cameras: no baseline
  auto r = pipeline_.Process(bad.msg, poses_, max_age_);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("stereo rectification"), std::string::npos)
      << r.status().message();
  EXPECT_TRUE(pipeline_.has_reference());
  const auto report = pipeline_.BadInput(bad.msg.stamp, poses_, max_age_);
  ASSERT_TRUE(report.has_value());
  EXPECT_EQ(report->status, msg::RelativePoseStatus::kBadInput);
  EXPECT_EQ(report->features, 0u);
  EXPECT_EQ(report->t_from, Time::FromSeconds(1.0));
  // The prior: the dl/pose change between the capture times.
  EXPECT_LT((report->delta.translation() - Eigen::Vector3d(0, 0, 0.3)).norm(), 1e-9);
  // Without poses the prior is vague (zero motion).
  const msg::PoseHistory none;
  const auto vague = pipeline_.BadInput(bad.msg.stamp, none, max_age_);
  ASSERT_TRUE(vague.has_value());
  EXPECT_LT(vague->delta.translation().norm(), 1e-12);
  EXPECT_NEAR(std::sqrt(vague->covariance(0, 0)), OdometryPriorOptions().vague_translation_sigma,
              1e-12);
}

TEST_F(VoPipelineTest, ACameraThatMovedOnTheRoverStartsANewReference) {
  const Frame a(1.0, Eigen::Isometry3d::Identity());
  ASSERT_TRUE(pipeline_.Process(a.msg, poses_, max_age_).ok());
  const Frame tilted(2.0, Forward(0.3), 0.6);  // the camera pitched further down
  auto r = pipeline_.Process(tilted.msg, poses_, max_age_);
  ASSERT_TRUE(r.ok()) << r.status().ToString();
  EXPECT_EQ(r->estimate.status, MotionStatus::kNoReference);
  EXPECT_FALSE(r->relative_pose.has_value());
  // The next step from it measures the motion again.
  const Frame c(3.0, Forward(0.6), 0.6);
  auto step = pipeline_.Process(c.msg, poses_, max_age_);
  ASSERT_TRUE(step.ok()) << step.status().ToString();
  ASSERT_TRUE(step->relative_pose.has_value());
  EXPECT_EQ(step->relative_pose->t_from, Time::FromSeconds(2.0));
  EXPECT_LT((step->relative_pose->delta.translation() - Eigen::Vector3d(0, 0, 0.3)).norm(), 0.02);
  pipeline_.Reset();
  EXPECT_FALSE(pipeline_.has_reference());
}

TEST(VoPipelineOptions, StatusesAndParameters) {
  EXPECT_EQ(RelativePoseStatusOf(MotionStatus::kConverged), msg::RelativePoseStatus::kConverged);
  EXPECT_EQ(RelativePoseStatusOf(MotionStatus::kLimitsFailed),
            msg::RelativePoseStatus::kLimitsFailed);
  EXPECT_EQ(RelativePoseStatusOf(MotionStatus::kNoReference), msg::RelativePoseStatus::kBadInput);
  ParamSet ps("dl-vo");
  DeclareParams<VoPipelineOptions>(ps, "");
  EXPECT_EQ(ps.GetInt("vo.cell_size"), Options::Rover().interest.cell_size);
  EXPECT_EQ(ps.GetInt("rectification_cache_size"), 2);
  EXPECT_NEAR(ps.GetDouble("vo.max_rotation_deg"), Options::Rover().max_rotation * 180 / M_PI,
              1e-9);
  ASSERT_TRUE(
      ps.LoadYamlString("vo:\n  min_inliers: 20\nprior:\n  rotation_sigma_min_deg: 2\n", "vo.yaml")
          .ok());
  auto o = ReadParams<VoPipelineOptions>(ps, "");
  ASSERT_TRUE(o.ok()) << o.status().ToString();
  EXPECT_EQ(o->vo.min_inliers, 20);
  EXPECT_NEAR(o->prior.rotation_sigma_min, 2.0 * M_PI / 180, 1e-15);
  EXPECT_EQ(o->vo.pixel_sigma, Options::Rover().pixel_sigma);
}

}  // namespace
}  // namespace rover::dl::vo
