// Ramp pose from stripe corners: a synthetic projection through a known pose (no renderer) and
// rendered NAVCAM pairs of the simulated lander (one renderer for the suite) against truth.
#include "rover/apl/rendezvous/ramp_pose.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
#include <random>
#include <string>

#include "lander_scene.hpp"
#include "rover/sim/render/cameras.hpp"

namespace rover::apl::rendezvous {
namespace {

using testing::LanderScene;
using testing::RoverView;

constexpr double kDeg = std::numbers::pi / 180.0;

struct Models {
  geometry::CameraModel left, right;
};

Models NavcamInRover(double tilt_deg) {
  const auto defs = sim::render::DefaultStereoCameras(1024);
  const auto navcam = sim::render::FindStereoCamera(defs, "navcam");
  const auto spec = sim::render::MakeCameraPairSpec(*navcam, {0.0, tilt_deg * kDeg});
  return {spec->LeftInRover(), spec->RightInRover()};
}

/// The detection a perfect detector would give of ramp `ramp` at `rover_from_ramp`.
StripeDetection Project(const hwconfig::LanderDescription& lander, int ramp,
                        const Eigen::Isometry3d& rover_from_ramp, const geometry::CameraModel& model,
                        double noise_px, std::mt19937* rng) {
  std::normal_distribution<double> n(0.0, noise_px);
  StripeDetection det;
  for (int s = 0; s < hwconfig::kStripesPerRamp; ++s) {
    DetectedStripe d;
    d.ramp = ramp;
    d.index = s;
    for (int c = 0; c < 4; ++c) {
      const auto px = model.Project(rover_from_ramp * StripeCornerInRamp(lander, ramp, s, c));
      d.corners[static_cast<std::size_t>(c)] = *px + Eigen::Vector2d(n(*rng), n(*rng));
      d.corner_valid[static_cast<std::size_t>(c)] = model.InImage(*px);
    }
    det.stripes.push_back(d);
  }
  return det;
}

/// A ramp 4 m ahead, yawed and inclined 18 deg.
Eigen::Isometry3d ExamplePose() {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  // The rover faces up the ramp: u points away from it (+x, yawed 8 deg) and 18 deg up, v to
  // the rover's left, w up and back towards the rover.
  t.linear() = (Eigen::AngleAxisd(8.0 * kDeg, Eigen::Vector3d::UnitZ()) *
                Eigen::AngleAxisd(-18.0 * kDeg, Eigen::Vector3d::UnitY()))
                   .toRotationMatrix();
  t.translation() = Eigen::Vector3d(5.8, 0.3, 0.5);
  return t;
}

TEST(RampPoseTest, OptionsValidate) {
  RampPoseOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.min_stripes = 0;
  const Status s = o.Validate();
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("ramp_pose.min_stripes"), std::string::npos) << s.message();
}

TEST(RampPoseTest, SyntheticProjectionConvergesToTheExactPose) {
  const hwconfig::LanderDescription lander;
  const Models m = NavcamInRover(-10.0);
  const Eigen::Isometry3d truth = ExamplePose();
  std::mt19937 rng(1);
  for (int ramp = 0; ramp < 2; ++ramp) {
    const StripeDetection left = Project(lander, ramp, truth, m.left, 0.0, &rng);
    const StripeDetection right = Project(lander, ramp, truth, m.right, 0.0, &rng);
    int valid = 0;
    for (const auto& s : left.stripes) for (bool v : s.corner_valid) valid += v;
    ASSERT_EQ(valid, 24);
    for (bool stereo : {false, true}) {
      const auto pose = EstimateRampPose(lander, left, m.left, stereo ? &right : nullptr,
                                         stereo ? &m.right : nullptr);
      ASSERT_TRUE(pose.ok()) << pose.status().message();
      EXPECT_EQ(pose->ramp, ramp);
      EXPECT_EQ(pose->stripes_used, 6);
      EXPECT_LT((pose->rover_from_ramp.translation() - truth.translation()).norm(), 1e-6);
      EXPECT_LT(Eigen::AngleAxisd(pose->rover_from_ramp.linear().transpose() * truth.linear()).angle(), 1e-7);
      EXPECT_LT(pose->rms_px, 1e-6);
    }
  }
}

TEST(RampPoseTest, NoisyCornersGiveAConsistentCovariance) {
  const hwconfig::LanderDescription lander;
  const Models m = NavcamInRover(-10.0);
  const Eigen::Isometry3d truth = ExamplePose();
  std::mt19937 rng(7);
  double chi2 = 0.0;
  const int runs = 40;
  for (int k = 0; k < runs; ++k) {
    const StripeDetection left = Project(lander, 0, truth, m.left, 0.3, &rng);
    const StripeDetection right = Project(lander, 0, truth, m.right, 0.3, &rng);
    RampPoseOptions o;
    o.huber_px = 10.0;  // Gaussian noise: plain least squares
    const auto pose = EstimateRampPose(lander, left, m.left, &right, &m.right, o);
    ASSERT_TRUE(pose.ok()) << pose.status().message();
    // delta with truth = est Exp(delta).
    const Eigen::Isometry3d d = pose->rover_from_ramp.inverse() * truth;
    Eigen::Matrix<double, 6, 1> delta;
    delta.head<3>() = d.translation();
    const Eigen::AngleAxisd aa(d.linear());
    delta.tail<3>() = aa.angle() * aa.axis();
    chi2 += delta.dot(pose->covariance.inverse() * delta);
  }
  // E[chi2] = 6 per run.
  std::printf("mean chi2 %.2f (expected 6)\n", chi2 / runs);
  EXPECT_GT(chi2 / runs, 3.0);
  EXPECT_LT(chi2 / runs, 12.0);
}

TEST(RampPoseTest, TooFewStripesIsAnError) {
  const hwconfig::LanderDescription lander;
  const Models m = NavcamInRover(-10.0);
  std::mt19937 rng(1);
  StripeDetection left = Project(lander, 0, ExamplePose(), m.left, 0.0, &rng);
  left.stripes.resize(3);
  const auto pose = EstimateRampPose(lander, left, m.left, nullptr, nullptr);
  ASSERT_FALSE(pose.ok());
  EXPECT_EQ(pose.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(pose.status().message().find("3 stripes"), std::string::npos) << pose.status().message();
  const auto none = EstimateRampPose(lander, StripeDetection{}, m.left, nullptr, nullptr);
  EXPECT_EQ(none.status().code(), StatusCode::kFailedPrecondition);
  const auto bad = EstimateRampPose(lander, left, m.left, &left, nullptr);
  EXPECT_EQ(bad.status().code(), StatusCode::kInvalidArgument);
}

TEST(RampPoseTest, RampBaseFromThePose) {
  const hwconfig::LanderDescription lander;
  RampPose p;
  p.rover_from_ramp = ExamplePose();
  const auto b = RampBaseInRover(lander, p);
  ASSERT_TRUE(b.ok());
  EXPECT_NEAR(b->inclination, 18.0 * kDeg, 1e-9);
  EXPECT_NEAR(b->slope_length, lander.ramp_length / std::cos(18.0 * kDeg), 1e-9);
  // The base is slope_length / 2 down the slope from the origin: horizontal run ramp_length / 2.
  const Eigen::Vector3d d = b->base_in_rover - p.rover_from_ramp.translation();
  EXPECT_NEAR(d.head<2>().norm(), 0.5 * lander.ramp_length, 1e-9);
  EXPECT_NEAR(b->up_axis_in_rover.z(), 0.0, 1e-12);
  EXPECT_GT(b->up_axis_in_rover.x(), 0.9);  // away from the rover
  EXPECT_LT(b->base_in_rover.x(), p.rover_from_ramp.translation().x());
  EXPECT_EQ(RampBaseInRover(lander, p, Eigen::Vector3d::Zero()).status().code(),
            StatusCode::kInvalidArgument);
}

// ---- rendered scenes ---------------------------------------------------------------------

class RampPoseSceneTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    auto s = LanderScene::Create();
    if (!s.ok()) {
      setup_error_ = new std::string(s.status().message());
      return;
    }
    scene_ = s->release();
  }
  static void TearDownTestSuite() {
    delete scene_;
    scene_ = nullptr;
    delete setup_error_;
    setup_error_ = nullptr;
  }
  void SetUp() override {
    if (setup_error_) GTEST_SKIP() << "no renderer: " << *setup_error_;
  }

