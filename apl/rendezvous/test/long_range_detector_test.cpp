// Long-range lander acquisition on rendered NAVCAM images with the simulator's truth: views from
// 25 to 125 m over a long map with layered outcrops (the distractors) in the search window. It
// prints, per range band, the candidates of each cue alone and fused with the true and false ones
// (a candidate is true when its box overlaps the lander's projected box), and checks that the
// fused detector finds the lander in most views, never reports a distractor, and measures the
// bearing within 2.5 m across the view (the lit part's centroid, up to half a ramp's reach off
// the deck centre) and the range within 15 %. Set ROVER_FAR_DRAW=<folder> to save every view
// drawn.

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "lander_scene.hpp"
#include "rover/apl/rendezvous/long_range_detector.hpp"
#include "rover/base/units.hpp"

namespace rover::apl::rendezvous {
namespace {

using testing::LanderScene;
using testing::LanderSceneOptions;
using testing::LanderShot;
using testing::RoverView;

constexpr double kLanderX = 125.0;

// Outcrops near the lines of sight from the views below: x, y, length, depth, height, yaw.
std::vector<sim::terrain::Outcrop> Distractors() {
  return {{112.0, 9.0, 5.0, 1.6, 1.2, 10.0},
          {118.0, -11.0, 4.0, 1.4, 0.9, -20.0},
          {96.0, -5.0, 4.5, 1.5, 1.0, 80.0},
          {104.0, 5.5, 3.5, 1.2, 0.8, 40.0},
          {82.0, 4.0, 4.0, 1.4, 1.1, -10.0}};
}

class LongRangeSceneTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    LanderSceneOptions o;
    o.size = 160.0;
    o.size_y = 50.0;
    o.center_x = 62.0;
    o.resolution = 0.05;
    o.lander_x = kLanderX;
    o.lander_y = 0.0;
    o.lander_yaw_deg = 150.0;
    o.outcrops = Distractors();
    o.rock_k = 0.03;  // sparse rocks, as the lander_return scenarios
    auto scene = LanderScene::Create(o);
    ASSERT_TRUE(scene.ok()) << scene.status().ToString();
    scene_ = std::move(scene).value().release();
  }
  static void TearDownTestSuite() {
    delete scene_;
    scene_ = nullptr;
  }

  // The lander's box in the left image (deck, legs and ramps).
  static cv::Rect TruthBox(const LanderShot& shot) {
    const Eigen::Vector2d c(kLanderX, 0.0);
    const double reach = scene_->description().Apothem() + scene_->description().ramp_length;
    double u0 = 1e9, u1 = -1e9, v0 = 1e9, v1 = -1e9;
    for (int k = 0; k < 16; ++k) {
      const double a = 2.0 * kPi * k / 16;
      for (double z : {0.0, scene_->description().deck_height}) {
        const double r = z > 0.0 ? scene_->description().deck_radius : reach;
        const Eigen::Vector3d site(c.x() + r * std::cos(a), c.y() + r * std::sin(a),
                                   scene_->terrain().bare.Height(c.x(), c.y()) + z);
        const auto px = shot.left_model.Project(shot.site_from_rover.inverse() * site);
        if (!px) continue;
        u0 = std::min(u0, px->x());
        u1 = std::max(u1, px->x());
        v0 = std::min(v0, px->y());
        v1 = std::max(v1, px->y());
      }
    }
    return cv::Rect(static_cast<int>(u0), static_cast<int>(v0), static_cast<int>(u1 - u0) + 1,
                    static_cast<int>(v1 - v0) + 1);
  }

  static LanderScene* scene_;
};
LanderScene* LongRangeSceneTest::scene_ = nullptr;

struct Tally {
  int views = 0, found = 0, wrong = 0;
  int line_true = 0, line_false = 0, tex_true = 0, tex_false = 0, fused_true = 0, fused_false = 0;
  double max_range_error = 0.0, max_bearing_error = 0.0, max_lateral_error = 0.0, ms = 0.0;
};

