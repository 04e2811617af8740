// Stripe detection and identification: options and bad input, a drawn synthetic ramp, and
// rendered NAVCAM views of the simulated lander (one renderer for the suite) checked against
// the stripes' true corners projected with the frame's camera model.
#include "rover/apl/rendezvous/stripe_detector.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <optional>
#include <string>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lander_scene.hpp"
#include "rover/apl/rendezvous/ramp_pose.hpp"

namespace rover::apl::rendezvous {
namespace {

using testing::LanderScene;
using testing::LanderShot;
using testing::RoverView;

TEST(StripeDetectorOptionsTest, DefaultsAreValidAndBadFieldsAreNamed) {
  StripeDetectorOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.dark_ratio = 1.5;
  Status s = o.Validate();
  EXPECT_EQ(s.code(), StatusCode::kInvalidArgument);
  EXPECT_NE(s.message().find("stripes.dark_ratio"), std::string::npos) << s.message();
  o = {};
  o.bright_window_px = 40;
  s = o.Validate();
  EXPECT_NE(s.message().find("bright_window_px: 40"), std::string::npos) << s.message();
}

TEST(StripeDetectorOptionsTest, BadImagesAreInvalidArguments) {
  for (const cv::Mat& bad : {cv::Mat(), cv::Mat(64, 64, CV_8UC3, cv::Scalar::all(100)),
                             cv::Mat(64, 64, CV_16UC1, cv::Scalar(100)),
                             cv::Mat(16, 16, CV_8UC1, cv::Scalar(100))}) {
    const auto r = DetectStripes(bad);
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(r.status().message().find("gray8"), std::string::npos) << r.status().message();
  }
}

TEST(StripeDetectorOptionsTest, BlankImageGivesNoStripesWithAReason) {
  const auto r = DetectStripes(cv::Mat(256, 256, CV_8UC1, cv::Scalar(120)));
  ASSERT_TRUE(r.ok()) << r.status().message();
  EXPECT_TRUE(r->stripes.empty());
  EXPECT_FALSE(r->why.empty());
}

// A fronto-parallel ramp drawn at 4x and area-averaged: every stripe found, identified and its
// corners where they were drawn.
cv::Mat DrawRamp(int ramp, double unit_px, std::array<std::array<Eigen::Vector2d, 4>, 6>* corners) {
  const int s = 4;
  cv::Mat big(600 * s, 800 * s, CV_8UC1, cv::Scalar(50));
  const double x0 = 200, x1 = 600, ramp_x0 = 170, ramp_x1 = 630;
  double y = 500;  // bottom of the lowest stripe; stripes go up the image
  cv::rectangle(big, cv::Point(static_cast<int>(ramp_x0 * s), 40 * s),
                cv::Point(static_cast<int>(ramp_x1 * s), 560 * s), cv::Scalar(210), cv::FILLED);
  for (int i = 0; i < 6; ++i) {
    const double w = hwconfig::kRampStripeCodes[static_cast<std::size_t>(ramp)][static_cast<std::size_t>(i)] * unit_px;
    const double y_top = y - w;
    cv::rectangle(big, cv::Point(static_cast<int>(x0 * s), static_cast<int>(y_top * s)),
                  cv::Point(static_cast<int>(x1 * s) - 1, static_cast<int>(y * s) - 1), cv::Scalar(15),
                  cv::FILLED);
    // Pixel-centre convention: the edge at big-pixel boundary b is at (b / s) - 0.5.
    (*corners)[static_cast<std::size_t>(i)] = {Eigen::Vector2d(x0 - 0.5, y - 0.5), Eigen::Vector2d(x1 - 0.5, y - 0.5),
                                               Eigen::Vector2d(x1 - 0.5, y_top - 0.5),
                                               Eigen::Vector2d(x0 - 0.5, y_top - 0.5)};
    y = y_top - 5 * unit_px;
  }
  cv::Mat img;
  cv::resize(big, img, cv::Size(800, 600), 0, 0, cv::INTER_AREA);
  cv::GaussianBlur(img, img, cv::Size(0, 0), 0.7);
  return img;
}

TEST(StripeDetectorOptionsTest, SyntheticRampsAreIdentifiedWithSubPixelCorners) {
  for (int ramp = 0; ramp < 2; ++ramp) {
    for (double unit : {2.0, 6.0}) {
      std::array<std::array<Eigen::Vector2d, 4>, 6> truth;
      const cv::Mat img = DrawRamp(ramp, unit, &truth);
      const auto r = DetectStripes(img);
      ASSERT_TRUE(r.ok()) << r.status().message();
      ASSERT_EQ(r->stripes.size(), 6u) << "ramp " << ramp << " unit " << unit << ": " << r->why;
      double worst = 0.0;
      for (const auto& s : r->stripes) {
        EXPECT_EQ(s.ramp, ramp);
        for (int c = 0; c < 4; ++c) {
          EXPECT_TRUE(s.corner_valid[static_cast<std::size_t>(c)]);
          worst = std::max(worst, (s.corners[static_cast<std::size_t>(c)] -
                                   truth[static_cast<std::size_t>(s.index)][static_cast<std::size_t>(c)]).norm());
        }
      }
      std::printf("synthetic ramp %d, %.0f px per unit: worst corner error %.3f px\n", ramp, unit, worst);
      EXPECT_LT(worst, 0.35);
    }
  }
}

// ---- rendered scenes ---------------------------------------------------------------------

class StripeDetectorSceneTest : public ::testing::Test {
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

