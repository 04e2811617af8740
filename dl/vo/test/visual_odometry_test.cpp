#include "rover/dl/vo/visual_odometry.hpp"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <opencv2/imgproc.hpp>

#include "rover/base/units.hpp"
#include "rover/dl/vo/kitti.hpp"
#include "synthetic_scene.hpp"

namespace rover::dl::vo {
namespace {

using testing::CameraPose;
using testing::RenderPair;
using testing::SyntheticScene;
using testing::TestCamera;
using testing::TestCameraMotion;
using testing::TestMotion;

// Three pairs along TestMotion() steps, for one texture seed.
std::vector<StereoFrame> RenderSequence(std::uint64_t texture_seed, std::uint64_t noise_seed) {
  const StereoCamera cam = TestCamera();
  SyntheticScene scene;
  scene.texture_seed = texture_seed;
  std::vector<StereoFrame> out;
  Eigen::Isometry3d rover = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 3; ++i) {
    out.push_back(RenderPair(cam, scene, CameraPose(rover), i, noise_seed + 2 * i));
    rover = rover * TestMotion();
  }
  return out;
}

// Rendering costs about half a second per pair: render the shared pairs once.
class VoSynthetic : public ::testing::Test {
 protected:
  static void SetUpTestSuite() { pairs_ = new std::vector<StereoFrame>(RenderSequence(7, 1)); }
  static void TearDownTestSuite() {
    delete pairs_;
    pairs_ = nullptr;
  }
  static const StereoFrame& Pair(int i) { return (*pairs_)[static_cast<std::size_t>(i)]; }

  static VisualOdometry MakeVo(const Options& o = Options{}) {
    Result<VisualOdometry> vo = VisualOdometry::Create(o, TestCamera());
    EXPECT_TRUE(vo.ok()) << vo.status().ToString();
    return std::move(vo).value();
  }