TEST_F(LongRangeSceneTest, FindsTheLanderFrom25To125MAndNeverADistractor) {
  struct View {
    double x, y, yaw_offset_deg, prior_error_m;
  };
  // Rover positions; the mast looks at an a-priori estimate `prior_error_m` to the side.
  const std::vector<View> views = {
      {0, 0, 0, 4},    {0, 6, 3, -5},  {0, -6, -4, 3},  {5, 2, 5, -3},  {15, -3, -2, 6},
      {25, 3, 2, -4},  {35, 0, -3, 4}, {45, -5, 4, 3},  {55, 4, -5, -5}, {65, 0, 2, 4},
      {65, -5, -2, -3}, {60, 6, 4, 2},  {95, 0, 2, 3},  {92, -4, -3, -2}, {100, 3, 1, -2}};
  const char* draw = std::getenv("ROVER_FAR_DRAW");
  Tally near_band, far_band;  // 25..90 m (the overlap with the mid-range detector and up), 90..125 m
  int index = 0;
  for (const View& v : views) {
    const double dx = kLanderX - v.x, dy = -v.y;
    const double yaw = std::atan2(dy, dx) / kDegree + v.yaw_offset_deg;
    RoverView rv;
    rv.x = v.x;
    rv.y = v.y;
    rv.yaw_deg = yaw;
    // The mast pans to the estimate (lateral error prior_error_m) and levels on it.
    const double est_bearing = std::atan2(dy + v.prior_error_m, dx) - yaw * kDegree;
    rv.pan_deg = est_bearing / kDegree;
    rv.tilt_deg = -std::atan2(1.0, std::hypot(dx, dy)) / kDegree;
    rv.frame = static_cast<std::uint64_t>(index);
    auto shot = scene_->Render(rv);
    ASSERT_TRUE(shot.ok()) << shot.status().ToString();
    const Eigen::Vector3d lander_rover =
        shot->site_from_rover.inverse() *
        Eigen::Vector3d(kLanderX, 0.0, scene_->terrain().bare.Height(kLanderX, 0.0));
    const double truth_range = std::hypot(lander_rover.x(), lander_rover.y());
    const double truth_bearing = std::atan2(lander_rover.y(), lander_rover.x());
    LanderPrior prior;
    prior.bearing = est_bearing;
    prior.range = std::hypot(dx, dy);
    prior.bearing_window = std::atan2(std::max(8.0, 0.1 * prior.range), prior.range);
    prior.range_window = 8.0 + 0.25 * prior.range;
    prior.ground_z = lander_rover.z();  // the pose estimate's view of the ground there
    auto s = DetectLanderFar(shot->left, shot->left_model, shot->right, &shot->right_model,
                             scene_->description(), {}, prior);
    ASSERT_TRUE(s.ok()) << s.status().ToString();
    const cv::Rect truth = TruthBox(*shot);
    Tally& t = truth_range > 90.0 ? far_band : near_band;
    ++t.views;
    t.ms += s->elapsed_ms;
    auto count = [&](const std::vector<CueBox>& boxes, int* yes, int* no) {
      for (const CueBox& c : boxes) ((c.box & truth).area() > 0 ? *yes : *no) += 1;
    };
    count(s->line_candidates, &t.line_true, &t.line_false);
    count(s->texture_candidates, &t.tex_true, &t.tex_false);
    count(s->fused, &t.fused_true, &t.fused_false);
    if (s->found) {
      if ((s->box & truth).area() > 0) {
        ++t.found;
        t.max_range_error = std::max(t.max_range_error, std::abs(s->range - truth_range) / truth_range);
        t.max_bearing_error = std::max(t.max_bearing_error, std::abs(s->bearing - truth_bearing));
        t.max_lateral_error =
            std::max(t.max_lateral_error, truth_range * std::abs(s->bearing - truth_bearing));
      } else {
        ++t.wrong;
      }
    }
    std::printf("view (%5.1f, %5.1f) range %6.1f: %s range %.1f (truth %.1f) bearing %.2f (truth %.2f) deg; %s\n",
                v.x, v.y, truth_range, s->found ? "found" : "none ", s->range, truth_range,
                s->bearing / kDegree, truth_bearing / kDegree,
                s->found ? s->features.c_str() : s->reason.c_str());
    if (draw != nullptr) {
      cv::Mat bgr;
      cv::cvtColor(shot->left, bgr, cv::COLOR_GRAY2BGR);
      cv::rectangle(bgr, truth, cv::Scalar(255, 128, 0), 1);
      DrawFarSighting(&bgr, *s);
      char name[64];
      std::snprintf(name, sizeof name, "/far_%02d.png", index);
      cv::imwrite(std::string(draw) + name, bgr(s->band.empty() ? cv::Rect(0, 0, bgr.cols, bgr.rows)
                                                                  : (s->band + cv::Size(0, 0))));
      cv::imwrite(std::string(draw) + "/full" + (name + 1), bgr);
    }
    ++index;
  }
  for (const auto& [label, t] : {std::pair{"25-90 m", near_band}, std::pair{"90-125 m", far_band}}) {
    std::printf(
        "%s: %d views, found %d, wrong %d | per image: lines %.2f true %.2f false, texture %.2f true "
        "%.2f false, fused %.2f true %.2f false | worst range %.1f %%, bearing %.2f deg (%.2f m across) | %.1f ms\n",
        label, t.views, t.found, t.wrong, double(t.line_true) / t.views, double(t.line_false) / t.views,
        double(t.tex_true) / t.views, double(t.tex_false) / t.views, double(t.fused_true) / t.views,
        double(t.fused_false) / t.views, 100 * t.max_range_error, t.max_bearing_error / kDegree,
        t.max_lateral_error, t.ms / t.views);
  }
  const int views_total = near_band.views + far_band.views;
  EXPECT_GE(near_band.found + far_band.found, views_total - 2);
  EXPECT_EQ(near_band.wrong + far_band.wrong, 0);
  // Stereo range (the lit part's depth against the deck centre's), sharp bearing.
  EXPECT_LE(std::max(near_band.max_range_error, far_band.max_range_error), 0.15);
  // The bearing is the lit part's centroid: up to a ramp's offset from the deck centre.
  EXPECT_LE(std::max(near_band.max_lateral_error, far_band.max_lateral_error), 2.5);
}

