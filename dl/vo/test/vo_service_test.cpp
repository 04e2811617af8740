// dl-vo in the shared ServiceHarness (isolated DDS domain, sim clock the test publishes). The
// test plays dl-pose (the fake pose: a wheel-odometry-like estimate that slips, 10 % long and
// drifting in heading) and the camera driver (tests/support fakes: textured ground rendered from
// the TRUE rover pose with known CAHV models in the rover frame). It checks MER's cadence (first
// pair at rest, a pair every step_distance of odometer, one at the end of the drive), that each
// dl/relative_pose matches the true motion between the two capture stamps far better than the
// odometry prior, and that a featureless pair or a bad frame is published with a failure status,
// not a motion.
#include "vo_service.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "rover/base/units.hpp"
#include "rover/testing/fakes/fake_camera_driver.hpp"
#include "rover/testing/fakes/fake_pose.hpp"
#include "rover/testing/service_harness.hpp"

namespace rover::dl::vo {
namespace {

constexpr double kStep = 0.1;  // [s] sim/clock and dl/pose period
Eigen::Isometry3d Delta(const rover_Pose3& p) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() =
      Eigen::Quaterniond(p.orientation.w, p.orientation.x, p.orientation.y, p.orientation.z)
          .normalized()
          .toRotationMatrix();
  t.translation() = Eigen::Vector3d(p.position.x, p.position.y, p.position.z);
  return t;
}

class VoServiceTest : public ::testing::Test {
 protected:
  /// The front HAZCAM (the default camera) as the simulator has it: 0.5 m high, 45 deg down,
  /// 0.10 m baseline, 120 deg across (a pinhole here: 74 px focal length at 256 px).
  static testing::Rig Hazcam() {
    testing::Rig rig;
    rig.rover_from_left = testing::CameraMount(0.785, {0.52, 0.05, 0.5});
    rig.baseline = 0.1;
    rig.focal_at_256 = 74.0;
    return rig;
  }
  /// A NAVCAM pointed down at the terrain as MER did for VO (25 deg, 1.5 m, 0.3 m baseline).
  static testing::Rig Navcam() {
    testing::Rig rig;
    rig.rover_from_left = testing::CameraMount(0.44, {0.3, 0.15, 1.5});
    rig.baseline = 0.3;
    rig.focal_at_256 = 200.0;
    return rig;
  }

  /// Imaging always (the vision set's setting) unless `overrides` say otherwise.
  void Start(std::vector<std::string> overrides = {}, const testing::Rig& rig = Navcam()) {
    if (std::none_of(overrides.begin(), overrides.end(),
                     [](const std::string& o) { return o.rfind("imaging=", 0) == 0; })) {
      overrides.push_back("imaging=always");
    }
    driver_.rig = rig;
    h_ = std::make_unique<testing::ServiceHarness>(service_, "dl-vo-test", std::move(overrides));
    ASSERT_TRUE(h_->ok()) << h_->status().message();
    ASSERT_TRUE(driver_.Create(h_->peer()).ok());
    ASSERT_TRUE(pose_.Create(h_->peer()).ok());
    relpose_r_ = h_->Reader<rover_dl_RelativePose>("dl/relative_pose");
    ASSERT_TRUE(h_->SpinUntil([&] { return driver_.Matched() && pose_.Matched(); }));
  }

  /// Drives for `seconds` at `speed` [m/s] and `yaw_rate` [rad/s] (true motion), in kStep steps.
  /// dl/pose carries the slipping estimate; the driver renders from the truth.
  void Drive(double seconds, double speed, double yaw_rate) {
    const int steps = static_cast<int>(std::lround(seconds / kStep));
    for (int i = 0; i < steps; ++i) {
      ++step_;
      now_ = Time{step_ * 100'000'000};
      Integrate(&truth_, speed, yaw_rate);
      const bool moving = speed != 0.0 || yaw_rate != 0.0;
      Integrate(&estimate_, speed * kOdometryScale, moving ? yaw_rate + kHeadingDrift : 0.0);
      odometer_ += std::abs(speed) * kOdometryScale * kStep;
      truth_at_[now_.ns] = truth_;
      pose_.state.SetPose(estimate_);
      pose_.state.velocity = {speed * kOdometryScale, 0.0, 0.0};
      pose_.state.odometer = odometer_;
      pose_.state.stationary = !moving;
      if (publish_pose_) {
        EXPECT_TRUE(pose_.Publish(now_).ok());
      }
      EXPECT_TRUE(h_->AdvanceTo(now_));
      h_->Spin(2, std::chrono::milliseconds(2));
      // A request sent at this tick reaches the driver before it serves (deterministic steps).
      EXPECT_TRUE(testing::WaitFor([&] {
        driver_.Poll();
        return driver_.seen.size() >= service_.stats().camera_requests;
      }));
      const std::uint64_t frames = service_.stats().frames;
      const int answered = driver_.Serve(now_, truth_);
      for (int k = 0; k < answered; ++k) captures_.push_back(now_);
      if (answered > 0) {
        EXPECT_TRUE(h_->SpinUntil([&] {
          return service_.stats().frames >= frames + static_cast<std::uint64_t>(answered);
        }));
      }
      Collect();
    }
  }

