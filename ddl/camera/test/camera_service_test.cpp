// ddl-camera in-process on an isolated DDS domain under a simulated clock: the test plays DL
// (ddl/camera_request), the encoder reader (ddl/joint_state with the mast angles) and the camera
// head (answers hw/camera_request with a synthetic hw/camera_frame), and checks ddl/stereo_frame:
// downsampled pixels and the models of deploy/config/cameras.yaml moved by the mast.
#include "camera_service.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

#include "rover/testing/service_harness.hpp"

namespace rover::ddl::camera {
namespace {

using testing::ServiceHarness;

const std::string kCameraFile = std::string(ROVER_SOURCE_DIR) + "/deploy/config/cameras.yaml";

// Block pattern: pixel (x, y) = 5 bx + 3 by (mod 256) with (bx, by) its `block` x `block` cell,
// so a block-aligned area downsampling reproduces the cell values exactly.
std::vector<std::uint8_t> Blocks(int w, int h, int block, int offset) {
  std::vector<std::uint8_t> px(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      px[static_cast<std::size_t>(y) * w + x] =
          static_cast<std::uint8_t>((5 * (x / block) + 3 * (y / block) + offset) % 256);
    }
  }
  return px;
}

// A model rebuilt from the message's CAHVOR fields.
geometry::CameraModel FromMessage(const rover_ddl_CameraModel& m) {
  auto v = [](const double* p) { return Eigen::Vector3d(p[0], p[1], p[2]); };
  geometry::Cahvor c{v(m.c), v(m.a), v(m.h), v(m.v), v(m.o), v(m.r)};
  auto model = geometry::CameraModel::Create(c, m.width, m.height);
  EXPECT_TRUE(model.ok()) << model.status().message();
  return *model;
}

class CameraServiceTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto cal = LoadCameraCalibration(kCameraFile);
    ASSERT_TRUE(cal.ok()) << cal.status().message();
    calibration_ = std::make_unique<CameraCalibration>(std::move(*cal));
    harness_ = std::make_unique<ServiceHarness>(
        service_, "ddl-camera-test",
        std::vector<std::string>{"camera_file=" + kCameraFile, "request_timeout_s=1.0"});
    ASSERT_TRUE(harness_->ok()) << harness_->status().message();
    request_ = harness_->Writer<rover_ddl_StereoRequest>("ddl/camera_request");
    joints_ = harness_->Writer<rover_ddl_JointState>("ddl/joint_state");
    frame_ = harness_->Writer<rover_hw_CameraFrame>("hw/camera_frame");
    hw_request_ = harness_->Reader<rover_hw_CameraRequest>("hw/camera_request");
    stereo_ = harness_->Reader<rover_ddl_StereoFrame>("ddl/stereo_frame");
  }
  void TearDown() override { harness_.reset(); }

  // 20 ms steps; ddl/joint_state with the mast angles every step unless `joints_silent_`.
  void Run(double seconds) {
    const Time end = now_ + Seconds(seconds);
    while (now_ < end) {
      now_ = now_ + Seconds(0.02);
      ASSERT_TRUE(harness_->AdvanceTo(now_));
      if (!joints_silent_) {
        rover_ddl_JointState js{};
        js.header.stamp_ns = now_.ns;
        js.mast_pan = pan_;
        js.mast_tilt = tilt_;
        js.health = rover_HEALTH_OK;
        ASSERT_TRUE(joints_.Write(js).ok());
      }
      harness_->Spin();
      Collect();
    }
  }
  void Collect() {
    for (auto& r : hw_request_.Take()) hw_requests_.push_back(r.data());
    for (auto& s : stereo_.Take()) frames_.push_back(std::move(s));
  }
  void Request(std::uint32_t id, rover_CameraId camera, std::uint16_t width,
               std::uint32_t exposure_us = 0) {
    rover_ddl_StereoRequest r{};
    r.request_id = id;
    r.camera = camera;
    r.width = width;
    r.exposure_us = exposure_us;
    ASSERT_TRUE(request_.Write(r).ok());
  }
  // Waits for the n-th hw request (1-based) and returns it.
  rover_hw_CameraRequest WaitHwRequest(std::size_t n) {
    EXPECT_TRUE(harness_->SpinUntil([&] {
      Collect();
      return hw_requests_.size() >= n;
    }));
    return hw_requests_.size() >= n ? hw_requests_[n - 1] : rover_hw_CameraRequest{};
  }
  // Answers `req` with a w x h block-pattern frame captured now.
  void Answer(const rover_hw_CameraRequest& req, int w, int h, int block) {
    left_px_ = Blocks(w, h, block, 0);
    right_px_ = Blocks(w, h, block, 100);
    rover_hw_CameraFrame f{};
    f.header.stamp_ns = now_.ns;
    f.request_id = req.request_id;
    f.camera = req.camera;
    f.exposure_us = 1500;
    f.width = static_cast<std::uint16_t>(w);
    f.height = static_cast<std::uint16_t>(h);
    dds::BorrowSequence(f.left, left_px_);
    dds::BorrowSequence(f.right, right_px_);
    ASSERT_TRUE(frame_.Write(f).ok());
  }
  const rover_ddl_StereoFrame& WaitFrame(std::size_t n) {
    EXPECT_TRUE(harness_->SpinUntil([&] {
      Collect();
      return frames_.size() >= n;
    }));
    return frames_.at(n - 1).data();
  }

  CameraService service_;
  std::unique_ptr<CameraCalibration> calibration_;
  std::unique_ptr<ServiceHarness> harness_;
  dds::Writer<rover_ddl_StereoRequest> request_;
  dds::Writer<rover_ddl_JointState> joints_;
  dds::Writer<rover_hw_CameraFrame> frame_;
  dds::Reader<rover_hw_CameraRequest> hw_request_;
  dds::Reader<rover_ddl_StereoFrame> stereo_;
  Time now_ = Time::FromSeconds(2.0);
  double pan_ = 0.3, tilt_ = -0.2;
  bool joints_silent_ = false;
  std::vector<std::uint8_t> left_px_, right_px_;
  std::vector<rover_hw_CameraRequest> hw_requests_;
  std::vector<dds::OwnedSample<rover_ddl_StereoFrame>> frames_;
};