  struct Errors {
    double lateral = 0, longitudinal = 0, heading_deg = 0, rms_px = 0, sigma_lat = 0;
    bool ok = false;
  };

  /// Pose of `ramp` from view, stereo; base errors in the ramp's horizontal axes [m], heading
  /// error [deg].
  static Errors Measure(const RoverView& view, int ramp, bool stereo = true) {
    Errors e;
    auto shot = scene_->Render(view);
    EXPECT_TRUE(shot.ok()) << shot.status().message();
    if (!shot.ok()) return e;
    const auto left = DetectStripes(shot->left);
    const auto right = DetectStripes(shot->right);
    EXPECT_TRUE(left.ok() && right.ok());
    if (!left.ok() || !right.ok()) return e;
    RampPoseOptions o;
    o.ramp = ramp;
    const auto pose = EstimateRampPose(scene_->description(), *left, shot->left_model,
                                       stereo ? &*right : nullptr,
                                       stereo ? &shot->right_model : nullptr, o);
    EXPECT_TRUE(pose.ok()) << pose.status().message();
    if (!pose.ok()) return e;
    const auto base = RampBaseInRover(scene_->description(), *pose, shot->up_in_rover);
    EXPECT_TRUE(base.ok());
    const testing::RampTruth& t = shot->ramps[static_cast<std::size_t>(ramp)];
    const Eigen::Vector3d err = base->base_in_rover - t.base_in_rover;
    const Eigen::Vector3d lat_axis = shot->up_in_rover.cross(t.up_axis_in_rover).normalized();
    e.longitudinal = err.dot(t.up_axis_in_rover);
    e.lateral = err.dot(lat_axis);
    e.heading_deg = std::atan2(base->up_axis_in_rover.dot(lat_axis), base->up_axis_in_rover.dot(t.up_axis_in_rover)) / kDeg;
    e.rms_px = pose->rms_px;
    // Lateral sigma of the G origin (translation block, v axis).
    e.sigma_lat = std::sqrt(pose->covariance(1, 1));
    e.ok = true;
    const Eigen::Vector3d dt = pose->rover_from_ramp.translation() - t.rover_from_ramp.translation();
    std::printf("ramp %d %-6s d %.1f m: base err lat %+6.1f mm lon %+6.1f mm head %+6.3f deg | "
                "origin err (%+.1f %+.1f %+.1f) mm | rms %.2f px, %d corners, sigma_v %.1f mm\n",
                ramp, stereo ? "stereo" : "left", (t.base_in_rover.head<2>()).norm(),
                1e3 * e.lateral, 1e3 * e.longitudinal, e.heading_deg, 1e3 * dt.x(), 1e3 * dt.y(),
                1e3 * dt.z(), e.rms_px, pose->corners_used, 1e3 * e.sigma_lat);
    return e;
  }

