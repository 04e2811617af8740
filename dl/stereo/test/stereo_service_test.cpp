// dl-stereo in the shared ServiceHarness (isolated DDS domain, sim clock the test publishes). The
// test plays the camera driver (tests/support fakes: textured ground rendered from the rover pose,
// known CAHV models in the rover frame) and dl-pose (fake, at 10 Hz), sends dl/range_request
// and checks dl/range_image against the scene geometry; bad frames, a missing pose and a request
// timeout produce no range image, a warning and a DEGRADED heartbeat.
#include "stereo_service.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "rover/testing/fakes/fake_camera_driver.hpp"
#include "rover/testing/fakes/fake_pose.hpp"
#include "rover/testing/service_harness.hpp"

namespace rover::dl::stereo {
namespace {

constexpr double kStep = 0.1;  // [s] sim/clock and dl/pose period

struct RangeImage {
  std::uint32_t request_id = 0;
  rover_CameraId camera = rover_CAMERA_NAVCAM;
  int width = 0, height = 0;
  std::int64_t stamp_ns = 0;
  std::string frame_id;
  rover_Pose3 rover_pose{};
  std::vector<float> xyz, disparity;
  std::vector<std::uint8_t> valid;
};

class StereoServiceTest : public ::testing::Test {
 protected:
  void Start(std::vector<std::string> overrides = {}) {
    h_ =
        std::make_unique<testing::ServiceHarness>(service_, "dl-stereo-test", std::move(overrides));
    ASSERT_TRUE(h_->ok()) << h_->status().message();
    ASSERT_TRUE(driver_.Create(h_->peer()).ok());
    ASSERT_TRUE(pose_.Create(h_->peer()).ok());
    request_w_ = h_->Writer<rover_dl_RangeRequest>("dl/range_request");
    range_r_ = h_->Reader<rover_dl_RangeImage>("dl/range_image");
    ASSERT_TRUE(h_->SpinUntil([&] { return driver_.Matched() && pose_.Matched(); }));
  }

  /// Advances the run clock by `seconds` in kStep steps: dl/pose (unless `publish_pose_` is
  /// false), sim/clock, the service spins until it sees the new time, the fake driver answers
  /// camera requests, and the service's output is collected.
  void Advance(double seconds) {
    const int steps = static_cast<int>(std::lround(seconds / kStep));
    for (int i = 0; i < steps; ++i) {
      ++step_;
      now_ = Time{step_ * 100'000'000};
      if (publish_pose_) {
        pose_.state.SetPose(rover_);
        pose_.state.stationary = true;
        EXPECT_TRUE(pose_.Publish(now_).ok());
      }
      EXPECT_TRUE(h_->AdvanceTo(now_));
      // Let the service take this step's dl/pose before a frame stamped now arrives.
      h_->Spin(2, std::chrono::milliseconds(2));
      const std::uint64_t frames = service_.stats().frames;
      const int answered = driver_.Serve(now_, rover_);
      if (answered > 0) {
        EXPECT_TRUE(h_->SpinUntil([&] {
          return service_.stats().frames >= frames + static_cast<std::uint64_t>(answered);
        })) << "the service did not take the frame";
      }
      Collect();
    }
  }

  void Collect() {
    h_->Spin(3);
    for (auto& s : range_r_.Take()) {
      RangeImage r;
      r.request_id = s->request_id;
      r.camera = s->camera;
      r.width = s->width;
      r.height = s->height;
      r.stamp_ns = s->header.stamp_ns;
      r.frame_id = s->header.frame_id;
      r.rover_pose = s->rover_pose;
      const auto xyz = dds::View(s->xyz);
      const auto valid = dds::View(s->valid);
      const auto disparity = dds::View(s->disparity);
      r.xyz.assign(xyz.begin(), xyz.end());
      r.valid.assign(valid.begin(), valid.end());
      r.disparity.assign(disparity.begin(), disparity.end());
      images_.push_back(std::move(r));
    }
  }