TEST_F(CameraServiceTest, DownsamplesNavcamAndAttachesMastFollowingModels) {
  Run(0.2);
  Request(21, rover_CAMERA_NAVCAM, 256);
  const rover_hw_CameraRequest hw = WaitHwRequest(1);
  EXPECT_EQ(hw.camera, rover_CAMERA_NAVCAM);
  EXPECT_EQ(hw.exposure_us, 0u);
  Run(0.04);
  Answer(hw, 1024, 1024, 4);
  const rover_ddl_StereoFrame& f = WaitFrame(1);
  EXPECT_EQ(f.request_id, 21u);  // the requester's id, not the hardware one
  EXPECT_EQ(f.camera, rover_CAMERA_NAVCAM);
  EXPECT_EQ(f.exposure_us, 1500u);
  EXPECT_EQ(f.header.stamp_ns, now_.ns);  // capture time
  EXPECT_STREQ(f.header.frame_id, "rover");
  EXPECT_EQ(f.health, rover_HEALTH_OK);
  ASSERT_EQ(f.width, 256);
  ASSERT_EQ(f.height, 256);
  ASSERT_EQ(f.left._length, 256u * 256u);
  ASSERT_EQ(f.right._length, 256u * 256u);
  for (int y = 0; y < 256; ++y) {
    for (int x = 0; x < 256; ++x) {
      const std::size_t i = static_cast<std::size_t>(y) * 256 + static_cast<std::size_t>(x);
      ASSERT_EQ(f.left._buffer[i], (5 * x + 3 * y) % 256) << x << "," << y;
      ASSERT_EQ(f.right._buffer[i], (5 * x + 3 * y + 100) % 256) << x << "," << y;
    }
  }

  // Models: the head-frame NAVCAM moved by the mast at (0.3, -0.2) and scaled to 256 px.
  const Eigen::Isometry3d head = MastHeadPose(pan_, tilt_, calibration_->mast);
  const auto& nav = calibration_->cameras[0];
  const geometry::CameraModel want_l = geometry::Scale(geometry::Transform(nav.left, head), 0.25);
  const geometry::CameraModel want_r = geometry::Scale(geometry::Transform(nav.right, head), 0.25);
  const geometry::CameraModel got_l = FromMessage(f.left_model);
  const geometry::CameraModel got_r = FromMessage(f.right_model);
  EXPECT_EQ(got_l.width(), 256);
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d p =
        head * Eigen::Vector3d(5.0 + 3.0 * u(rng), 2.0 * u(rng), 2.0 * u(rng));
    auto a = want_l.Project(p), b = got_l.Project(p);
    auto c = want_r.Project(p), d = got_r.Project(p);
    ASSERT_TRUE(a && b && c && d);
    EXPECT_LT((*a - *b).norm(), 1e-6);
    EXPECT_LT((*c - *d).norm(), 1e-6);
  }
  // The camera centres in the rover frame: 0.20 m apart, on the mast head 1.5 m up.
  const Eigen::Vector3d cl(f.left_model.c[0], f.left_model.c[1], f.left_model.c[2]);
  const Eigen::Vector3d cr(f.right_model.c[0], f.right_model.c[1], f.right_model.c[2]);
  EXPECT_NEAR((cl - cr).norm(), 0.20, 1e-12);
  EXPECT_NEAR(cl.z(), 1.5 + 0.05 * std::sin(tilt_), 1e-9);
  // The pinhole part agrees: focal length scaled by 1/4 (f = 1236.08 px at 1024).
  EXPECT_NEAR(f.left_model.fx, 1236.07734393502 / 4, 0.5);
  EXPECT_NEAR(f.left_model.pose.position.x, cl.x(), 1e-12);
}

