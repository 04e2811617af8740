// Mid-range lander detection on rendered NAVCAM pairs with the simulator's truth: range and
// bearing errors over 5..30 m and several sides of the lander (the ramp-facing views must be
// found at 10..30 m), campaign-like ramp-facing views at 25..30 m, a sun variation, views
// without the lander, and bad input. Set ROVER_LANDER_DRAW=<file.png> to save the ~20 m sighting drawn.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lander_scene.hpp"
#include "rover/apl/rendezvous/lander_detector.hpp"
#include "rover/base/units.hpp"

namespace rover::apl::rendezvous {
namespace {

using testing::LanderScene;
using testing::LanderSceneOptions;
using testing::LanderShot;
using testing::RoverView;

struct Case {
  double distance;  // [m] rover to deck centre
  double side_deg;  // where the rover stands around the lander, from ramp 0's axis
};

struct Errors {
  double range_error = 0.0;    // [m] estimate - truth
  double bearing_error = 0.0;  // [rad]
  double truth_range = 0.0;
  LanderSighting sighting;
};

class LanderDetectorSceneTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    LanderSceneOptions o;
    o.size = 70.0;  // views up to 30 m from the centre in every direction
    auto scene = LanderScene::Create(o);
    ASSERT_TRUE(scene.ok()) << scene.status().ToString();
    scene_ = std::move(scene).value().release();
  }
  static void TearDownTestSuite() {
    delete scene_;
    scene_ = nullptr;
  }

  // The rover `distance` m from the deck centre at `side_deg` around it, facing the lander.
  static RoverView ViewAt(double distance, double side_deg, double yaw_offset_deg = 0.0) {
    const auto& l = scene_->lander();
    const double yaw0 = l.params.yaw_deg;
    const double a = (yaw0 + side_deg) * kDegree;
    RoverView v;
    v.x = l.params.x + distance * std::cos(a);
    v.y = l.params.y + distance * std::sin(a);
    v.yaw_deg = yaw0 + side_deg + 180.0 + yaw_offset_deg;
    v.tilt_deg = distance < 8.0 ? -10.0 : -3.0;
    return v;
  }

  static Errors Measure(const LanderShot& shot) {
    Errors e;
    auto s = DetectLander(shot.left, shot.right, shot.left_model, &shot.right_model,
                          scene_->description());
    EXPECT_TRUE(s.ok()) << s.status().ToString();
    if (!s.ok()) return e;
    e.sighting = *s;
    const auto& l = scene_->lander();
    const Eigen::Vector3d c =
        shot.site_from_rover.inverse() * Eigen::Vector3d(l.params.x, l.params.y, l.deck_z);
    e.truth_range = std::hypot(c.x(), c.y());
    if (s->found) {
      e.range_error = s->range - e.truth_range;
      e.bearing_error = std::remainder(s->bearing - std::atan2(c.y(), c.x()), 2.0 * kPi);
    }
    return e;
  }

  static LanderScene* scene_;
};

LanderScene* LanderDetectorSceneTest::scene_ = nullptr;

