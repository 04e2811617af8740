#include "rover/ddl/camera/camera_driver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace rover::ddl::camera {
namespace {

constexpr int kSize = 64;

// A small calibration: a 64 x 64 CAHVOR navcam on the mast head, two CAHV hazcams on the body.
geometry::CameraModel Cam(const Eigen::Vector3d& c, const Eigen::Matrix3d& r, double f) {
  geometry::Cahvor m;
  m.c = c;
  m.a = r.col(0);
  m.h = f * (-r.col(1)) + 31.5 * m.a;
  m.v = f * (-r.col(2)) + 31.5 * m.a;
  m.o = m.a;
  m.r = Eigen::Vector3d(0.0, -0.01, 0.0);
  return *geometry::CameraModel::Create(m, kSize, kSize);
}

CameraCalibration SmallCalibration() {
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d down =
      Eigen::AngleAxisd(0.785398163397448, Eigen::Vector3d::UnitY()).toRotationMatrix();
  CameraCalibration cal;
  cal.cameras.push_back({"navcam", CameraMount::kMastHead, Cam({0.05, 0.1, 0}, id, 77.0),
                         Cam({0.05, -0.1, 0}, id, 77.0)});
  cal.cameras.push_back({"front_hazcam", CameraMount::kBody, Cam({0.52, 0.05, 0.5}, down, 20.0),
                         Cam({0.52, -0.05, 0.5}, down, 20.0)});
  cal.cameras.push_back({"rear_hazcam", CameraMount::kBody, Cam({-0.52, -0.05, 0.5}, down, 20.0),
                         Cam({-0.52, 0.05, 0.5}, down, 20.0)});
  return cal;
}

CameraDriver Driver(CameraDriverOptions o = {}) {
  auto d = CameraDriver::Create(SmallCalibration(), o);
  EXPECT_TRUE(d.ok()) << d.status().message();
  return std::move(*d);
}

Time T(double s) { return Time::FromSeconds(s); }

msg::StereoRequest Req(std::uint32_t id, int camera, std::uint32_t exposure_us, int width) {
  msg::StereoRequest r;
  r.request_id = id;
  r.camera = static_cast<msg::CameraId>(camera);
  r.exposure_us = exposure_us;
  r.width = width;
  return r;
}

// An image of 4 x 4 blocks of constant value (block (i, j) = 5 i + 3 j + offset).
std::vector<std::uint8_t> Blocks(int w, int h, int block, int offset) {
  std::vector<std::uint8_t> px(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      px[static_cast<std::size_t>(y * w + x)] =
          static_cast<std::uint8_t>(5 * (x / block) + 3 * (y / block) + offset);
    }
  }
  return px;
}

struct Frame {
  std::vector<std::uint8_t> left, right;
  hw::CameraFrame view;
};
Frame MakeFrame(std::uint32_t hw_id, int camera, int w, int h, double stamp_s) {
  Frame f;
  f.left = Blocks(w, h, 4, 0);
  f.right = Blocks(w, h, 4, 100);
  f.view = {T(stamp_s).ns, hw_id, camera, 1234, w, h, f.left, f.right};
  return f;
}

TEST(CameraDriver, RejectsBadRequestsNamingFieldValueAndRange) {
  CameraDriver d = Driver();
  auto r = d.HandleRequest(Req(7, 3, 0, 0), T(1));
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("request 7: camera 3 is not one of 0 (navcam)"),
            std::string::npos)
      << r.status().message();
  r = d.HandleRequest(Req(8, 0, 0, kSize + 1), T(1));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("width 65 is out of range [0, 64] for navcam"),
            std::string::npos)
      << r.status().message();
  EXPECT_FALSE(d.HandleRequest(Req(9, 0, 0, -1), T(1)).ok());
  r = d.HandleRequest(Req(10, 1, 20'000'000, 0), T(1));
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("exposure_us 20000000"), std::string::npos);
  EXPECT_EQ(d.pending(), 0u);
}