  static std::vector<StereoFrame>* pairs_;
};
std::vector<StereoFrame>* VoSynthetic::pairs_ = nullptr;

// A wheel-odometry-like prior: the true motion, 4 cm and 1 degree off, with matching sigmas.
MotionPrior PriorFromTruth(const Eigen::Isometry3d& truth = TestCameraMotion()) {
  MotionPrior p = MotionPrior::Stationary(0.05, 1.5 * kDegree);
  p.delta = truth;
  p.delta.translation() += Eigen::Vector3d(0.02, -0.01, -0.03);
  p.delta.linear() = ExpSo3(Eigen::Vector3d(0.0, 1.0 * kDegree, 0.0)) * truth.linear();
  return p;
}

TEST(VoOptions, ValidateNamesTheField) {
  EXPECT_TRUE(Options{}.Validate().ok());
  EXPECT_TRUE(Options::Automotive().Validate().ok());
  Options o;
  o.pixel_sigma = 0;
  EXPECT_NE(o.Validate().message().find("pixel_sigma"), std::string::npos);
  o = Options{};
  o.max_range = 0.1;
  EXPECT_NE(o.Validate().message().find("range"), std::string::npos);
  o = Options{};
  o.max_rotation = 4.0;
  EXPECT_NE(o.Validate().message().find("max_rotation"), std::string::npos);
  o = Options{};
  o.match.template_radius = 0;
  EXPECT_NE(o.Validate().message().find("template_radius"), std::string::npos);
  o = Options{};
  o.min_inliers = 2;
  EXPECT_FALSE(o.Validate().ok());
  o = Options{};
  o.interest.cell_size = 1;
  EXPECT_FALSE(o.Validate().ok());
}

TEST(VoCreate, RejectsBadOptionsAndMissingCamera) {
  Options bad;
  bad.window_sigmas = -1;
  const auto r1 = VisualOdometry::Create(bad, TestCamera());
  ASSERT_FALSE(r1.ok());
  EXPECT_NE(r1.status().message().find("window_sigmas"), std::string::npos);
  const auto r2 = VisualOdometry::Create(Options{}, StereoCamera{});
  ASSERT_FALSE(r2.ok());
  EXPECT_EQ(r2.status().code(), StatusCode::kInvalidArgument);
  StereoCamera tiny = TestCamera();
  tiny.width = 20;
  EXPECT_FALSE(VisualOdometry::Create(Options{}, tiny).ok());
}

TEST_F(VoSynthetic, RejectsBadInputWithoutChangingState) {
  VisualOdometry vo = MakeVo();
  const MotionPrior prior = MotionPrior::Stationary(0.3, 0.1);
  StereoFrame f = Pair(0);
  f.left = cv::Mat(100, 100, CV_8UC1, cv::Scalar(0));
  auto r = vo.Process(f, prior);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("100x100"), std::string::npos);
  f = Pair(0);
  cv::cvtColor(Pair(0).right, f.right, cv::COLOR_GRAY2BGR);
  r = vo.Process(f, prior);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("CV_8UC1"), std::string::npos);
  f = Pair(0);
  f.right = cv::Mat();
  EXPECT_FALSE(vo.Process(f, prior).ok());
  f = Pair(0);
  Pair(0).left.convertTo(f.left, CV_16U);
  EXPECT_FALSE(vo.Process(f, prior).ok());
  EXPECT_FALSE(vo.has_reference());

  MotionPrior bad_prior = prior;
  bad_prior.covariance(0, 1) = 1.0;  // not symmetric
  EXPECT_EQ(vo.Process(Pair(0), bad_prior).status().code(), StatusCode::kInvalidArgument);
  bad_prior = prior;
  bad_prior.delta.translation().x() = std::nan("");
  EXPECT_EQ(vo.Process(Pair(0), bad_prior).status().code(), StatusCode::kInvalidArgument);
  bad_prior = prior;
  bad_prior.covariance(2, 2) = -1.0;
  EXPECT_EQ(vo.Process(Pair(0), bad_prior).status().code(), StatusCode::kInvalidArgument);
  EXPECT_FALSE(vo.has_reference());

  // Out of time order: same stamp, then an older one, are rejected and keep the reference.
  auto first = vo.Process(Pair(0), prior);
  ASSERT_TRUE(first.ok());
  EXPECT_EQ(first->status, MotionStatus::kNoReference);
  StereoFrame same = Pair(1);
  same.stamp = Pair(0).stamp;
  auto r3 = vo.Process(same, prior);
  ASSERT_FALSE(r3.ok());
  EXPECT_EQ(r3.status().code(), StatusCode::kFailedPrecondition);
  EXPECT_NE(r3.status().message().find("time order"), std::string::npos);
  same.stamp = Time::FromSeconds(-1.0);
  EXPECT_FALSE(vo.Process(same, prior).ok());
  // The reference is still pair 0: the next valid pair gives the motion from pair 0.
  auto est = vo.Process(Pair(1), PriorFromTruth());
  ASSERT_TRUE(est.ok());
  ASSERT_TRUE(est->converged()) << est->message;
  EXPECT_EQ(est->t_from, Pair(0).stamp);
  EXPECT_LT(MotionError(est->delta, TestCameraMotion()).head<3>().norm(), 0.002);
}