  static void Integrate(Eigen::Isometry3d* pose, double speed, double yaw_rate) {
    // Constant speed and turn rate over the step: move along the chord at the mid heading.
    const Eigen::Isometry3d step =
        testing::RoverPose(speed * kStep * std::cos(yaw_rate * kStep / 2),
                           speed * kStep * std::sin(yaw_rate * kStep / 2), yaw_rate * kStep);
    *pose = *pose * step;
  }

  void Collect() {
    h_->Spin(3);
    for (auto& s : relpose_r_.Take()) relposes_.push_back(s.data());
  }

  /// True motion between two run-clock times (rover frame at `from`).
  Eigen::Isometry3d TrueDelta(std::int64_t from, std::int64_t to) const {
    return truth_at_.at(from).inverse() * truth_at_.at(to);
  }

  static constexpr double kOdometryScale = 1.10;  // wheel odometry 10 % long (slip)
  static constexpr double kHeadingDrift = 0.01;   // [rad/s] heading error while driving

  VoService service_;  // outlives the harness that runs it
  std::unique_ptr<testing::ServiceHarness> h_;
  testing::FakeCameraDriver driver_;
  testing::FakePose pose_;
  dds::Reader<rover_dl_RelativePose> relpose_r_;
  std::int64_t step_ = 0;
  Time now_;
  Eigen::Isometry3d truth_ = testing::RoverPose(0.0, 0.0, 0.0);
  Eigen::Isometry3d estimate_ = testing::RoverPose(0.0, 0.0, 0.0);
  double odometer_ = 0.0;
  bool publish_pose_ = true;
  std::map<std::int64_t, Eigen::Isometry3d> truth_at_;
  std::vector<Time> captures_;
  std::vector<rover_dl_RelativePose> relposes_;