TEST_F(LanderDetectorSceneTest, RangeAndBearingOverDistancesAndSides) {
  const std::vector<double> distances = {5, 10, 15, 20, 25, 30};
  // 0: along the ramps (one faces the rover, one away), 90: side-on, 30: oblique.
  const std::vector<double> sides = {0, 30, 90, 180};
  std::printf("  dist  side   found  range   err[m]  err[%%]  sigma   mono    stereo  bear.err[deg]  ms   features\n");
  double worst_stereo_pct = 0.0, worst_bearing = 0.0;
  double worst_ramp_pct_25 = 0.0, worst_ramp_pct_30 = 0.0;  // ramp-facing, 10..25 m and 30 m
  int found = 0, total = 0, stereo_used = 0, ramp_facing_found = 0;
  for (double d : distances) {
    for (double side : sides) {
      if (side == 180 && d != 15 && d != 25) continue;  // the far side once or twice is enough
      auto shot = scene_->Render(ViewAt(d, side));
      ASSERT_TRUE(shot.ok()) << shot.status().ToString();
      const Errors e = Measure(*shot);
      ++total;
      const auto& s = e.sighting;
      const double pct = 100.0 * std::abs(e.range_error) / e.truth_range;
      std::printf("  %4.0f  %4.0f  %5s  %6.2f  %7.3f  %6.2f  %5.2f  %6.2f  %6.2f  %8.3f  %6.0f   %s\n", d,
                  side, s.found ? "yes" : "NO", s.range, e.range_error, pct, s.range_sigma,
                  s.range_monocular, s.range_stereo, e.bearing_error / kDegree, s.elapsed_ms,
                  s.found ? s.features.c_str() : s.reason.c_str());
      if (side == 0.0 && d >= 10.0) {
        EXPECT_TRUE(s.found) << "ramp facing at " << d << " m: " << s.reason;
      }
      if (!s.found) continue;
      ++found;
      if (side == 0.0 && d >= 10.0) {
        ++ramp_facing_found;
        double& worst = d <= 25.0 ? worst_ramp_pct_25 : worst_ramp_pct_30;
        worst = std::max(worst, pct);
      }
      if (s.range_stereo > 0.0 && d >= 10.0) {
        worst_stereo_pct = std::max(worst_stereo_pct, pct);
        worst_bearing = std::max(worst_bearing, std::abs(e.bearing_error));
        ++stereo_used;
      }
      if (d == 20.0 && side == 30.0) {
        if (const char* path = std::getenv("ROVER_LANDER_DRAW")) {
          cv::Mat bgr;
          cv::cvtColor(shot->left, bgr, cv::COLOR_GRAY2BGR);
          DrawLanderSighting(&bgr, s);
          // The lander's neighbourhood (keeps the picture small).
          const cv::Rect crop = cv::Rect(s.box.x + s.box.width / 2 - 280, s.box.y - 150, 560, 330) &
                                cv::Rect(0, 0, bgr.cols, bgr.rows);
          cv::imwrite(path, bgr(crop));
        }
      }
    }
  }
  std::printf("found %d of %d; stereo used in %d (10..30 m): worst range error %.2f %%, worst "
              "bearing error %.3f deg; ramp facing found %d of 5, worst %.2f %% (10..25 m), "
              "%.2f %% (30 m)\n",
              found, total, stereo_used, worst_stereo_pct, worst_bearing / kDegree,
              ramp_facing_found, worst_ramp_pct_25, worst_ramp_pct_30);
  // Bounds from the measured table (doc/lander_lines.md) with margin. Known weakness: oblique
  // views at 5..15 m are missed, and monocular-only ranges are off by up to ~60 %.
  EXPECT_GE(found, 14);
  EXPECT_GE(stereo_used, 13);
  EXPECT_EQ(ramp_facing_found, 5);
  EXPECT_LT(worst_ramp_pct_25, 1.6);  // measured 1.11 % (10 m, deck band and truss)
  EXPECT_LT(worst_ramp_pct_30, 3.0);  // measured 1.93 %
  EXPECT_LT(worst_stereo_pct, 4.0);
  EXPECT_LT(worst_bearing, 0.5 * kDegree);
}

TEST_F(LanderDetectorSceneTest, NoLanderInViewIsNotFound) {
  // The rover looks away from the lander (180 deg) or well to one side of it (+-60 deg; the
  // NAVCAM's half field is ~24 deg): rocks, shadows and the horizon only.
  struct Away {
    double distance, side_deg, yaw_offset_deg;
  };
  for (const Away& a : {Away{10, 90, 180}, Away{20, 90, 180}, Away{30, 0, 180}, Away{15, 0, 60},
                        Away{25, 0, -60}, Away{25, 30, 60}}) {
    auto shot = scene_->Render(ViewAt(a.distance, a.side_deg, a.yaw_offset_deg));
    ASSERT_TRUE(shot.ok()) << shot.status().ToString();
    auto s = DetectLander(shot->left, shot->right, shot->left_model, &shot->right_model,
                          scene_->description());
    ASSERT_TRUE(s.ok()) << s.status().ToString();
    EXPECT_FALSE(s->found) << "at " << a.distance << " m, side " << a.side_deg << ", yaw "
                           << a.yaw_offset_deg << ": " << s->features << " range " << s->range;
    std::printf("no lander, %.0f m side %.0f yaw %+.0f: %s (%.0f ms)\n", a.distance, a.side_deg,
                a.yaw_offset_deg, s->reason.c_str(), s->elapsed_ms);
  }
}