TEST(LongRangeDetector, BadInputIsNamed) {
  const hwconfig::LanderDescription lander;
  geometry::Cahv cahv;
  cahv.c = Eigen::Vector3d(0, 0, 1.5);
  cahv.a = Eigen::Vector3d(1, 0, 0);
  cahv.h = Eigen::Vector3d(64, -100, 0);
  cahv.v = Eigen::Vector3d(64, 0, -100);
  auto model = geometry::CameraModel::Create(cahv, 128, 128);
  ASSERT_TRUE(model.ok()) << model.status().ToString();
  EXPECT_NE(DetectLanderFar(cv::Mat(), *model, cv::Mat(), nullptr, lander).status().message().find("left image: empty"),
            std::string::npos);
  EXPECT_NE(DetectLanderFar(cv::Mat(64, 64, CV_8UC1), *model, cv::Mat(), nullptr, lander).status().message().find("64x64"),
            std::string::npos);
  EXPECT_NE(DetectLanderFar(cv::Mat(128, 128, CV_8UC1), *model, cv::Mat(128, 128, CV_8UC1), nullptr, lander)
                .status()
                .message()
                .find("right image: given without a right model"),
            std::string::npos);
  LongRangeOptions o;
  o.max_range = 10.0;
  EXPECT_NE(DetectLanderFar(cv::Mat(128, 128, CV_8UC1), *model, cv::Mat(), nullptr, lander, o).status().message().find(
                "long_range.max_range"),
            std::string::npos);
  LanderPrior p;
  p.range = std::nan("");
  EXPECT_NE(DetectLanderFar(cv::Mat(128, 128, CV_8UC1), *model, cv::Mat(), nullptr, lander, {}, p).status().message().find(
                "prior.range"),
            std::string::npos);
  // A flat grey image: nothing found, no error.
  auto s = DetectLanderFar(cv::Mat(128, 128, CV_8UC1, cv::Scalar(90)), *model, cv::Mat(), nullptr, lander);
  ASSERT_TRUE(s.ok());
  EXPECT_FALSE(s->found);
}

}  // namespace
}  // namespace rover::apl::rendezvous