  static LanderScene* scene_;
  static std::string* setup_error_;
};
LanderScene* RampPoseSceneTest::scene_ = nullptr;
std::string* RampPoseSceneTest::setup_error_ = nullptr;

TEST_F(RampPoseSceneTest, OnAxisAccuracyVersusDistance) {
  for (double d : {2.0, 3.0, 4.0, 5.0, 6.0, 8.0}) {
    const Errors e = Measure(scene_->ViewOfRamp(0, d, 0.0), 0);
    ASSERT_TRUE(e.ok);
    const double scale = d <= 5.0 ? 1.0 : 2.0;
    EXPECT_LT(std::abs(e.lateral), 0.015 * scale) << d;
    EXPECT_LT(std::abs(e.longitudinal), 0.015 * scale) << d;
    EXPECT_LT(std::abs(e.heading_deg), 0.5 * scale) << d;
    EXPECT_LT(e.rms_px, 0.8);
  }
}

TEST_F(RampPoseSceneTest, ObliqueViewsAndRampOne) {
  for (double off : {-40.0, -20.0, 20.0, 40.0}) {
    const Errors e = Measure(scene_->ViewOfRamp(0, 4.0, off), 0);
    ASSERT_TRUE(e.ok);
    EXPECT_LT(std::abs(e.lateral), 0.015) << off;
    EXPECT_LT(std::abs(e.longitudinal), 0.015) << off;
    EXPECT_LT(std::abs(e.heading_deg), 0.5) << off;
  }
  const Errors mono = Measure(scene_->ViewOfRamp(0, 4.0, 0.0), 0, false);
  EXPECT_TRUE(mono.ok);
  const Errors e1 = Measure(scene_->ViewOfRamp(1, 4.0, 10.0), 1);
  ASSERT_TRUE(e1.ok);
  EXPECT_LT(std::abs(e1.lateral), 0.015);
  EXPECT_LT(std::abs(e1.longitudinal), 0.015);
  EXPECT_LT(std::abs(e1.heading_deg), 0.5);
}

}  // namespace
}  // namespace rover::apl::rendezvous