  void Request(std::uint32_t id, rover_CameraId camera, std::uint16_t width) {
    rover_dl_RangeRequest m{};
    m.header.stamp_ns = now_.ns;
    m.request_id = id;
    m.camera = camera;
    m.width = width;
    const std::uint64_t before =
        service_.stats().range_requests + service_.stats().rejected_requests;
    const std::uint64_t sent = service_.stats().camera_requests;
    ASSERT_TRUE(request_w_.Write(m).ok());
    ASSERT_TRUE(h_->SpinUntil([&] {
      return service_.stats().range_requests + service_.stats().rejected_requests > before;
    }));
    // The camera request (if one went out at once) reaches the driver before time moves on.
    if (service_.stats().camera_requests > sent) {
      ASSERT_TRUE(testing::WaitFor([&] { return driver_.Poll() > 0; }));
    }
  }

  /// The true scene point (rover frame) seen by left-image pixel (u, v) of a `width` image.
  Eigen::Vector3d TruePoint(int width, double u, double v) const {
    const testing::PinholeStereo cam = driver_.rig.Camera(width);
    const Eigen::Isometry3d world_from_rover =
        testing::WorldFromSite(driver_.scene.ground_y) * rover_;
    const Eigen::Isometry3d world_from_cam = world_from_rover * driver_.rig.rover_from_left;
    const Eigen::Vector3d o = world_from_cam.translation();
    const Eigen::Vector3d d = world_from_cam.linear() * cam.Ray({u, v});
    double best = std::numeric_limits<double>::infinity();
    if (d.y() > 1e-9) {
      const double l = (driver_.scene.ground_y - o.y()) / d.y();
      if (l > 0 && (o + l * d).z() < driver_.scene.wall_z) best = l;
    }
    if (d.z() > 1e-9) best = std::min(best, (driver_.scene.wall_z - o.z()) / d.z());
    return world_from_rover.inverse() * (o + best * d);
  }