TEST(CameraDriver, BusyBeyondMaxPendingAndExpiresUnansweredRequests) {
  CameraDriverOptions o;
  o.max_pending = 2;
  o.request_timeout_s = 1.0;
  CameraDriver d = Driver(o);
  ASSERT_TRUE(d.HandleRequest(Req(1, 0, 0, 0), T(1)).ok());
  ASSERT_TRUE(d.HandleRequest(Req(2, 1, 0, 0), T(1.5)).ok());
  EXPECT_EQ(d.HandleRequest(Req(3, 1, 0, 0), T(1.6)).status().code(), StatusCode::kBusy);
  EXPECT_TRUE(d.ExpireRequests(T(2.0)).empty());
  auto expired = d.ExpireRequests(T(2.1));
  ASSERT_EQ(expired.size(), 1u);
  EXPECT_EQ(expired[0].request.request_id, 1u);
  EXPECT_EQ(d.pending(), 1u);
  EXPECT_TRUE(d.HandleRequest(Req(3, 1, 0, 0), T(2.1)).ok());
}

TEST(CameraDriver, HardwareIdsAreTheDriversOwnAndFramesEchoTheRequesterId) {
  CameraDriver d = Driver();
  auto a = d.HandleRequest(Req(5, 1, 0, 0), T(1));
  auto b = d.HandleRequest(Req(5, 2, 0, 0), T(1));  // another requester, same id
  ASSERT_TRUE(a.ok() && b.ok());
  EXPECT_NE(a->request_id, b->request_id);
  EXPECT_EQ(a->camera, 1);
  Frame f = MakeFrame(b->request_id, 2, kSize, kSize, 1.1);
  auto out = d.HandleFrame(f.view);
  ASSERT_TRUE(out.ok()) << out.status().message();
  EXPECT_EQ(out->request_id, 5u);
  EXPECT_EQ(out->camera, 2);
  EXPECT_EQ(out->exposure_us, 1234u);
  EXPECT_EQ(d.pending(), 1u);
  // The same frame again, or one for an id never issued: not ours.
  EXPECT_EQ(d.HandleFrame(f.view).status().code(), StatusCode::kNotFound);
  Frame g = MakeFrame(999, 1, kSize, kSize, 1.1);
  EXPECT_EQ(d.HandleFrame(g.view).status().code(), StatusCode::kNotFound);
}

TEST(CameraDriver, DownsamplesAndAttachesNavcamModelsAtTheInterpolatedMastPose) {
  CameraDriver d = Driver();
  ASSERT_TRUE(d.HandleMast({T(1.00).ns, 0.0, -0.2}).ok());
  ASSERT_TRUE(d.HandleMast({T(1.02).ns, 0.2, -0.4}).ok());
  auto hw = d.HandleRequest(Req(42, 0, 0, 16), T(1.0));
  ASSERT_TRUE(hw.ok());
  Frame f = MakeFrame(hw->request_id, 0, kSize, kSize, 1.01);
  auto out = d.HandleFrame(f.view);
  ASSERT_TRUE(out.ok()) << out.status().message();
  EXPECT_EQ(out->health, msg::SensorHealth::kOk) << out->health_reason;
  EXPECT_NEAR(out->mast_pan, 0.1, 1e-12);
  EXPECT_NEAR(out->mast_tilt, -0.3, 1e-12);
  EXPECT_EQ(out->stamp_ns, T(1.01).ns);

  // 64 -> 16: each output pixel is the mean of one 4 x 4 block.
  const GrayImage& l = out->pair.left;
  ASSERT_EQ(l.width, 16);
  ASSERT_EQ(l.height, 16);
  for (int y = 0; y < 16; ++y) {
    for (int x = 0; x < 16; ++x) {
      ASSERT_EQ(l.pixels[static_cast<std::size_t>(y * 16 + x)], 5 * x + 3 * y);
      ASSERT_EQ(out->pair.right.pixels[static_cast<std::size_t>(y * 16 + x)], 5 * x + 3 * y + 100);
    }
  }

  // Models: the head-frame calibration moved by the mast at (0.1, -0.3) and scaled by 1/4.
  const CameraCalibration cal = SmallCalibration();
  const Eigen::Isometry3d pose = MastHeadPose(0.1, -0.3, cal.mast);
  const geometry::CameraModel want_l =
      geometry::Scale(geometry::Transform(cal.cameras[0].left, pose), 0.25);
  const geometry::CameraModel want_r =
      geometry::Scale(geometry::Transform(cal.cameras[0].right, pose), 0.25);
  EXPECT_EQ(out->pair.left_model.width(), 16);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 50; ++i) {
    // Points in front of the head, expressed in the rover frame.
    const Eigen::Vector3d p = pose * Eigen::Vector3d(3.0 + u(rng), u(rng), 0.5 * u(rng));
    auto a = want_l.Project(p), b = out->pair.left_model.Project(p);
    auto c = want_r.Project(p), e = out->pair.right_model.Project(p);
    ASSERT_TRUE(a && b && c && e);
    EXPECT_LT((*a - *b).norm(), 1e-9);
    EXPECT_LT((*c - *e).norm(), 1e-9);
  }
  // The message fields describe the same models.
  auto fields = msg::CameraModelFieldsFromModel(want_l);
  ASSERT_TRUE(fields.ok());
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(out->left_fields.c[static_cast<std::size_t>(k)],
                fields->c[static_cast<std::size_t>(k)], 1e-12);
    EXPECT_NEAR(out->left_fields.h[static_cast<std::size_t>(k)],
                fields->h[static_cast<std::size_t>(k)], 1e-9);
  }
  EXPECT_NEAR(out->left_fields.fx, fields->fx, 1e-9);
  EXPECT_EQ(out->left_fields.width, 16);
}