  /// Renders, detects in the left image and checks every identified stripe against the truth:
  /// its valid corners within `tol_px` of the true corners (projected). Returns the detection.
  static StripeDetection DetectAndCheck(const RoverView& view, int expected_ramp, double tol_px,
                                        std::optional<LanderShot>* shot_out = nullptr) {
    auto shot = scene_->Render(view);
    EXPECT_TRUE(shot.ok()) << shot.status().message();
    if (!shot.ok()) return {};
    auto det = DetectStripes(shot->left);
    EXPECT_TRUE(det.ok()) << det.status().message();
    if (!det.ok()) return {};
    const hwconfig::LanderDescription desc = scene_->description();
    double worst = 0.0;
    for (const auto& s : det->stripes) {
      EXPECT_EQ(s.ramp, expected_ramp) << "stripe " << s.index;
      const Eigen::Isometry3d& t = shot->ramps[static_cast<std::size_t>(s.ramp)].rover_from_ramp;
      for (int c = 0; c < 4; ++c) {
        if (!s.corner_valid[static_cast<std::size_t>(c)]) continue;
        const auto px = shot->left_model.Project(t * StripeCornerInRamp(desc, s.ramp, s.index, c, 0.003));
        EXPECT_TRUE(px.has_value());
        if (!px) continue;
        const double e = (*px - s.corners[static_cast<std::size_t>(c)]).norm();
        worst = std::max(worst, e);
        EXPECT_LT(e, tol_px) << "ramp " << s.ramp << " stripe " << s.index << " corner " << c;
      }
    }
    std::printf("view (%.2f, %.2f, yaw %.1f, tilt %.1f): %zu stripes [", view.x, view.y,
                view.yaw_deg, view.tilt_deg, det->stripes.size());
    for (const auto& s : det->stripes) std::printf(" r%ds%d:%.2f", s.ramp, s.index, s.code_measured);
    std::printf(" ] %d candidates, worst corner %.2f px, %.1f ms%s%s\n", det->candidates, worst,
                det->elapsed_ms, det->why.empty() ? "" : ", why: ", det->why.c_str());
    // ROVER_STRIPES_DEBUG_DIR=<folder>: every view with its detection drawn, for inspection.
    if (const char* dir = std::getenv("ROVER_STRIPES_DEBUG_DIR"); dir && *dir) {
      static int n = 0;
      cv::Mat bgr;
      cv::cvtColor(shot->left, bgr, cv::COLOR_GRAY2BGR);
      DrawStripeDetection(&bgr, *det);
      cv::imwrite(std::string(dir) + "/view" + std::to_string(n++) + ".png", bgr);
    }
    if (shot_out) shot_out->emplace(std::move(*shot));
    return *det;
  }