  StereoService service_;  // outlives the harness that runs it
  std::unique_ptr<testing::ServiceHarness> h_;
  testing::FakeCameraDriver driver_;
  testing::FakePose pose_;
  dds::Writer<rover_dl_RangeRequest> request_w_;
  dds::Reader<rover_dl_RangeImage> range_r_;
  std::int64_t step_ = 0;
  Time now_;
  Eigen::Isometry3d rover_ = testing::RoverPose(1.5, -0.7, 0.3);
  bool publish_pose_ = true;
  std::vector<RangeImage> images_;
};

TEST_F(StereoServiceTest, RangesTheSyntheticGroundInTheRoverFrame) {
  Start();
  Advance(0.5);
  Request(77, rover_CAMERA_FRONT_HAZCAM, 0);  // width 0: the default, 256
  Advance(0.5);
  ASSERT_EQ(driver_.seen.size(), 1u);
  const rover_ddl_StereoRequest& req = driver_.seen[0];
  EXPECT_EQ(req.camera, rover_CAMERA_FRONT_HAZCAM);
  EXPECT_EQ(req.width, 256);
  EXPECT_EQ(req.request_id >> 24, 1u);  // request_id_prefix
  ASSERT_EQ(images_.size(), 1u) << service_.last_problem();
  const RangeImage& r = images_[0];
  EXPECT_EQ(r.request_id, 77u);
  EXPECT_EQ(r.camera, rover_CAMERA_FRONT_HAZCAM);
  EXPECT_EQ(r.frame_id, "rover");
  ASSERT_EQ(r.width, 256);
  ASSERT_EQ(r.height, 192);
  EXPECT_EQ(r.stamp_ns, Time::FromSeconds(0.6).ns);  // captured when the driver answered
  EXPECT_NEAR(r.rover_pose.position.x, 1.5, 1e-12);
  EXPECT_NEAR(r.rover_pose.position.y, -0.7, 1e-12);
  EXPECT_NEAR(2.0 * std::atan2(r.rover_pose.orientation.z, r.rover_pose.orientation.w), 0.3, 1e-12);
  const std::size_t n = 256u * 192u;
  ASSERT_EQ(r.xyz.size(), 3 * n);
  ASSERT_EQ(r.valid.size(), n);
  ASSERT_EQ(r.disparity.size(), n);

  std::vector<double> rel_errors, d_errors;
  for (int v = 0; v < r.height; ++v) {
    for (int u = 0; u < r.width; ++u) {
      const std::size_t i = static_cast<std::size_t>(v * r.width + u);
      if (r.valid[i] == 0) {
        EXPECT_EQ(r.disparity[i], -1.0F);
        EXPECT_TRUE(std::isnan(r.xyz[3 * i]));
        continue;
      }
      ASSERT_EQ(r.valid[i], 1);
      EXPECT_GT(r.disparity[i], 0.0F);
      const Eigen::Vector3d p(r.xyz[3 * i], r.xyz[3 * i + 1], r.xyz[3 * i + 2]);
      const Eigen::Vector3d truth = TruePoint(r.width, u, v);
      const double range = (truth - driver_.rig.rover_from_left.translation()).norm();
      rel_errors.push_back((p - truth).norm() / range);
      // Disparity of the true point: f B / depth along the (rectified = raw) left camera's axis.
      const Eigen::Vector3d pc = driver_.rig.rover_from_left.inverse() * truth;
      const double d_true = driver_.rig.Camera(r.width).fx * driver_.rig.baseline / pc.z();
      d_errors.push_back(r.disparity[i] - d_true);
    }
  }
  const double valid_fraction = static_cast<double>(rel_errors.size()) / static_cast<double>(n);
  EXPECT_GT(valid_fraction, 0.5);
  ASSERT_FALSE(rel_errors.empty());
  std::sort(rel_errors.begin(), rel_errors.end());
  std::sort(d_errors.begin(), d_errors.end());
  const double median = rel_errors[rel_errors.size() / 2];
  const double p95 = rel_errors[rel_errors.size() * 95 / 100];
  const double d_bias = d_errors[d_errors.size() / 2];
  // No systematic error (a frame, pose or pixel-convention mistake would show here as a bias
  // of pixels or a wrong range), and the library's random error (measured: median 0.7 %,
  // p95 2.4 %, disparity bias -0.014 px at 256 x 192 on this slanted ground).
  EXPECT_LT(std::abs(d_bias), 0.05) << "median disparity error [px]";
  EXPECT_LT(median, 0.012) << "median relative range error";
  EXPECT_LT(p95, 0.05) << "95th percentile relative range error";
  std::printf(
      "range image: %.1f%% valid, relative range error median %.4f, p95 %.4f; "
      "disparity bias %.3f px\n",
      100.0 * valid_fraction, median, p95, d_bias);

  // A second request with the same models reuses the rectification.
  Request(78, rover_CAMERA_FRONT_HAZCAM, 256);
  Advance(0.3);
  ASSERT_EQ(images_.size(), 2u) << service_.last_problem();
  EXPECT_EQ(images_[1].request_id, 78u);
  EXPECT_EQ(service_.setup_cache()->misses(), 1u);
  EXPECT_EQ(service_.setup_cache()->hits(), 1u);
  EXPECT_EQ(h_->health(), rover_HEALTH_OK) << h_->health_message();
}

TEST_F(StereoServiceTest, BadFramesAreDroppedWithAWarningAndNoRangeImage) {
  Start();
  Advance(0.3);
  struct Case {
    const char* name;
    const char* expect;  // in the reported problem
    std::function<void(rover_ddl_StereoFrame&, std::vector<std::uint8_t>&,
                       std::vector<std::uint8_t>&)>
        corrupt;
  };
  const std::vector<Case> cases = {
      {"short image", "right image has",
       [](rover_ddl_StereoFrame& m, std::vector<std::uint8_t>&, std::vector<std::uint8_t>& r) {
         r.pop_back();
         dds::BorrowSequence(m.right, r);
       }},
      {"missing model", "missing",
       [](rover_ddl_StereoFrame& m, std::vector<std::uint8_t>&, std::vector<std::uint8_t>&) {
         const auto w = m.left_model.width, h = m.left_model.height;
         m.left_model = rover_ddl_CameraModel{};
         m.left_model.width = w;
         m.left_model.height = h;
       }},
      {"singular pair (no baseline)", "stereo rectification",
       [](rover_ddl_StereoFrame& m, std::vector<std::uint8_t>&, std::vector<std::uint8_t>&) {
         m.right_model = m.left_model;
       }},
      {"corrupt model", "disagree",
       [](rover_ddl_StereoFrame& m, std::vector<std::uint8_t>&, std::vector<std::uint8_t>&) {
         m.left_model.c[2] += 0.5;
       }},
      {"wrong size", "px wide, requested 256",
       [](rover_ddl_StereoFrame& m, std::vector<std::uint8_t>& l, std::vector<std::uint8_t>& r) {
         m.width = 128;
         m.height = 384;
         m.left_model.width = m.right_model.width = 128;
         m.left_model.height = m.right_model.height = 384;
         dds::BorrowSequence(m.left, l);
         dds::BorrowSequence(m.right, r);
       }},
      {"failed health", "FAILED",
       [](rover_ddl_StereoFrame& m, std::vector<std::uint8_t>&, std::vector<std::uint8_t>&) {
         m.health = rover_HEALTH_FAILED;
       }},
      {"captured before the request", "before the request was sent",
       [](rover_ddl_StereoFrame& m, std::vector<std::uint8_t>&, std::vector<std::uint8_t>&) {
         m.header.stamp_ns -= 2'000'000'000;
       }},
      {"wrong camera", "requested front_hazcam",
       [](rover_ddl_StereoFrame& m, std::vector<std::uint8_t>&, std::vector<std::uint8_t>&) {
         m.camera = rover_CAMERA_NAVCAM;
       }},
  };
  std::uint32_t id = 100;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    driver_.corrupt = c.corrupt;
    const std::uint64_t bad = service_.stats().bad_frames;
    Request(++id, rover_CAMERA_FRONT_HAZCAM, 256);
    Advance(0.3);
    EXPECT_EQ(service_.stats().bad_frames, bad + 1);
    EXPECT_TRUE(images_.empty()) << "a range image was sent for a bad frame";
    EXPECT_NE(service_.last_problem().find(c.expect), std::string::npos) << service_.last_problem();
    EXPECT_EQ(h_->health(), rover_HEALTH_DEGRADED);
    EXPECT_NE(h_->health_message().find("dropped"), std::string::npos) << h_->health_message();
  }
  // A good frame afterwards is ranged and the health recovers.
  driver_.corrupt = nullptr;
  Request(++id, rover_CAMERA_FRONT_HAZCAM, 256);
  Advance(0.3);
  ASSERT_EQ(images_.size(), 1u) << service_.last_problem();
  EXPECT_EQ(h_->health(), rover_HEALTH_OK) << h_->health_message();
  EXPECT_EQ(service_.stats().published, 1u);
}

TEST_F(StereoServiceTest, NoRangeImageWithoutAPoseAtCaptureTime) {
  Start({"pose_max_age_s=0.5"});
  publish_pose_ = false;
  Advance(0.3);
  Request(5, rover_CAMERA_NAVCAM, 128);
  Advance(0.3);
  EXPECT_EQ(service_.stats().bad_frames, 1u);
  EXPECT_TRUE(images_.empty());
  EXPECT_NE(service_.last_problem().find("no pose estimate received yet"), std::string::npos)
      << service_.last_problem();
}

TEST_F(StereoServiceTest, WithoutRequirePoseTheImageCarriesAnIdentityPose) {
  Start({"require_pose=false"});
  publish_pose_ = false;
  Advance(0.3);
  Request(6, rover_CAMERA_NAVCAM, 128);
  Advance(0.3);
  ASSERT_EQ(images_.size(), 1u) << service_.last_problem();
  EXPECT_EQ(images_[0].width, 128);
  EXPECT_EQ(images_[0].height, 96);
  EXPECT_EQ(images_[0].camera, rover_CAMERA_NAVCAM);
  EXPECT_EQ(images_[0].rover_pose.orientation.w, 1.0);
  EXPECT_EQ(images_[0].rover_pose.position.x, 0.0);
}

TEST_F(StereoServiceTest, RequestTimeoutIsReportedOnTheRunClock) {
  Start({"request_timeout_s=2"});
  driver_.answer = false;
  Advance(0.2);
  Request(9, rover_CAMERA_REAR_HAZCAM, 256);
  Advance(1.9);
  EXPECT_EQ(service_.stats().timeouts, 0u);
  Advance(0.3);  // > 2 s of simulated time since the request, however long that took
  EXPECT_EQ(service_.stats().timeouts, 1u);
  EXPECT_NE(service_.last_problem().find("timed out"), std::string::npos)
      << service_.last_problem();
  EXPECT_EQ(h_->health(), rover_HEALTH_DEGRADED);
  EXPECT_TRUE(images_.empty());
  // The late answer is ignored; the next request is served.
  driver_.answer = true;
  ASSERT_EQ(driver_.seen.size(), 1u);
  driver_.Answer(driver_.seen[0], now_, rover_);
  Advance(0.2);
  EXPECT_TRUE(images_.empty());
  EXPECT_EQ(service_.stats().frames, 0u);
  Request(10, rover_CAMERA_REAR_HAZCAM, 256);
  Advance(0.3);
  ASSERT_EQ(images_.size(), 1u) << service_.last_problem();
  EXPECT_EQ(images_[0].request_id, 10u);
  EXPECT_EQ(h_->health(), rover_HEALTH_OK) << h_->health_message();
}

TEST_F(StereoServiceTest, QueuesRequestsAndDropsThoseThatOverflow) {
  Start({"max_queue=2"});
  driver_.answer = false;
  Advance(0.2);
  Request(1, rover_CAMERA_FRONT_HAZCAM, 256);  // outstanding
  Request(2, rover_CAMERA_FRONT_HAZCAM, 256);  // queued
  Request(3, rover_CAMERA_FRONT_HAZCAM, 256);  // queued
  Request(4, rover_CAMERA_FRONT_HAZCAM, 256);  // queue full
  // (An unknown camera value cannot be sent: DDS refuses to serialise an out-of-range enum.)
  EXPECT_EQ(service_.stats().range_requests, 3u);
  EXPECT_EQ(service_.stats().rejected_requests, 1u);
  EXPECT_EQ(service_.stats().camera_requests, 1u);  // one at a time
  EXPECT_NE(service_.last_problem().find("queue full"), std::string::npos);
  // Served in order once the driver answers.
  driver_.answer = true;
  Advance(1.0);
  ASSERT_EQ(images_.size(), 3u) << service_.last_problem();
  EXPECT_EQ(images_[0].request_id, 1u);
  EXPECT_EQ(images_[1].request_id, 2u);
  EXPECT_EQ(images_[2].request_id, 3u);
}

TEST(StereoServiceConfig, RejectsInconsistentParametersNamingThem) {
  StereoService svc;
  const testing::ServiceHarness h(svc, "dl-stereo-config",
                                  {"stereo.min_range_m=5", "stereo.max_range_m=4"});
  const Status& s = h.status();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("stereo.max_range_m"), std::string::npos) << s.message();
  StereoService svc2;
  const testing::ServiceHarness h2(svc2, "dl-stereo-config", {"stereo.window=8"});
  const Status& s2 = h2.status();
  ASSERT_FALSE(s2.ok());
  EXPECT_NE(s2.message().find("window"), std::string::npos) << s2.message();
}

}  // namespace
}  // namespace rover::dl::stereo