TEST(CameraDriver, MastAgeDecidesTheHealthOfNavcamFramesOnly) {
  CameraDriver d = Driver();
  // No mast sample at all: navcam models unknown -> FAILED; a hazcam does not care.
  auto nav = d.HandleRequest(Req(1, 0, 0, 0), T(1));
  auto haz = d.HandleRequest(Req(2, 1, 0, 0), T(1));
  ASSERT_TRUE(nav.ok() && haz.ok());
  Frame fn = MakeFrame(nav->request_id, 0, kSize, kSize, 1.0);
  Frame fh = MakeFrame(haz->request_id, 1, kSize, kSize, 1.0);
  auto on = d.HandleFrame(fn.view);
  auto oh = d.HandleFrame(fh.view);
  ASSERT_TRUE(on.ok() && oh.ok());
  EXPECT_EQ(on->health, msg::SensorHealth::kFailed);
  EXPECT_NE(on->health_reason.find("mast pose unknown"), std::string::npos);
  EXPECT_EQ(oh->health, msg::SensorHealth::kOk);

  // A mast sample 0.5 s before the capture: DEGRADED, using that sample.
  ASSERT_TRUE(d.HandleMast({T(2.0).ns, 0.3, 0.1}).ok());
  nav = d.HandleRequest(Req(3, 0, 0, 0), T(2.5));
  fn = MakeFrame(nav->request_id, 0, kSize, kSize, 2.5);
  on = d.HandleFrame(fn.view);
  ASSERT_TRUE(on.ok());
  EXPECT_EQ(on->health, msg::SensorHealth::kDegraded);
  EXPECT_NEAR(on->mast_pan, 0.3, 1e-15);
  // Within mast_max_age_s: OK.
  ASSERT_TRUE(d.HandleMast({T(2.45).ns, 0.3, 0.1}).ok());
  nav = d.HandleRequest(Req(4, 0, 0, 0), T(2.5));
  fn = MakeFrame(nav->request_id, 0, kSize, kSize, 2.5);
  on = d.HandleFrame(fn.view);
  ASSERT_TRUE(on.ok());
  EXPECT_EQ(on->health, msg::SensorHealth::kOk);
  // Non-finite angles are refused; older samples ignored.
  EXPECT_EQ(d.HandleMast({T(3).ns, std::nan(""), 0.0}).code(), StatusCode::kInvalidArgument);
  EXPECT_TRUE(d.HandleMast({T(1).ns, 9.0, 9.0}).ok());
  d.Reset();
  nav = d.HandleRequest(Req(5, 0, 0, 0), T(2.5));
  fn = MakeFrame(nav->request_id, 0, kSize, kSize, 2.5);
  on = d.HandleFrame(fn.view);
  ASSERT_TRUE(on.ok());
  EXPECT_EQ(on->health, msg::SensorHealth::kFailed);  // Reset forgot the mast history
}