TEST(VoSyntheticAccuracy, RecoversKnownMotionWithinOneMillimetreAndTwentiethDegree) {
  // Three textures, each with a wheel-odometry prior and with a vague stationary prior; the
  // camera looks 25 degrees down at textured ground from 1.5 m and steps 0.46 m and 3 degrees.
  double nees_sum = 0.0;
  int runs = 0;
  for (const std::uint64_t texture : {7u, 107u, 207u}) {
    const std::vector<StereoFrame> pairs = RenderSequence(texture, 10 * texture + 1);
    for (const bool vague : {false, true}) {
      SCOPED_TRACE(::testing::Message()
                   << "texture " << texture << (vague ? ", vague prior" : ", odometry prior"));
      auto vo = VisualOdometry::Create(Options{}, TestCamera());
      ASSERT_TRUE(vo.ok());
      const MotionPrior prior =
          vague ? MotionPrior::Stationary(0.3, 3.0 * kDegree) : PriorFromTruth();
      ASSERT_TRUE(vo->Process(pairs[0], prior).ok());
      const auto est = vo->Process(pairs[1], prior);
      ASSERT_TRUE(est.ok());
      ASSERT_TRUE(est->converged()) << est->message;
      const Vector6d e = MotionError(est->delta, TestCameraMotion());
      EXPECT_LT(e.head<3>().norm(), 0.001) << e.transpose();
      EXPECT_LT(e.tail<3>().norm(), 0.05 * kDegree) << e.transpose();
      EXPECT_GT(est->inliers, 100);
      if (vague) {
        EXPECT_TRUE(est->first_pass);  // the coarse first pass narrowed the windows
      }
      EXPECT_EQ(est->t_from, pairs[0].stamp);
      EXPECT_EQ(est->t_to, pairs[1].stamp);
      // Covariance sanity: symmetric positive definite and never over-confident (NEES below
      // chi^2_6 at 0.999 in every run).
      EXPECT_NEAR((est->covariance - est->covariance.transpose()).norm(), 0.0, 1e-15);
      EXPECT_GT(est->covariance.ldlt().vectorD().minCoeff(), 0.0);
      const double nees = e.dot(est->covariance.ldlt().solve(e));
      EXPECT_LT(nees, 22.46);
      nees_sum += nees;
      ++runs;
    }
  }
  // With pixel_sigma = 0.3 px against ~0.1 px of real matching noise the covariance is
  // conservative (mean NEES measured 1.5, consistent would be 6), but not absurdly so.
  const double mean_nees = nees_sum / runs;
  EXPECT_GT(mean_nees, 0.2);
  EXPECT_LT(mean_nees, 12.0);
}

TEST_F(VoSynthetic, ChainsStepsAndIsDeterministic) {
  VisualOdometry a = MakeVo(), b = MakeVo();
  Eigen::Isometry3d pose_a = Eigen::Isometry3d::Identity();
  for (int i = 0; i < 3; ++i) {
    const MotionPrior prior = PriorFromTruth();
    const auto ea = a.Process(Pair(i), prior);
    const auto eb = b.Process(Pair(i), prior);
    ASSERT_TRUE(ea.ok() && eb.ok());
    EXPECT_TRUE(ea->delta.isApprox(eb->delta, 0.0));
    EXPECT_EQ(ea->inliers, eb->inliers);
    if (i > 0) {
      ASSERT_TRUE(ea->converged()) << ea->message;
      pose_a = pose_a * ea->delta;
    }
  }
  const Eigen::Isometry3d truth = TestCameraMotion() * TestCameraMotion();
  EXPECT_LT(MotionError(pose_a, truth).head<3>().norm(), 0.002);
  EXPECT_FALSE(a.last_tracks().empty());
  a.Reset();
  EXPECT_FALSE(a.has_reference());
}