// The campaign's failed sightings (deploy/scenarios/lander_return_30m.yaml: ramp 0 pointing
// straight at the rover 25..30 m away, VL-1-like rocks, mast tilt -3 deg), rendered with other
// terrain seeds and noise frames than the suite's scene.
TEST(LanderDetectorCampaignTest, RampFacingAt25To30m) {
  for (std::uint64_t seed : {3u, 5u}) {
    LanderSceneOptions o;
    o.seed = seed;
    o.size = 70.0;
    o.lander_yaw_deg = 180.0;  // ramp 0 descends towards -x, where the rover stands
    auto scene = LanderScene::Create(o);
    ASSERT_TRUE(scene.ok()) << scene.status().ToString();
    for (double d : {25.0, 27.5, 30.0}) {
      RoverView v;
      v.x = -d;
      v.y = 0.0;
      v.yaw_deg = 0.0;
      v.tilt_deg = -3.0;
      v.frame = static_cast<std::uint64_t>(d * 10.0);
      auto shot = (*scene)->Render(v);
      ASSERT_TRUE(shot.ok()) << shot.status().ToString();
      auto s = DetectLander(shot->left, shot->right, shot->left_model, &shot->right_model,
                            (*scene)->description());
      ASSERT_TRUE(s.ok()) << s.status().ToString();
      const auto& l = (*scene)->lander();
      const Eigen::Vector3d c =
          shot->site_from_rover.inverse() * Eigen::Vector3d(l.params.x, l.params.y, l.deck_z);
      const double truth = std::hypot(c.x(), c.y());
      const double bearing_err =
          std::remainder(s->bearing - std::atan2(c.y(), c.x()), 2.0 * kPi) / kDegree;
      std::printf("campaign-like seed %d, %.1f m: found %d range %.2f (truth %.2f, %.2f %%) "
                  "bearing err %.3f deg, %.0f ms: %s\n",
                  static_cast<int>(seed), d, s->found ? 1 : 0, s->range, truth,
                  s->found ? 100.0 * (s->range - truth) / truth : 0.0, s->found ? bearing_err : 0.0,
                  s->elapsed_ms, s->found ? s->features.c_str() : s->reason.c_str());
      ASSERT_TRUE(s->found) << "seed " << seed << ", " << d << " m: " << s->reason;
      // Measured: <= 0.55 % at 25-27.5 m, <= 1.40 % at 30 m; bearing <= 0.10 deg.
      EXPECT_NEAR(s->range, truth, (d <= 25.0 ? 0.02 : 0.03) * truth);
      EXPECT_LT(std::abs(bearing_err), 0.5);
    }
  }
}

TEST_F(LanderDetectorSceneTest, MonocularWithoutRightImage) {
  auto shot = scene_->Render(ViewAt(20.0, 90.0));
  ASSERT_TRUE(shot.ok()) << shot.status().ToString();
  // Monocular only (no right image): found, range within the monocular error.
  auto s = DetectLander(shot->left, cv::Mat(), shot->left_model, nullptr, scene_->description());
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  ASSERT_TRUE(s->found) << s->reason;
  const Errors e = Measure(*shot);
  std::printf("monocular 20 m side-on: %.2f m (stereo %.2f m, truth %.2f m)\n", s->range,
              e.sighting.range, e.truth_range);
  EXPECT_NEAR(s->range, e.truth_range, 0.2 * e.truth_range);
}

class LanderDetectorSunTest : public ::testing::Test {};