TEST(CameraDriver, CorruptFramesAreRejectedAndEndTheirRequest) {
  CameraDriver d = Driver();
  auto hw = d.HandleRequest(Req(1, 1, 0, 0), T(1));
  Frame f = MakeFrame(hw->request_id, 1, kSize, kSize, 1.0);
  f.view.right = f.view.right.subspan(1);
  auto out = d.HandleFrame(f.view);
  EXPECT_EQ(out.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(out.status().message().find("4096 left and 4095 right bytes for a 64x64 image"),
            std::string::npos)
      << out.status().message();
  EXPECT_EQ(d.pending(), 0u);

  hw = d.HandleRequest(Req(2, 1, 0, 0), T(1));
  f = MakeFrame(hw->request_id, 2, kSize, kSize, 1.0);  // wrong camera
  EXPECT_NE(d.HandleFrame(f.view).status().message().find("front_hazcam was requested"),
            std::string::npos);
  hw = d.HandleRequest(Req(3, 1, 0, 0), T(1));
  f = MakeFrame(hw->request_id, 1, 60, 64, 1.0);  // not a binning of 64x64
  EXPECT_NE(d.HandleFrame(f.view).status().message().find("image size 60x64 is not 64x64"),
            std::string::npos);
  hw = d.HandleRequest(Req(4, 1, 0, 0), T(1));
  f = MakeFrame(hw->request_id, 1, 0, 0, 1.0);
  EXPECT_EQ(d.HandleFrame(f.view).status().code(), StatusCode::kInvalidArgument);
  EXPECT_EQ(d.pending(), 0u);
}

TEST(CameraDriver, BinnedFramesGetScaledModelsAndTooWideRequestsGoFullSize) {
  CameraDriver d = Driver();
  auto hw = d.HandleRequest(Req(1, 1, 0, 48), T(1));  // valid for the 64 px calibration
  ASSERT_TRUE(hw.ok());
  Frame f = MakeFrame(hw->request_id, 1, 32, 32, 1.0);  // the camera sends 2x2-binned frames
  auto out = d.HandleFrame(f.view);
  ASSERT_TRUE(out.ok()) << out.status().message();
  EXPECT_EQ(out->pair.left.width, 32);
  EXPECT_NE(out->note.find("requested width 48 is larger than the 32 px frame"), std::string::npos);
  const geometry::CameraModel want = geometry::Scale(SmallCalibration().cameras[1].left, 0.5);
  const Eigen::Vector3d p(2.0, 0.3, -0.2);
  auto a = want.Project(p), b = out->pair.left_model.Project(p);
  ASSERT_TRUE(a && b);
  EXPECT_LT((*a - *b).norm(), 1e-9);
}

TEST(CameraDriver, OptionsAreValidated) {
  CameraDriverOptions o;
  o.request_timeout_s = 0.0;
  EXPECT_FALSE(CameraDriver::Create(SmallCalibration(), o).ok());
  o = {};
  o.mast_history_s = 0.01;
  EXPECT_FALSE(CameraDriver::Create(SmallCalibration(), o).ok());
  CameraCalibration two = SmallCalibration();
  two.cameras.pop_back();
  EXPECT_FALSE(CameraDriver::Create(two, {}).ok());
}

TEST(CameraDriver, AsksForTheLargestBinningThatStillCoversTheRequestedWidth) {
  CameraDriver d = Driver();  // 64 px calibration
  auto full = d.HandleRequest(Req(1, 1, 0, 0), T(1));
  ASSERT_TRUE(full.ok());
  EXPECT_EQ(full->readout_width, 0);  // width 0: the full frame
  auto quarter = d.HandleRequest(Req(2, 1, 0, 16), T(1));
  ASSERT_TRUE(quarter.ok());
  EXPECT_EQ(quarter->readout_width, 16);  // 4 x 4 binning
  auto odd = d.HandleRequest(Req(3, 1, 0, 20), T(1));
  ASSERT_TRUE(odd.ok());
  EXPECT_EQ(odd->readout_width, 32);  // 2 x 2, then 32 -> 20 in software
  EXPECT_EQ(d.ReadoutFor(64, 64), 0);
  EXPECT_EQ(d.ReadoutFor(256, 1024), 256);
  EXPECT_EQ(d.ReadoutFor(512, 1024), 512);
  EXPECT_EQ(d.ReadoutFor(100, 1024), 128);  // 8 x 8 is the most by default
  EXPECT_EQ(d.ReadoutFor(100, 1000), 125);  // binnings must divide the sensor width
  CameraDriverOptions o;
  o.max_binning = 1;
  auto no_binning = CameraDriver::Create(SmallCalibration(), o);
  ASSERT_TRUE(no_binning.ok());
  EXPECT_EQ(no_binning->ReadoutFor(16, 64), 0);  // always the full frame
  o.max_binning = 0;
  auto bad = CameraDriver::Create(SmallCalibration(), o);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("max_binning: 0 is out of range [1, 16]"),
            std::string::npos)
      << bad.status().message();
}

}  // namespace
}  // namespace rover::ddl::camera