TEST_F(VoSynthetic, SanityLimitsReportFailureAndEchoThePrior) {
  Options o;
  o.max_translation = 0.2;  // the step is 0.45 m
  VisualOdometry vo = MakeVo(o);
  const MotionPrior prior = PriorFromTruth();
  ASSERT_TRUE(vo.Process(Pair(0), prior).ok());
  auto est = vo.Process(Pair(1), prior);
  ASSERT_TRUE(est.ok());
  EXPECT_EQ(est->status, MotionStatus::kLimitsFailed);
  EXPECT_NE(est->message.find("max_translation"), std::string::npos);
  EXPECT_TRUE(est->delta.isApprox(prior.delta));  // not a measurement: the prior is echoed
  EXPECT_TRUE(est->covariance.isApprox(prior.covariance));

  o = Options{};
  o.max_rotation = 1.0 * kDegree;  // the step turns ~3 degrees
  VisualOdometry vo2 = MakeVo(o);
  ASSERT_TRUE(vo2.Process(Pair(0), prior).ok());
  est = vo2.Process(Pair(1), prior);
  ASSERT_TRUE(est.ok());
  EXPECT_EQ(est->status, MotionStatus::kLimitsFailed);

  // A confident but wrong prior (20 cm off, 1 cm sigma) fails the prior gate. Wide search
  // windows keep the tracking independent of the prior, so only the gate can fail.
  o = Options{};
  o.max_prior_mahalanobis_sq = 30.0;
  o.min_window = 40.0;
  MotionPrior wrong = MotionPrior::Stationary(0.01, 0.2 * kDegree);
  wrong.delta = TestCameraMotion();
  wrong.delta.translation().z() -= 0.2;
  VisualOdometry vo3 = MakeVo(o);
  ASSERT_TRUE(vo3.Process(Pair(0), wrong).ok());
  est = vo3.Process(Pair(1), wrong);
  ASSERT_TRUE(est.ok());
  EXPECT_EQ(est->status, MotionStatus::kLimitsFailed) << est->message;
  EXPECT_NE(est->message.find("prior"), std::string::npos);
  MotionPrior right = wrong;
  right.delta = TestCameraMotion();
  VisualOdometry vo4 = MakeVo(o);
  ASSERT_TRUE(vo4.Process(Pair(0), right).ok());
  est = vo4.Process(Pair(1), right);
  ASSERT_TRUE(est.ok());
  EXPECT_TRUE(est->converged()) << est->message;

  o = Options{};
  o.min_features = 100000;
  VisualOdometry vo5 = MakeVo(o);
  ASSERT_TRUE(vo5.Process(Pair(0), prior).ok());
  est = vo5.Process(Pair(1), prior);
  ASSERT_TRUE(est.ok());
  EXPECT_EQ(est->status, MotionStatus::kTooFewFeatures);
}

TEST(VoFrames, BodyAndCameraFrameConversionsAreInverse) {
  // Camera looking forward and 25 degrees down, 1.2 m up and 0.5 m forward on the rover.
  Eigen::Isometry3d t_b_c = Eigen::Isometry3d::Identity();
  const Eigen::Matrix3d level = (Eigen::Matrix3d() << 0, 0, 1, -1, 0, 0, 0, -1, 0).finished();
  t_b_c.linear() = level * Eigen::AngleAxisd(-0.44, Eigen::Vector3d::UnitX()).toRotationMatrix();
  t_b_c.translation() = Eigen::Vector3d(0.5, 0.0, 1.2);
  // The rover drives 0.5 m forward and turns 3 degrees left: its camera sees the conjugate.
  MotionPrior body = MotionPrior::Stationary(0.02, 0.5 * kDegree);
  body.delta.translation() = Eigen::Vector3d(0.5, 0.0, 0.0);
  body.delta.linear() = ExpSo3(Eigen::Vector3d(0, 0, 3 * kDegree));
  const MotionPrior cam = ToCameraFrame(body, t_b_c);
  EXPECT_TRUE(cam.delta.isApprox(t_b_c.inverse() * body.delta * t_b_c, 1e-12));
  MotionEstimate e;
  e.status = MotionStatus::kConverged;
  e.delta = cam.delta;
  e.covariance = cam.covariance;
  const MotionEstimate back = ToBodyFrame(e, t_b_c);
  EXPECT_TRUE(back.delta.isApprox(body.delta, 1e-12));
  EXPECT_NEAR((back.covariance - body.covariance).norm(), 0.0, 1e-15);
  EXPECT_EQ(back.status, MotionStatus::kConverged);
  // Yaw of the body is about the camera's -y axis tilted by the mount.
  EXPECT_NEAR(RotationAngle(cam.delta.linear()), 3 * kDegree, 1e-12);
}

