// dl-pose in the shared ServiceHarness (isolated DDS domain, sim clock the test publishes), with
// ddl/imu (100 Hz, the fake IMU), ddl/joint_state (50 Hz), ddl/sun_sensor and dl/relative_pose
// written by the test: rate on the sim clock, levelling, gyro heading integration, sun heading
// updates with the shared ephemeris, gating of a corrupted relative pose (event published).
#include "pose_service.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <cmath>
#include <functional>
#include <limits>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include "rover/base/units.hpp"
#include "rover/dl/pose/chi_square.hpp"
#include "rover/geometry/transforms.hpp"
#include "rover/testing/fakes/fake_imu.hpp"
#include "rover/testing/service_harness.hpp"

namespace rover::dl::pose {
namespace {

constexpr double kStep = 0.01;  // 100 Hz IMU and sim/clock
constexpr std::int64_t kStepNs = 10'000'000;

Eigen::Vector3d RpyOf(const rover_dl_PoseEstimate& p) {
  const auto& q = p.pose.orientation;
  return geometry::RpyFromQuaternion(Eigen::Quaterniond(q.w, q.x, q.y, q.z));
}

class PoseServiceTest : public ::testing::Test {
 protected:
  void TearDown() override {
    h_.reset();
    unsetenv("ROVER_STATE_DIR");
    unsetenv("ROVER_SET_ID");
  }

  void Start(std::vector<std::string> overrides = {}, PoseService* service = nullptr) {
    // Level on 0.5 s (the service's default of 10 s is for real drives).
    overrides.insert(overrides.begin(), "start.level_samples=50");
    h_ = std::make_unique<testing::ServiceHarness>(service ? *service : service_, "dl-pose-test",
                                                   std::move(overrides));
    ASSERT_TRUE(h_->ok()) << h_->status().message();
    ASSERT_TRUE(imu_.Create(h_->peer()).ok());
    joint_w_ = h_->Writer<rover_ddl_JointState>("ddl/joint_state");
    sun_w_ = h_->Writer<rover_ddl_SunSensor>("ddl/sun_sensor");
    relpose_w_ = h_->Writer<rover_dl_RelativePose>("dl/relative_pose");
    pose_r_ = h_->Reader<rover_dl_PoseEstimate>("dl/pose");
    event_r_ = h_->Reader<rover_dl_EstimatorEvent>("dl/estimator_event");
    ASSERT_TRUE(h_->SpinUntil([&] { return imu_.Matched(); }));
  }

  /// Advances the run clock by `seconds` in 10 ms steps: IMU (the fake's yaw rate and specific
  /// force) every step, joint state every other step, optional per-step hook, then sim/clock;
  /// waits until the service has seen the new time and collects its output.
  void Advance(double seconds, const std::function<void()>& each_step = nullptr) {
    const int steps = static_cast<int>(std::lround(seconds / kStep));
    for (int i = 0; i < steps; ++i) {
      ++step_;
      now_ = Time{step_ * kStepNs};
      EXPECT_TRUE(imu_.Publish(now_, kStep).ok());
      wheel_angle_ += wheel_rate_ * kStep;
      if (step_ % 2 == 0) {
        rover_ddl_JointState j{};
        j.header.stamp_ns = now_.ns;
        for (double& w : j.wheel_angle) w = wheel_angle_;
        for (double& w : j.wheel_rate) w = wheel_rate_;
        j.health = rover_HEALTH_OK;
        EXPECT_TRUE(joint_w_.Write(j).ok());
      }
      if (each_step) each_step();
      EXPECT_TRUE(h_->AdvanceTo(now_));
      Collect();
    }
  }

  void Collect() {
    for (auto& s : pose_r_.Take(64)) poses_.push_back({now_, s.data()});
    for (auto& e : event_r_.Take(64)) events_.push_back(e.data());
  }