TEST_F(LanderDetectorSunTest, LowMorningSun) {
  LanderSceneOptions o;
  o.size = 50.0;
  o.sun_azimuth_deg = 60.0;
  o.sun_elevation_deg = 20.0;
  auto scene = LanderScene::Create(o);
  ASSERT_TRUE(scene.ok()) << scene.status().ToString();
  RoverView v;
  v.x = 0.0;
  v.y = 20.0;  // side-on to the ramps, 20 m out
  v.yaw_deg = -90.0;
  v.tilt_deg = -3.0;
  auto shot = (*scene)->Render(v);
  ASSERT_TRUE(shot.ok()) << shot.status().ToString();
  auto s = DetectLander(shot->left, shot->right, shot->left_model, &shot->right_model,
                        (*scene)->description());
  ASSERT_TRUE(s.ok()) << s.status().ToString();
  const auto& l = (*scene)->lander();
  const Eigen::Vector3d c =
      shot->site_from_rover.inverse() * Eigen::Vector3d(l.params.x, l.params.y, l.deck_z);
  const double truth = std::hypot(c.x(), c.y());
  std::printf("low sun, 20 m: found %d range %.2f (truth %.2f) %s\n", s->found ? 1 : 0, s->range,
              truth, s->features.c_str());
  // Known weakness (doc/lander_lines.md): with this low sun the deck is not always confirmed;
  // when it is reported it must be right.
  if (s->found) {
    EXPECT_NEAR(s->range, truth, 0.04 * truth);
  }
}

TEST(LanderDetectorInputTest, BadInputIsInvalidArgument) {
  geometry::Cahv m;
  m.c = Eigen::Vector3d(0, 0, 1.5);
  m.a = Eigen::Vector3d::UnitX();
  m.h = Eigen::Vector3d(31.5, -100.0, 0.0);
  m.v = Eigen::Vector3d(23.5, 0.0, -100.0);
  auto model = geometry::CameraModel::Create(m, 64, 48);
  ASSERT_TRUE(model.ok()) << model.status().ToString();
  const hwconfig::LanderDescription lander;
  const cv::Mat good(48, 64, CV_8UC1, cv::Scalar(80));
  auto expect_invalid = [](const Result<LanderSighting>& r, const std::string& word) {
    ASSERT_FALSE(r.ok());
    EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
    EXPECT_NE(r.status().ToString().find(word), std::string::npos) << r.status().ToString();
  };
  expect_invalid(DetectLander(cv::Mat(), cv::Mat(), *model, nullptr, lander), "left image");
  expect_invalid(DetectLander(cv::Mat(40, 64, CV_8UC1), cv::Mat(), *model, nullptr, lander),
                 "left image");
  expect_invalid(DetectLander(good, good, *model, nullptr, lander), "right image");
  expect_invalid(DetectLander(good, cv::Mat(48, 60, CV_8UC1), *model, &*model, lander),
                 "right image");
  LanderPrior prior;
  prior.bearing = std::nan("");
  expect_invalid(DetectLander(good, cv::Mat(), *model, nullptr, lander, {}, prior),
                 "prior.bearing");
  LanderDetectorOptions bad;
  bad.max_range = 1.0;
  expect_invalid(DetectLander(good, cv::Mat(), *model, nullptr, lander, bad), "max_range");
  LanderDetectorOptions bad_ramp;
  bad_ramp.min_ramp_edges = 2;  // 0 (off) or 3..12
  expect_invalid(DetectLander(good, cv::Mat(), *model, nullptr, lander, bad_ramp),
                 "min_ramp_edges");
  bad_ramp.min_ramp_edges = 0;
  EXPECT_TRUE(bad_ramp.Validate().ok());
  bad_ramp.min_ramp_contrast = -1.0;
  expect_invalid(DetectLander(good, cv::Mat(), *model, nullptr, lander, bad_ramp),
                 "min_ramp_contrast");
  // A blank image is valid input without a lander.
  auto blank = DetectLander(good, good, *model, &*model, lander);
  ASSERT_TRUE(blank.ok());
  EXPECT_FALSE(blank->found);
}

}  // namespace
}  // namespace rover::apl::rendezvous