  static LanderScene* scene_;
  static std::string* setup_error_;
};
LanderScene* StripeDetectorSceneTest::scene_ = nullptr;
std::string* StripeDetectorSceneTest::setup_error_ = nullptr;

TEST_F(StripeDetectorSceneTest, AllSixOnAxisFromThreeToEightMetres) {
  for (double d : {3.0, 5.0, 8.0}) {
    const StripeDetection det = DetectAndCheck(scene_->ViewOfRamp(0, d, 0.0), 0, 1.5);
    EXPECT_EQ(det.stripes.size(), 6u) << "at " << d << " m: " << det.why;
  }
}

TEST_F(StripeDetectorSceneTest, CloseAndObliqueViews) {
  // 2 m from the base: the whole ramp still fits the 45 deg NAVCAM.
  EXPECT_GE(DetectAndCheck(scene_->ViewOfRamp(0, 2.0, 0.0), 0, 1.5).stripes.size(), 4u);
  for (double off : {-40.0, 25.0, 40.0}) {
    const StripeDetection det = DetectAndCheck(scene_->ViewOfRamp(0, 4.0, off), 0, 1.5);
    EXPECT_GE(det.stripes.size(), 4u) << off << " deg off axis: " << det.why;
  }
}

TEST_F(StripeDetectorSceneTest, PartialViewStillIdentifies) {
  // Turned so that the ramp's left part leaves the frame.
  RoverView v = scene_->ViewOfRamp(0, 3.0, 0.0, -14.0);
  const StripeDetection det = DetectAndCheck(v, 0, 1.5);
  EXPECT_GE(det.stripes.size(), 2u) << det.why;
  int invalid = 0;
  for (const auto& s : det.stripes) {
    for (bool ok : s.corner_valid) invalid += ok ? 0 : 1;
  }
  std::printf("partial view: %d corners not valid\n", invalid);
}

TEST_F(StripeDetectorSceneTest, TheOtherRampIsRampOne) {
  const StripeDetection det = DetectAndCheck(scene_->ViewOfRamp(1, 4.0, 10.0), 1, 1.5);
  EXPECT_EQ(det.stripes.size(), 6u) << det.why;
  EXPECT_EQ(det.BestRamp(), 1);
}

TEST_F(StripeDetectorSceneTest, NoLanderInViewGivesNoStripes) {
  // At ramp 0's base looking away from the lander, and from the side at the truss.
  RoverView away = scene_->ViewOfRamp(0, 4.0, 0.0, 180.0);
  away.tilt_deg = -20.0;
  StripeDetection det = DetectAndCheck(away, -1, 1.0);
  EXPECT_TRUE(det.stripes.empty());
  EXPECT_FALSE(det.why.empty());
  RoverView side;
  side.x = 0.0;
  side.y = 6.0;
  side.yaw_deg = -90.0;
  side.tilt_deg = -12.0;
  det = DetectAndCheck(side, -1, 1.0);
  EXPECT_TRUE(det.stripes.empty());
  EXPECT_FALSE(det.why.empty());
}

TEST_F(StripeDetectorSceneTest, DrawsTheDetection) {
  std::optional<LanderShot> shot;
  const StripeDetection det = DetectAndCheck(scene_->ViewOfRamp(0, 4.0, 25.0), 0, 1.5, &shot);
  ASSERT_TRUE(shot.has_value());
  cv::Mat bgr;
  cv::cvtColor(shot->left, bgr, cv::COLOR_GRAY2BGR);
  DrawStripeDetection(&bgr, det);
  EXPECT_EQ(bgr.type(), CV_8UC3);
  // ROVER_WRITE_DOC_IMAGES=1 refreshes the design page's picture (cropped, PNG).
  if (const char* w = std::getenv("ROVER_WRITE_DOC_IMAGES"); w && std::string(w) == "1") {
    const cv::Rect roi(262, 470, 540, 290);  // the stripes of this view
    cv::imwrite(std::string(ROVER_SOURCE_DIR) + "/apl/rendezvous/doc/stripes_detection.png",
                bgr(roi & cv::Rect(0, 0, bgr.cols, bgr.rows)));
  }
}

}  // namespace
}  // namespace rover::apl::rendezvous