  /// Writes a relative pose and lets the service take it.
  void SendRelativePose(const rover_dl_RelativePose& m) {
    const std::size_t before = events_.size();
    ASSERT_TRUE(relpose_w_.Write(m).ok());
    // Converged samples always produce an event (processed now: t_to <= filter time).
    if (m.status == rover_dl_RELPOSE_CONVERGED) {
      ASSERT_TRUE(h_->SpinUntil([&] {
        Collect();
        return events_.size() > before;
      }));
    } else {
      h_->Spin(5, std::chrono::milliseconds(5));
      Collect();
    }
  }

  static rover_dl_RelativePose RelativePose(double t_from, double t_to, double dx) {
    rover_dl_RelativePose m{};
    m.source = rover_dl_SOURCE_VISUAL_ODOMETRY;
    m.t_from_ns = Time::FromSeconds(t_from).ns;
    m.t_to_ns = Time::FromSeconds(t_to).ns;
    m.delta.position = {dx, 0.0, 0.0};
    m.delta.orientation = {1.0, 0.0, 0.0, 0.0};
    for (int i = 0; i < 6; ++i) m.covariance[i * 7] = i < 3 ? 1e-4 : 1e-6;  // 1 cm, 1 mrad
    m.status = rover_dl_RELPOSE_CONVERGED;
    m.features = 100;
    return m;
  }

  struct Received {
    Time when;  // run-clock time the test had published when it arrived
    rover_dl_PoseEstimate pose;
  };

