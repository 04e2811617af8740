#include "rover/dl/vo/matching.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "synthetic_scene.hpp"

namespace rover::dl::vo {
namespace {

// 8-bit image of f(x, y) = texture at the warped coordinates given by `map`.
cv::Mat Render(int w, int h, const std::function<Eigen::Vector2d(double, double)>& map) {
  cv::Mat img(h, w, CV_8UC1);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      // 3x3 supersampling keeps the image band-limited.
      double acc = 0.0;
      for (int j = -1; j <= 1; ++j) {
        for (int i = -1; i <= 1; ++i) {
          const Eigen::Vector2d p = map(x + i / 3.0, y + j / 3.0);
          acc += testing::Texture(p.x() / 50.0, p.y() / 50.0, 9);
        }
      }
      img.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(std::lround(25 + 205 * acc / 9));
    }
  }
  return img;
}

TEST(MatchOptions, Validate) {
  MatchOptions o;
  EXPECT_TRUE(o.Validate().ok());
  o.max_disparity = o.min_disparity;
  EXPECT_NE(o.Validate().message().find("disparity"), std::string::npos);
  o = MatchOptions{};
  o.min_correlation = 1.2;
  EXPECT_FALSE(o.Validate().ok());
  o = MatchOptions{};
  o.pyramid_levels = 0;
  EXPECT_FALSE(o.Validate().ok());
}

TEST(MatchStereo, RecoversSubpixelDisparity) {
  for (const double d : {23.0, 23.25, 23.5}) {
    const cv::Mat l = Render(320, 120, [](double x, double y) { return Eigen::Vector2d(x, y); });
    const cv::Mat r =
        Render(320, 120, [d](double x, double y) { return Eigen::Vector2d(x + d, y); });
    const CorrelationImage li(l), ri(r);
    MatchOptions o;
    o.max_disparity = 64;
    int ok = 0, tried = 0;
    double sum_x = 0.0, sq_x = 0.0, sq_y = 0.0, worst = 0.0;
    for (int y = 30; y < 95; y += 5) {
      for (int x = 80; x < 300; x += 5) {
        // Half the templates centred on sub-pixel positions (the remainder is carried over).
        const Eigen::Vector2d px =
            (x + y) % 2 ? Eigen::Vector2d(x + 0.3, y - 0.2) : Eigen::Vector2d(x, y);
        ++tried;
        const StereoMatch m = MatchStereo(li, ri, px, o);
        if (!m.ok) continue;
        ++ok;
        const double ex = px.x() - m.right.x() - d, ey = m.right.y() - px.y();
        sum_x += ex;
        sq_x += ex * ex;
        sq_y += ey * ey;
        worst = std::max({worst, std::abs(ex), std::abs(ey)});
      }
    }
    SCOPED_TRACE(d);
    EXPECT_GE(ok, 0.9 * tried);
    // Correlation + biquadratic: ~0.07 px rms per coordinate, unbiased.
    EXPECT_LT(std::sqrt(sq_x / ok), 0.1);
    EXPECT_LT(std::sqrt(sq_y / ok), 0.1);
    EXPECT_LT(std::abs(sum_x / ok), 0.05);
    EXPECT_LT(worst, 0.35);
  }
}

TEST(MatchStereo, FailsOnFlatAndOnUnmatchedImages) {
  const cv::Mat l = Render(320, 120, [](double x, double y) { return Eigen::Vector2d(x, y); });
  const CorrelationImage li(l);
  const CorrelationImage flat(cv::Mat(120, 320, CV_8UC1, cv::Scalar(90)));
  MatchOptions o;
  o.max_disparity = 64;
  EXPECT_FALSE(MatchStereo(li, flat, {200, 60}, o).ok);
  EXPECT_FALSE(MatchStereo(flat, li, {200, 60}, o).ok);
  // A right image of an unrelated texture: nothing passes the correlation and LR checks.
  const cv::Mat other = Render(
      320, 120, [](double x, double y) { return Eigen::Vector2d(y * 1.7 + 500, x * 0.6 - 300); });
  const CorrelationImage oi(other);
  int accepted = 0;
  for (int x = 80; x < 300; x += 10) accepted += MatchStereo(li, oi, {double(x), 60.0}, o).ok;
  EXPECT_LE(accepted, 1);
}

TEST(TrackFeature, CoarseToFineFindsLargeShift) {
  const Eigen::Vector2d shift(37.3, -14.6);
  const cv::Mat a = Render(320, 240, [](double x, double y) { return Eigen::Vector2d(x, y); });
  const cv::Mat b = Render(
      320, 240, [&](double x, double y) { return Eigen::Vector2d(x - shift.x(), y - shift.y()); });
  const ImagePyramid pa(a, 4), pb(b, 4);
  ASSERT_EQ(pa.levels(), 4);
  MatchOptions o;
  TrackRequest req;
  req.from = Eigen::Vector2d(140, 130);
  req.predicted = req.from;  // a poor prediction
  req.half_window = Eigen::Vector2d(48, 48);
  const TrackMatch m = TrackFeature(pa, pb, req, o);
  ASSERT_TRUE(m.ok) << m.failure;
  EXPECT_GE(m.level, 2);
  EXPECT_NEAR((m.to - (req.from + shift)).norm(), 0.0, 0.15);
  // Without the pyramid the same window is searched on full resolution and also succeeds.
  MatchOptions flat = o;
  flat.pyramid_levels = 1;
  const ImagePyramid qa(a, 1), qb(b, 1);
  const TrackMatch m1 = TrackFeature(qa, qb, req, flat);
  ASSERT_TRUE(m1.ok) << m1.failure;
  EXPECT_EQ(m1.level, 0);
  EXPECT_NEAR((m1.to - (req.from + shift)).norm(), 0.0, 0.15);
}

TEST(TrackFeature, WarpedTemplateFollowsScaleChange) {
  // The second image is the first magnified 1.35x about (160, 120), as when driving forward.
  const double s = 1.35;
  const Eigen::Vector2d c(160, 120);
  const cv::Mat a = Render(320, 240, [](double x, double y) { return Eigen::Vector2d(x, y); });
  const cv::Mat b = Render(320, 240, [&](double x, double y) {
    return Eigen::Vector2d((x - c.x()) / s + c.x(), (y - c.y()) / s + c.y());
  });
  const ImagePyramid pa(a, 3), pb(b, 3);
  MatchOptions o;
  int ok_warped = 0;
  double err_warped = 0.0;
  for (int k = 0; k < 16; ++k) {
    TrackRequest req;
    req.from = Eigen::Vector2d(100 + 8 * k, 90 + 4 * k);
    const Eigen::Vector2d truth = c + s * (req.from - c);
    req.predicted = truth + Eigen::Vector2d(1.2, -0.8);
    req.half_window = Eigen::Vector2d(4, 4);
    req.warp = s * Eigen::Matrix2d::Identity();
    const TrackMatch m = TrackFeature(pa, pb, req, o);
    if (m.ok) {
      ++ok_warped;
      err_warped = std::max(err_warped, (m.to - truth).norm());
    }
  }
  EXPECT_GE(ok_warped, 14);
  EXPECT_LT(err_warped, 0.2);
}

}  // namespace
}  // namespace rover::dl::vo