TEST(VoFeatureless, ConstantAndSmoothImagesReportFailure) {
  const StereoCamera cam = TestCamera();
  for (const bool smooth : {false, true}) {
    SCOPED_TRACE(smooth ? "smooth" : "constant");
    SyntheticScene scene;
    scene.flat = !smooth;
    scene.smooth = smooth;
    scene.supersample = 1;
    const StereoFrame a = RenderPair(cam, scene, Eigen::Isometry3d::Identity(), 0.0, 1);
    const StereoFrame b = RenderPair(cam, scene, CameraPose(TestMotion()), 1.0, 3);
    for (const bool vague : {false, true}) {
      Result<VisualOdometry> vo = VisualOdometry::Create(Options{}, cam);
      ASSERT_TRUE(vo.ok());
      const MotionPrior prior = vague ? MotionPrior::Stationary(0.3, 0.1) : PriorFromTruth();
      ASSERT_TRUE(vo->Process(a, prior).ok());
      const auto est = vo->Process(b, prior);
      ASSERT_TRUE(est.ok());
      EXPECT_FALSE(est->converged()) << "a featureless pair gave a motion";
      EXPECT_EQ(est->status, MotionStatus::kTooFewFeatures) << est->message;
      EXPECT_FALSE(est->message.empty());
    }
  }
}

TEST_F(VoSynthetic, LensCapAfterTexturedPairReportsFailure) {
  VisualOdometry vo = MakeVo();
  ASSERT_TRUE(vo.Process(Pair(0), MotionPrior::Stationary(0.3, 0.1)).ok());
  StereoFrame cap;
  cap.stamp = Pair(1).stamp;
  cap.left = cv::Mat(Pair(1).left.size(), CV_8UC1, cv::Scalar(12));
  cap.right = cap.left.clone();
  const auto est = vo.Process(cap, MotionPrior::Stationary(0.3, 0.1));
  ASSERT_TRUE(est.ok());
  EXPECT_EQ(est->status, MotionStatus::kTooFewFeatures);
}

TEST(VoKitti, FirstTenFramesTranslationalError) {
  const std::string dir = std::string(ROVER_SHARED_DATA_DIR) + "/kitti-seq1";
  if (!std::filesystem::is_directory(dir)) {
    GTEST_SKIP() << "KITTI data not found at " << dir << " (set ROVER_SHARED_DATA_DIR)";
  }
  const auto seq = kitti::OpenSequence(dir);
  ASSERT_TRUE(seq.ok()) << seq.status().ToString();
  ASSERT_FALSE(seq->poses_file.empty());
  const auto truth_all = kitti::ReadPoses(seq->poses_file);
  ASSERT_TRUE(truth_all.ok());
  auto vo = VisualOdometry::Create(Options::Automotive(), seq->camera);
  ASSERT_TRUE(vo.ok());
  const int kFrames = 10;
  const kitti::ConstantVelocityModel model;
  std::vector<Eigen::Isometry3d> est{Eigen::Isometry3d::Identity()};
  MotionEstimate last;
  for (int i = 0; i < kFrames; ++i) {
    const auto frame = kitti::LoadFrame(*seq, static_cast<std::size_t>(i));
    ASSERT_TRUE(frame.ok());
    const auto e = vo->Process(*frame, model.Next(last));
    ASSERT_TRUE(e.ok()) << e.status().ToString();
    if (i > 0) {
      EXPECT_TRUE(e->converged()) << "frame " << i << ": " << e->message;
      est.push_back(est.back() * e->delta);
    }
    last = *e;
  }
  const std::vector<Eigen::Isometry3d> truth(truth_all->begin(), truth_all->begin() + kFrames);
  const kitti::ErrorMetrics m = kitti::Evaluate(truth, est, {2.0, 4.0, 6.0, 8.0});
  ASSERT_GT(m.segments, 10);
  // Measured on this data: 1.5 % (2-8 m segments), 1.6 % end point, 0.10 deg/m. The rotation
  // error of these first frames is that of the ground truth itself: an independent OpenCV
  // pipeline (LK + solvePnPRansac) shows the same per-frame yaw differences within 0.01 deg.
  EXPECT_LT(m.translation_percent, 2.5);
  EXPECT_LT(m.endpoint_percent, 2.5);
  EXPECT_LT(m.rotation_deg_per_m, 0.2);
  std::printf("KITTI frames 0-%d: %.2f %% translation, %.4f deg/m, end point %.2f %% of %.1f m\n",
              kFrames - 1, m.translation_percent, m.rotation_deg_per_m, m.endpoint_percent,
              m.path_length);
}

}  // namespace
}  // namespace rover::dl::vo