  PoseService service_;  // outlives the harness that runs it
  std::unique_ptr<testing::ServiceHarness> h_;
  testing::FakeImu imu_;  // yaw rate and specific force of the rover; Mars gravity at rest
  dds::Writer<rover_ddl_JointState> joint_w_;
  dds::Writer<rover_ddl_SunSensor> sun_w_;
  dds::Writer<rover_dl_RelativePose> relpose_w_;
  dds::Reader<rover_dl_PoseEstimate> pose_r_;
  dds::Reader<rover_dl_EstimatorEvent> event_r_;
  std::int64_t step_ = 0;
  Time now_;
  double wheel_rate_ = 0.0;  // [rad/s] all six wheels, steering straight
  double wheel_angle_ = 0.0;
  std::vector<Received> poses_;
  std::vector<rover_dl_EstimatorEvent> events_;
};

TEST_F(PoseServiceTest, PublishesAtTheConfiguredRateOnTheSimClock) {
  Start({"publish_rate_hz=20"});
  EXPECT_EQ(h_->lifecycle().params().GetDouble("ekf.gravity"), 3.711);  // Mars, as the simulator
  Advance(1.0);
  ASSERT_FALSE(poses_.empty()) << "no dl/pose after levelling";
  const std::size_t before = poses_.size();
  Advance(3.0);
  // 20 Hz of simulated time, whatever the wall-clock speed of the test.
  EXPECT_EQ(poses_.size() - before, 60u);
  for (std::size_t i = before; i < poses_.size(); ++i) {
    const rover_dl_PoseEstimate& p = poses_[i].pose;
    EXPECT_STREQ(p.header.frame_id, "site");
    EXPECT_LE(p.header.stamp_ns, poses_[i].when.ns);  // the filter's time, never ahead
    EXPECT_GE(p.header.stamp_ns, poses_[i].when.ns - Time::FromSeconds(0.011).ns);
    if (i > before) {
      EXPECT_GT(p.header.stamp_ns, poses_[i - 1].pose.header.stamp_ns);
    }
    EXPECT_TRUE(p.stationary);
    for (int r = 0; r < 6; ++r) {
      EXPECT_GT(p.covariance[r * 7], 0.0);
      for (int c = 0; c < 6; ++c) {
        EXPECT_DOUBLE_EQ(p.covariance[r * 6 + c], p.covariance[c * 6 + r]);
      }
    }
  }
}

TEST_F(PoseServiceTest, LevelsFromTheAccelerometerAndIntegratesAConstantYawRate) {
  // The fake wheels stand still while the gyro turns: the gyro check would (rightly) call that a
  // gyro fault; this test is about the propagation alone.
  Start({"start.yaw_deg=10", "start.x=2", "start.y=-3", "gyro_check.enabled=false"});
  const double roll = 4.0 * kDegree, pitch = -3.0 * kDegree, g = 3.711;
  imu_.specific_force = g * Eigen::Vector3d(-std::sin(pitch), std::sin(roll) * std::cos(pitch),
                                            std::cos(roll) * std::cos(pitch));
  Advance(1.0);  // at rest: levels after 50 samples (0.5 s)
  ASSERT_FALSE(poses_.empty());
  const rover_dl_PoseEstimate start = poses_.back().pose;
  Eigen::Vector3d rpy = RpyOf(start);
  EXPECT_NEAR(rpy.x(), roll, 1e-6);
  EXPECT_NEAR(rpy.y(), pitch, 1e-6);
  EXPECT_NEAR(rpy.z(), 10.0 * kDegree, 1e-6);
  EXPECT_NEAR(start.pose.position.x, 2.0, 1e-9);
  EXPECT_NEAR(start.pose.position.y, -3.0, 1e-9);
  EXPECT_NEAR(start.gyro_bias.z, 0.0, 1e-12);
  const double yaw_var0 = start.covariance[35];

  // 0.2 rad/s about the rover z axis for 5 s: +1 rad of rotation about body z. On a tilted rover
  // that is not exactly +1 rad of ZYX yaw; compare rotations instead.
  imu_.yaw_rate = 0.2;
  Advance(5.0);
  EXPECT_FALSE(poses_.back().pose.stationary);  // turning
  imu_.yaw_rate = 0.0;
  Advance(0.1);
  const rover_dl_PoseEstimate end = poses_.back().pose;
  const auto q = [](const rover_dl_PoseEstimate& p) {
    return Eigen::Quaterniond(p.pose.orientation.w, p.pose.orientation.x, p.pose.orientation.y,
                              p.pose.orientation.z);
  };
  const Eigen::Quaterniond expected = q(start) * Eigen::AngleAxisd(1.0, Eigen::Vector3d::UnitZ());
  EXPECT_LT(expected.angularDistance(q(end)), 1e-5);
  rpy = RpyOf(end);
  EXPECT_NEAR(rpy.z(), 10.0 * kDegree + 1.0, 0.02);
  EXPECT_GT(end.covariance[35], yaw_var0);  // heading uncertainty grows with gyro propagation
  EXPECT_TRUE(end.stationary);
  EXPECT_EQ(end.rejected_measurements, 0u);
}

TEST_F(PoseServiceTest, AGyroTurningWhileTheWheelsStandStillMakesThePoseUnknown) {
  Start({});
  Advance(2.0);
  ASSERT_FALSE(poses_.empty());
  EXPECT_EQ(h_->health(), rover_HEALTH_OK);
  // A 0.05 rad/s gyro bias appears (the safety campaign's "bias the gyro"): the wheels say the
  // rover does not turn. One window fails after 0.4-0.65 s and the next disjoint window confirms
  // it (gyro_check.confirm_s, 1 s).
  imu_.yaw_rate = 0.05;
  const Time onset = now_;
  Advance(3.0);
  ASSERT_FALSE(poses_.empty());
  const double last = ToSeconds(Time{poses_.back().pose.header.stamp_ns} - onset);
  EXPECT_GT(last, 1.2);  // not before the confirming window
  EXPECT_LT(last, 2.0);  // and no dl/pose after it
  h_->Spin(20, std::chrono::milliseconds(5));
  EXPECT_EQ(h_->health(), rover_HEALTH_FAILED);
  EXPECT_NE(h_->health_message().find("gyro fault: ddl/imu gyro z disagrees with wheel odometry"),
            std::string::npos)
      << h_->health_message();
}

TEST_F(PoseServiceTest, AnEncoderJumpIsARejectedInput) {
  Start({});
  Advance(1.0);
  wheel_angle_ += 1e5;  // one wheel-angle sample with a flipped exponent bit, then it is back
  Advance(0.02);
  wheel_angle_ -= 1e5;
  Advance(0.1);
  h_->Spin(20, std::chrono::milliseconds(5));
  EXPECT_EQ(h_->health(), rover_HEALTH_DEGRADED);
  EXPECT_NE(h_->health_message().find("ddl/joint_state rejected"), std::string::npos)
      << h_->health_message();
  EXPECT_NE(h_->health_message().find("angle jumped"), std::string::npos) << h_->health_message();
}

TEST_F(PoseServiceTest, WheelOdometryFromJointStatesMovesThePositionAlongTheHeading) {
  Start({"start.yaw_deg=90"});  // facing west (site +y)
  Advance(1.0);
  const double var_y0 = poses_.back().pose.covariance[7];
  wheel_rate_ = 0.4;  // 0.05 m/s with the 0.125 m default wheels
  Advance(4.0);
  wheel_rate_ = 0.0;
  const rover_dl_PoseEstimate moving = poses_.back().pose;
  EXPECT_FALSE(moving.stationary);
  EXPECT_NEAR(moving.velocity.x, 0.05, 1e-6);
  Advance(1.0);
  const rover_dl_PoseEstimate p = poses_.back().pose;
  EXPECT_NEAR(p.pose.position.x, 0.0, 1e-6);
  EXPECT_NEAR(p.pose.position.y, 0.2, 1e-6);  // 4 s at 0.05 m/s
  EXPECT_NEAR(p.odometer, 0.2, 0.01);  // counted in ekf.odometer_step (1 cm) steps
  // Along-track variance grew by odometry.along_variance_per_m (1e-3 m^2/m) * 0.2 m.
  EXPECT_NEAR(p.covariance[7] - var_y0, 1e-3 * 0.2, 2e-5);
  EXPECT_TRUE(p.stationary);
}

TEST_F(PoseServiceTest, SunSensorCorrectsAWrongStartHeadingWithTheSharedEphemeris) {
  Start({"start.yaw_deg=6"});  // the rover really faces north (yaw 0)
  const geometry::SunEphemeris sun{geometry::SunEphemerisOptions{}};  // the simulator's defaults
  Advance(1.0);
  ASSERT_NEAR(RpyOf(poses_.back().pose).z(), 6.0 * kDegree, 1e-6);
  Advance(5.0, [&] {
    if (step_ % 50 != 0) return;  // 2 Hz
    rover_ddl_SunSensor s{};
    s.header.stamp_ns = now_.ns;
    const Eigen::Vector3d d = sun.At(now_.seconds()).direction_site;  // level, yaw 0: rover = site
    s.sun_vector = {d.x(), d.y(), d.z()};
    s.valid = true;
    s.intensity = 1.0;
    s.health = rover_HEALTH_OK;
    EXPECT_TRUE(sun_w_.Write(s).ok());
  });
  EXPECT_NEAR(RpyOf(poses_.back().pose).z(), 0.0, 0.5 * kDegree);
  // The dl/pose_odometry baseline takes no sun updates: it keeps the wrong start heading.
  ASSERT_NE(service_.odometry_only(), nullptr);
  ASSERT_TRUE(service_.odometry_only()->initialized());
  EXPECT_NEAR(geometry::RpyFromQuaternion(service_.odometry_only()->Estimate().orientation).z(),
              6.0 * kDegree, 1e-3 * kDegree);
  int sun_events = 0;
  for (const auto& e : events_) {
    if (e.source != rover_dl_SOURCE_SUN_SENSOR) continue;
    ++sun_events;
    EXPECT_TRUE(e.accepted) << e.message;
    EXPECT_NEAR(e.gate, ChiSquareQuantile(0.999, 2), 1e-9);
  }
  EXPECT_GE(sun_events, 9);
}

TEST_F(PoseServiceTest, CorruptedRelativePoseIsGatedAndReported) {
  Start();
  Advance(3.0);  // at rest: clones from ~0.5 s on
  ASSERT_FALSE(poses_.empty());
  const std::size_t accel_events = events_.size();
  // Consistent with the rover at rest: accepted.
  SendRelativePose(RelativePose(1.0, 2.0, 0.0));
  ASSERT_EQ(events_.size(), accel_events + 1);
  EXPECT_TRUE(events_.back().accepted) << events_.back().message;
  EXPECT_EQ(events_.back().source, rover_dl_SOURCE_VISUAL_ODOMETRY);
  // Corrupted: a 1 m jump with a 1 cm sigma while the rover stood still: gated.
  SendRelativePose(RelativePose(1.5, 2.5, 1.0));
  ASSERT_EQ(events_.size(), accel_events + 2);
  const rover_dl_EstimatorEvent& e = events_.back();
  EXPECT_FALSE(e.accepted);
  EXPECT_EQ(e.source, rover_dl_SOURCE_VISUAL_ODOMETRY);
  EXPECT_NEAR(e.gate, ChiSquareQuantile(0.999, 6), 1e-9);
  EXPECT_GT(e.mahalanobis_sq, e.gate);
  EXPECT_EQ(e.header.stamp_ns, Time::FromSeconds(2.5).ns);
  EXPECT_NE(std::string(e.message).find("rejected"), std::string::npos) << e.message;
  // Not converged: not a measurement, no event, even with a wild value.
  rover_dl_RelativePose nc = RelativePose(1.0, 2.0, 50.0);
  nc.status = rover_dl_RELPOSE_TOO_FEW_FEATURES;
  SendRelativePose(nc);
  EXPECT_EQ(events_.size(), accel_events + 2);
  // Bad input (NaN, non-unit quaternion): refused before gating, reported with d2 NaN.
  rover_dl_RelativePose bad = RelativePose(1.0, 2.0, 0.0);
  bad.delta.position.y = std::numeric_limits<double>::quiet_NaN();
  SendRelativePose(bad);
  ASSERT_EQ(events_.size(), accel_events + 3);
  EXPECT_FALSE(events_.back().accepted);
  EXPECT_TRUE(std::isnan(events_.back().mahalanobis_sq));
  bad = RelativePose(1.0, 2.0, 0.0);
  bad.delta.orientation = {0.5, 0.0, 0.0, 0.0};
  SendRelativePose(bad);
  ASSERT_EQ(events_.size(), accel_events + 4);
  EXPECT_NE(std::string(events_.back().message).find("quaternion has norm 0.5"), std::string::npos)
      << events_.back().message;
  // The state was not moved by the rejected jump, and the count is on dl/pose.
  Advance(0.2);
  const rover_dl_PoseEstimate p = poses_.back().pose;
  EXPECT_NEAR(p.pose.position.x, 0.0, 1e-3);
  EXPECT_EQ(p.rejected_measurements, 1u);
}

TEST_F(PoseServiceTest, InvalidParametersKeepTheServiceUnconfigured) {
  testing::ServiceHarness h(service_, "dl-pose-bad", {"ephemeris.mode=calendar"});
  const Status& s = h.status();
  EXPECT_FALSE(s.ok());
  EXPECT_NE(s.message().find("ephemeris.mode"), std::string::npos) << s.message();
  EXPECT_EQ(h.lifecycle().state(), LifecycleState::kUnconfigured);
}

// The conversions (RelativePoseFromIdl, PoseEstimateToIdl): core/msg/test/pose_idl_test.cpp;
// the levelling (LevelFromSpecificForce, Leveller): test/pose_startup_test.cpp.

// ---- restart (kill -9 mid-drive) ----------------------------------------------------------------

class PoseRestartTest : public PoseServiceTest {
 protected:
  // As roverctl runs it: a state folder and the set's id (rover/base/checkpoint.hpp).
  void Supervised(const std::string& set_id) {
    if (state_dir_.empty()) state_dir_ = testing::MakeTempDir("dl-pose-restart");
    setenv("ROVER_STATE_DIR", state_dir_.c_str(), 1);
    setenv("ROVER_SET_ID", set_id.c_str(), 1);
  }
  // Levels, then drives 4 s at 0.05 m/s along site x (0.2 m).
  void LevelAndDrive() {
    Start();
    Advance(1.0);
    wheel_rate_ = 0.4;
    Advance(4.0);
    ASSERT_FALSE(poses_.empty());
    before_ = poses_.back().pose;
    ASSERT_NEAR(before_.pose.position.x, 0.2, 0.01);
  }
  // The process is gone (nothing of it runs any more: its checkpoint file stays, as after kill
  // -9); the rover drives on for `gap_s` of run time; the supervisor starts a new dl-pose.
  void KillAndRestart(double gap_s, std::vector<std::string> overrides = {}) {
    h_.reset();
    const auto gap_steps = static_cast<std::int64_t>(std::lround(gap_s / kStep));
    step_ += gap_steps;
    wheel_angle_ += wheel_rate_ * kStep * static_cast<double>(gap_steps);
    poses_.clear();
    restarted_ = std::make_unique<PoseService>();
    Start(std::move(overrides), restarted_.get());
  }
  std::string state_dir_;
  rover_dl_PoseEstimate before_{};
  std::unique_ptr<PoseService> restarted_;
};

TEST_F(PoseRestartTest, KillNineMidDriveResumesFromTheCheckpointWithInflatedCovariance) {
  Supervised("drive.1.a/dl-pose");
  LevelAndDrive();
  KillAndRestart(2.0);  // down for 2 s while driving at 0.05 m/s: 0.1 m unseen
  Advance(1.0);         // still driving
  ASSERT_FALSE(poses_.empty()) << "a resumed dl-pose publishes at once";
  const rover_dl_PoseEstimate& first = poses_.front().pose;
  // Not the start (x = 0, yaw 0, odometer 0): where the checkpoint left it (at most 1 s of
  // checkpoint period before the kill), then on from there.
  EXPECT_GT(first.pose.position.x, 0.15);
  EXPECT_LT(first.pose.position.x, 0.25);
  EXPECT_NEAR(RpyOf(first).z(), 0.0, 1e-3);
  EXPECT_GT(first.odometer, 0.14);
  // The covariance grew for the unseen gap (resume.max_speed 0.1 m/s times >= 2 s).
  EXPECT_GT(first.covariance[0], before_.covariance[0] + 0.9 * 0.04);
  EXPECT_GT(first.covariance[35], before_.covariance[35]);
  EXPECT_EQ(h_->health(), rover_HEALTH_OK) << h_->health_message();
  // And it drives on from there: 1 s more at 0.05 m/s.
  EXPECT_NEAR(poses_.back().pose.pose.position.x - first.pose.position.x, 0.05, 0.01);
}

TEST_F(PoseRestartTest, ACheckpointTooOldForResumingMeansThePoseIsUnknown) {
  Supervised("drive.1.a/dl-pose");
  LevelAndDrive();
  KillAndRestart(3.0, {"resume.max_age_s=2"});
  Advance(2.0);
  EXPECT_TRUE(poses_.empty()) << "a restarted dl-pose without a usable checkpoint must not "
                                 "publish a pose anything could drive on";
  EXPECT_EQ(h_->health(), rover_HEALTH_FAILED);
  EXPECT_NE(h_->health_message().find("pose unknown after restart"), std::string::npos)
      << h_->health_message();
}

TEST_F(PoseRestartTest, ACheckpointOfAnotherSetIsNotResumed) {
  Supervised("drive.1.a/dl-pose");
  LevelAndDrive();
  Supervised("drive.2.b/dl-pose");  // a later `up` of the same project: a fresh start
  wheel_rate_ = 0.0;
  KillAndRestart(1.0);
  Advance(1.0);
  ASSERT_FALSE(poses_.empty());
  EXPECT_NEAR(poses_.back().pose.pose.position.x, 0.0, 1e-6);  // levelled at start.*, as a first start
  EXPECT_EQ(h_->health(), rover_HEALTH_OK) << h_->health_message();
}

}  // namespace
}  // namespace rover::dl::pose