  /// Drives 0.7 m on an arc and stops; checks the pairs, the steps against the truth and the
  /// odometry prior, and the cadence.
  void CheckMerCadence(rover_CameraId camera, int width) {
    Drive(1.0, 0.0, 0.0);  // at rest: the first pair, the reference
    ASSERT_EQ(captures_.size(), 1u);
    EXPECT_EQ(service_.stats().references, 1u);
    EXPECT_TRUE(relposes_.empty());
    ASSERT_EQ(driver_.seen.size(), 1u);
    EXPECT_EQ(driver_.seen[0].camera, camera);
    EXPECT_EQ(driver_.seen[0].width, width);
    EXPECT_EQ(driver_.seen[0].request_id >> 24, 2u);
    Drive(7.0, 0.1, 0.04);  // 0.7 m (odometer 0.77 m) on a left arc: one pair at 0.5 m odometer
    EXPECT_EQ(captures_.size(), 2u);
    Drive(3.0, 0.0, 0.0);  // stop: one pair once settled
    ASSERT_EQ(captures_.size(), 3u);
    EXPECT_EQ(service_.stats().camera_requests, 3u);
    ASSERT_EQ(relposes_.size(), 2u) << service_.last_problem();

    for (std::size_t i = 0; i < relposes_.size(); ++i) {
      SCOPED_TRACE("step " + std::to_string(i));
      const rover_dl_RelativePose& r = relposes_[i];
      EXPECT_EQ(r.status, rover_dl_RELPOSE_CONVERGED);
      EXPECT_EQ(r.source, rover_dl_SOURCE_VISUAL_ODOMETRY);
      EXPECT_STREQ(r.header.frame_id, "rover");
      EXPECT_EQ(r.header.stamp_ns, r.t_to_ns);
      EXPECT_EQ(r.t_from_ns, captures_[i].ns);
      EXPECT_EQ(r.t_to_ns, captures_[i + 1].ns);
      EXPECT_GE(r.features, 10u);
      const Eigen::Isometry3d truth = TrueDelta(r.t_from_ns, r.t_to_ns);
      const Eigen::Isometry3d vo = Delta(r.delta);
      const double t_err = (vo.translation() - truth.translation()).norm();
      const double r_err = RotationAngle(vo.linear().transpose() * truth.linear());
      // What the odometry prior said (10 % long, drifting heading).
      const double prior_err = 0.10 * truth.translation().norm();
      std::printf(
          "step %zu: true %.3f m / %.2f deg; VO error %.1f mm, %.3f deg; %u inliers; "
          "odometry error ~%.0f mm\n",
          i, truth.translation().norm(), RotationAngle(truth.linear()) / kDegree, 1e3 * t_err,
          r_err / kDegree, r.features, 1e3 * prior_err);
      EXPECT_GT(truth.translation().norm(), 0.2);
      // Measured (0.46 m and 0.24 m steps): HAZCAM 512 x 384: 1.0 mm / 0.006 deg, 0.5 mm /
      // 0.010 deg; NAVCAM 256 x 192: 1.5 mm / 0.004 deg, 0.3 mm / 0.016 deg. (HAZCAM at 256 px:
      // 6.5 mm / 0.15 deg with only 14 inliers, hence the default width 512.)
      EXPECT_LT(t_err, 0.01);
      EXPECT_LT(r_err, 0.1 * kDegree);
      EXPECT_LT(t_err, prior_err / 3.0) << "VO must be much closer to the truth than odometry";
      // Covariance: symmetric, positive, consistent in scale with the error.
      Eigen::Matrix<double, 6, 6> cov;
      for (int a = 0; a < 6; ++a) {
        for (int b = 0; b < 6; ++b) cov(a, b) = r.covariance[a * 6 + b];
      }
      EXPECT_LT((cov - cov.transpose()).norm(), 1e-12 * cov.norm());
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>> eig(cov);
      EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
      EXPECT_LT(std::sqrt(cov(0, 0)), 0.05);
    }
    EXPECT_EQ(h_->health(), rover_HEALTH_OK) << h_->health_message();
    // Parked: nothing more to measure.
    Drive(3.0, 0.0, 0.0);
    EXPECT_EQ(captures_.size(), 3u);
  }
};

TEST_F(VoServiceTest, MeasuresTheTrueMotionAtMerCadenceWithTheDefaultHazcam) {
  Start({}, Hazcam());
  CheckMerCadence(rover_CAMERA_FRONT_HAZCAM, 512);
}

TEST_F(VoServiceTest, MeasuresTheTrueMotionWithANavcamAt256) {
  Start({"camera=navcam", "width=256"}, Navcam());
  CheckMerCadence(rover_CAMERA_NAVCAM, 256);
}

TEST_F(VoServiceTest, FeaturelessPairIsPublishedAsAFailureNotAMotion) {
  Start({"width=256"});
  driver_.scene.flat = true;
  Drive(1.0, 0.0, 0.0);
  Drive(6.0, 0.1, 0.0);
  ASSERT_EQ(captures_.size(), 2u);
  ASSERT_EQ(relposes_.size(), 1u);
  const rover_dl_RelativePose& r = relposes_[0];
  EXPECT_EQ(r.status, rover_dl_RELPOSE_TOO_FEW_FEATURES);
  EXPECT_EQ(r.t_from_ns, captures_[0].ns);
  EXPECT_EQ(r.t_to_ns, captures_[1].ns);
  EXPECT_LT(r.features, 10u);
  EXPECT_EQ(service_.stats().converged, 0u);
  EXPECT_EQ(h_->health(), rover_HEALTH_DEGRADED);
  EXPECT_NE(h_->health_message().find("visual odometry step failed"), std::string::npos)
      << h_->health_message();
}

TEST_F(VoServiceTest, BadFrameIsReportedAndTheReferenceKept) {
  Start({"retry_delay_s=1", "width=256"});
  Drive(1.0, 0.0, 0.0);
  ASSERT_EQ(captures_.size(), 1u);
  // The next frame (first step while driving) has a singular model pair.
  driver_.corrupt = [](rover_ddl_StereoFrame& m, std::vector<std::uint8_t>&,
                       std::vector<std::uint8_t>&) { m.right_model = m.left_model; };
  Drive(5.0, 0.1, 0.0);  // odometer 0.55 m: a pair is due
  ASSERT_EQ(captures_.size(), 2u);
  ASSERT_EQ(relposes_.size(), 1u);
  EXPECT_EQ(relposes_[0].status, rover_dl_RELPOSE_BAD_INPUT);
  EXPECT_EQ(relposes_[0].t_from_ns, captures_[0].ns);
  EXPECT_EQ(service_.stats().bad_frames, 1u);
  EXPECT_NE(service_.last_problem().find("stereo rectification"), std::string::npos)
      << service_.last_problem();
  EXPECT_EQ(h_->health(), rover_HEALTH_DEGRADED);
  // After retry_delay_s the next pair measures from the kept reference.
  driver_.corrupt = nullptr;
  Drive(1.5, 0.1, 0.0);
  ASSERT_EQ(captures_.size(), 3u);
  EXPECT_GE(captures_[2] - captures_[1], Seconds(1.0));  // retry_delay_s of run-clock time
  EXPECT_LE(captures_[2] - captures_[1], Seconds(1.0) + Seconds(kStep));
  ASSERT_EQ(relposes_.size(), 2u);
  const rover_dl_RelativePose& r = relposes_[1];
  EXPECT_EQ(r.status, rover_dl_RELPOSE_CONVERGED) << service_.last_problem();
  EXPECT_EQ(r.t_from_ns, captures_[0].ns);
  EXPECT_EQ(r.t_to_ns, captures_[2].ns);
  const Eigen::Isometry3d truth = TrueDelta(r.t_from_ns, r.t_to_ns);
  EXPECT_LT((Delta(r.delta).translation() - truth.translation()).norm(), 0.015);
  EXPECT_EQ(h_->health(), rover_HEALTH_OK) << h_->health_message();
}

TEST_F(VoServiceTest, TimeoutIsReportedOnTheRunClockAndTheRequestRepeated) {
  Start({"request_timeout_s=1.5", "width=256"});
  driver_.answer = false;
  Drive(0.2, 0.0, 0.0);
  ASSERT_EQ(service_.stats().camera_requests, 1u);
  Drive(1.3, 0.0, 0.0);
  EXPECT_EQ(service_.stats().timeouts, 0u);
  Drive(0.4, 0.0, 0.0);  // > 1.5 s of run-clock time since the request
  EXPECT_EQ(service_.stats().timeouts, 1u);
  EXPECT_NE(service_.last_problem().find("timed out"), std::string::npos);
  EXPECT_EQ(h_->health(), rover_HEALTH_DEGRADED);
  EXPECT_EQ(service_.stats().camera_requests, 2u);  // asked again at once (still no reference)
}

TEST_F(VoServiceTest, StalePosePausesTheCadence) {
  Start({"pose_max_age_s=0.5", "width=256"});
  Drive(1.0, 0.0, 0.0);
  ASSERT_EQ(captures_.size(), 1u);
  publish_pose_ = false;  // dl-pose stops while the rover drives on
  Drive(8.0, 0.1, 0.0);
  EXPECT_EQ(captures_.size(), 1u) << "no pair may be requested on a stale pose";
  // dl/pose older than inputs.dl_pose.max_age_s (1 s): STALE on sys/health.
  EXPECT_EQ(h_->health(), rover_HEALTH_STALE);
  EXPECT_NE(h_->health_message().find("dl/pose stale"), std::string::npos) << h_->health_message();
  publish_pose_ = true;  // back: the odometer has moved on, so a pair is due at once
  Drive(0.3, 0.1, 0.0);
  EXPECT_EQ(captures_.size(), 2u);
}

// MER took VO pairs only in its VisOdom modes: by default dl-vo images only while a client asks
// on dl/vo_command, and each time imaging starts the chain starts over with a reference pair.
TEST_F(VoServiceTest, ImagesOnlyWhileAClientAsks) {
  Start({"imaging=on_request", "width=256"});
  EXPECT_FALSE(service_.imaging());
  Drive(1.0, 0.0, 0.0);
  Drive(7.0, 0.1, 0.0);  // 0.7 m with nobody asking: no pair
  EXPECT_TRUE(captures_.empty());
  EXPECT_EQ(service_.stats().camera_requests, 0u);
  auto w = h_->Writer<rover_dl_VoCommand>("dl/vo_command");
  auto ask = [&](const char* client, bool imaging) {
    rover_dl_VoCommand c{};
    c.header.stamp_ns = now_.ns;
    dds::CopyString(c.client, client);
    c.imaging = imaging;
    ASSERT_TRUE(w.Write(c).ok());
    ASSERT_TRUE(
        h_->SpinUntil([&] { return service_.clients().count(client) == (imaging ? 1u : 0u); }));
  };
  ask("apl-mobility", true);
  EXPECT_TRUE(service_.imaging());
  Drive(1.0, 0.0, 0.0);  // a new reference pair at rest
  ASSERT_EQ(captures_.size(), 1u);
  Drive(6.0, 0.1, 0.0);  // 0.6 m: one pair at 0.5 m of odometer, and a motion estimate
  EXPECT_EQ(captures_.size(), 2u);
  EXPECT_EQ(relposes_.size(), 1u);
  ask("operator", true);
  ask("apl-mobility", false);  // one client still asks
  EXPECT_TRUE(service_.imaging());
  ask("operator", false);
  EXPECT_FALSE(service_.imaging());
  const std::size_t before = captures_.size();
  Drive(8.0, 0.1, 0.0);  // nobody asks again
  EXPECT_EQ(captures_.size(), before);
  // A command without a client name is refused (counted, on sys/health).
  rover_dl_VoCommand bad{};
  bad.imaging = true;
  ASSERT_TRUE(w.Write(bad).ok());
  ASSERT_TRUE(h_->SpinUntil([&] { return service_.stats().rejected_commands == 1; }));
  EXPECT_FALSE(service_.imaging());
}

}  // namespace
}  // namespace rover::dl::vo