TEST_F(CameraServiceTest, BinnedHazcamFrameKeepsBodyModels) {
  Run(0.1);
  Request(3, rover_CAMERA_FRONT_HAZCAM, 0);  // full size of whatever the camera sends
  const rover_hw_CameraRequest hw = WaitHwRequest(1);
  EXPECT_EQ(hw.camera, rover_CAMERA_FRONT_HAZCAM);
  Answer(hw, 256, 256, 1);  // a 4x4-binned frame
  const rover_ddl_StereoFrame& f = WaitFrame(1);
  EXPECT_EQ(f.width, 256);
  EXPECT_EQ(f.health, rover_HEALTH_OK);
  EXPECT_EQ(f.left._buffer[257], (5 * 1 + 3 * 1) % 256);
  const geometry::CameraModel want = geometry::Scale(calibration_->cameras[1].left, 0.25);
  const geometry::CameraModel got = FromMessage(f.left_model);
  const Eigen::Vector3d p(2.0, 0.4, -0.3);  // ground ahead of the rover
  auto a = want.Project(p), b = got.Project(p);
  ASSERT_TRUE(a && b);
  EXPECT_LT((*a - *b).norm(), 1e-6);
}

TEST_F(CameraServiceTest, InvalidRequestsReachNeitherTheCameraNorTheRequester) {
  Run(0.1);
  // Unknown camera (a raw value no CameraId names). DDS itself may refuse to send it; if it
  // goes out, the driver must reject it.
  rover_ddl_StereoRequest bad{};
  bad.request_id = 1;
  const std::int32_t seven = 7;
  std::memcpy(&bad.camera, &seven, sizeof seven);
  (void)request_.Write(bad);
  Request(2, rover_CAMERA_NAVCAM, 2048);                 // wider than the 1024 px camera
  Request(3, rover_CAMERA_REAR_HAZCAM, 0, 700'000'000);  // exposure beyond max_exposure_us
  Request(4, rover_CAMERA_FRONT_HAZCAM, 128);            // valid
  const rover_hw_CameraRequest hw = WaitHwRequest(1);
  EXPECT_EQ(hw.camera, rover_CAMERA_FRONT_HAZCAM);  // the first request sent is the valid one
  Run(0.2);
  EXPECT_EQ(hw_requests_.size(), 1u);
  EXPECT_TRUE(frames_.empty());
  EXPECT_EQ(harness_->health(), rover_HEALTH_OK);  // a bad request is not a driver fault
  // The service carries on: the valid request is answered.
  Answer(hw, 1024, 1024, 8);
  const rover_ddl_StereoFrame& f = WaitFrame(1);
  EXPECT_EQ(f.request_id, 4u);
  EXPECT_EQ(f.width, 128);
  EXPECT_EQ(f.left._buffer[1], 5);  // 1024 -> 128: 8x8 blocks
}

TEST_F(CameraServiceTest, UnansweredRequestsAndStaleJointsDegradeTheHealth) {
  Run(0.2);
  Request(5, rover_CAMERA_FRONT_HAZCAM, 0);
  const rover_hw_CameraRequest lost = WaitHwRequest(1);
  Run(1.2);  // request_timeout_s = 1 s
  EXPECT_EQ(harness_->health(), rover_HEALTH_DEGRADED);
  EXPECT_STREQ(harness_->heartbeats().back().message,
               "camera head did not answer request 5 (front_hazcam) within 1 s");
  // A late answer is ignored (no frame); the next request succeeds and clears the fault.
  Answer(lost, 1024, 1024, 4);
  Run(0.1);
  EXPECT_TRUE(frames_.empty());
  Request(6, rover_CAMERA_NAVCAM, 256);
  Answer(WaitHwRequest(2), 1024, 1024, 4);
  EXPECT_EQ(WaitFrame(1).request_id, 6u);
  Run(0.2);
  EXPECT_EQ(harness_->health(), rover_HEALTH_OK);

  // ddl/joint_state stops: the service is DEGRADED and NAVCAM frames carry the mast age.
  joints_silent_ = true;
  Run(0.4);
  EXPECT_EQ(harness_->health(), rover_HEALTH_DEGRADED);
  EXPECT_STREQ(harness_->heartbeats().back().message,
               "ddl/joint_state: no sample for more than 0.25 s (NAVCAM models cannot follow "
               "the mast)");
  Request(7, rover_CAMERA_NAVCAM, 256);
  Answer(WaitHwRequest(3), 1024, 1024, 4);
  const rover_ddl_StereoFrame& f = WaitFrame(2);
  EXPECT_EQ(f.request_id, 7u);
  EXPECT_EQ(f.health, rover_HEALTH_DEGRADED);
}

}  // namespace
}  // namespace rover::ddl::camera
