#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "rover/base/units.hpp"
#include "rover/geometry/camera_model.hpp"
#include "test/test_models.hpp"

namespace rover::geometry {
namespace {

using testing::CameraPose;
using testing::MakeCahv;
using testing::Must;
// A deliberately non-parallel NAVCAM-like pair, 1024 x 768: 30 cm baseline with a 2 cm vertical
// and 1 cm fore-aft offset, toed in by 2 deg each, pitch differing by 0.7 deg, roll by 1 deg,
// focal lengths differing by 1 %, different principal points and distortion.
struct Pair {
  CameraModel left;
  CameraModel right;
};

Pair NonParallelPair() {
  const Eigen::Vector3d cl(0.8, 0.15, 1.9);
  const Eigen::Vector3d cr(0.81, -0.15, 1.92);
  const Cahv l = MakeCahv(CameraPose(cl, -2.0 * kDegree, 25.0 * kDegree, 0.3 * kDegree), 1236.0,
                          1234.0, 515.0, 380.0);
  const Cahv r = MakeCahv(CameraPose(cr, 2.0 * kDegree, 25.7 * kDegree, -0.7 * kDegree), 1248.0,
                          1247.0, 505.0, 390.0);
  Cahvor lo{l.c, l.a, l.h, l.v, l.a, Eigen::Vector3d(0.0, -0.02, 0.01)};
  Cahvor ro{r.c, r.a, r.h, r.v, r.a, Eigen::Vector3d(0.0, -0.025, 0.012)};
  ro.o = Eigen::AngleAxisd(0.2 * kDegree, Eigen::Vector3d::UnitX()) * r.a;
  return {Must(CameraModel::Create(lo, 1024, 768)), Must(CameraModel::Create(ro, 1024, 768))};
}

// Bilinear interpolation of a remap table at a non-integer pixel.
Eigen::Vector2d SampleMap(const std::vector<float>& mx, const std::vector<float>& my, int w,
                          const Eigen::Vector2d& q) {
  const int x0 = static_cast<int>(std::floor(q.x()));
  const int y0 = static_cast<int>(std::floor(q.y()));
  const double fx = q.x() - x0;
  const double fy = q.y() - y0;
  const auto at = [&](const std::vector<float>& m, int x, int y) {
    return static_cast<double>(m[static_cast<std::size_t>(y * w + x)]);
  };
  const auto lerp = [&](const std::vector<float>& m) {
    return (1 - fy) * ((1 - fx) * at(m, x0, y0) + fx * at(m, x0 + 1, y0)) +
           fy * ((1 - fx) * at(m, x0, y0 + 1) + fx * at(m, x0 + 1, y0 + 1));
  };
  return {lerp(mx), lerp(my)};
}

TEST(RectifyStereoPair, CorrespondingPointsLandOnTheSameRow) {
  const Pair pair = NonParallelPair();
  const auto rect = RectifyStereoPair(pair.left, pair.right);
  ASSERT_TRUE(rect.ok()) << rect.status().ToString();
  EXPECT_EQ(rect->left.kind(), CameraModel::Kind::kCahv);
  EXPECT_NEAR(rect->baseline_m, (pair.right.Center() - pair.left.Center()).norm(), 1e-12);
  EXPECT_NEAR(rect->focal_px, 0.25 * (1236.0 + 1234.0 + 1248.0 + 1247.0), 1e-9);
  const Cahv& l = *rect->left.As<Cahv>();
  const Cahv& r = *rect->right.As<Cahv>();
  EXPECT_EQ(l.a, r.a);
  EXPECT_EQ(l.h, r.h);
  EXPECT_EQ(l.v, r.v);

  // The unrectified pair has large row differences.
  std::mt19937_64 rng(1234);
  std::uniform_real_distribution<double> ux(0, 1023), uy(0, 767), range(2.0, 40.0);
  double worst_row = 0.0;
  double worst_raw_row = 0.0;
  int checked = 0;
  while (checked < 500) {
    const Eigen::Vector3d p =
        pair.left.Unproject({ux(rng), uy(rng)})->direction * range(rng) + pair.left.Center();
    const auto pl = pair.left.Project(p);
    const auto pr = pair.right.Project(p);
    if (!pl || !pr || !pair.left.InImage(*pl) || !pair.right.InImage(*pr)) continue;
    ++checked;
    worst_raw_row = std::max(worst_raw_row, std::abs(pl->y() - pr->y()));
    // Original pixel -> ray -> rectified pixel.
    const auto ql = rect->left.ProjectDirection(pair.left.Unproject(*pl)->direction);
    const auto qr = rect->right.ProjectDirection(pair.right.Unproject(*pr)->direction);
    ASSERT_TRUE(ql && qr);
    worst_row = std::max(worst_row, std::abs(ql->y() - qr->y()));
    // Disparity = f b / z with z the depth along the common axis.
    const double z = (p - l.c).dot(l.a);
    EXPECT_NEAR(ql->x() - qr->x(), rect->focal_px * rect->baseline_m / z, 1e-6);
  }
  EXPECT_GT(worst_raw_row, 10.0);
  EXPECT_LT(worst_row, 0.01);
  RecordProperty("rectified_row_error_max_px", ::testing::PrintToString(worst_row));
}

TEST(RectifyStereoPair, RemapTablesPointAtTheSourcePixels) {
  const Pair pair = NonParallelPair();
  const auto rect = RectifyStereoPair(pair.left, pair.right);
  ASSERT_TRUE(rect.ok());
  const int w = rect->left.width();
  ASSERT_EQ(rect->left_map_x.size(), static_cast<std::size_t>(w * rect->left.height()));
  ASSERT_EQ(rect->right_map_y.size(), rect->left_map_x.size());
  // Integer pixels: exactly the source projection of the rectified ray.
  for (const Eigen::Vector2i& q : {Eigen::Vector2i(0, 0), Eigen::Vector2i(511, 383),
                                   Eigen::Vector2i(1023, 767), Eigen::Vector2i(100, 700)}) {
    const std::size_t i = static_cast<std::size_t>(q.y() * w + q.x());
    const auto src =
        pair.right.ProjectDirection(rect->right.Unproject(q.cast<double>())->direction);
    EXPECT_NEAR(rect->right_map_x[i], src->x(), 1e-3);
    EXPECT_NEAR(rect->right_map_y[i], src->y(), 1e-3);
  }
  // Between pixels: bilinear interpolation of the table lands on the source pixel of a 3D point
  // (to within the table's interpolation error).
  std::mt19937_64 rng(77);
  std::uniform_real_distribution<double> ux(10, 1010), uy(10, 750), range(2.0, 40.0);
  double worst = 0.0;
  for (int k = 0; k < 300; ++k) {
    const Eigen::Vector3d p =
        rect->left.Unproject({ux(rng), uy(rng)})->direction * range(rng) + pair.left.Center();
    const Eigen::Vector2d q = *rect->left.Project(p);
    const Eigen::Vector2d src = *pair.left.Project(p);
    worst = std::max(worst, (SampleMap(rect->left_map_x, rect->left_map_y, w, q) - src).norm());
  }
  EXPECT_LT(worst, 0.01);
}

TEST(RectifyStereoPair, OptionsSetSizeAndFocalLength) {
  const Pair pair = NonParallelPair();
  RectifyOptions options;
  options.width = 512;
  options.height = 384;
  options.focal_px = 600.0;
  options.compute_maps = false;
  const auto rect = RectifyStereoPair(pair.left, pair.right, options);
  ASSERT_TRUE(rect.ok());
  EXPECT_EQ(rect->left.width(), 512);
  EXPECT_EQ(rect->right.height(), 384);
  EXPECT_TRUE(rect->left_map_x.empty());
  const Intrinsics in = ComputeIntrinsics(*rect->left.As<Cahv>());
  EXPECT_NEAR(in.hs, 600.0, 1e-9);
  EXPECT_NEAR(in.vs, 600.0, 1e-9);
  EXPECT_NEAR(in.hc, 255.5, 1e-9);
  EXPECT_NEAR(in.vc, 191.5, 1e-9);
  EXPECT_NEAR(in.theta, std::numbers::pi / 2, 1e-12);
}

TEST(RectifyStereoPair, PinholeAndFisheyeInputs) {
  PinholeRadial pl = testing::TestPinholeRadial();
  PinholeRadial pr = pl;
  pr.pose.translation() += pl.pose.linear().col(0) * 0.12;  // 12 cm to the right
  pr.pose.linear() = pr.pose.linear() * Eigen::AngleAxisd(0.01, Eigen::Vector3d::UnitY());
  const auto rect = RectifyStereoPair(Must(CameraModel::Create(pl)), Must(CameraModel::Create(pr)));
  ASSERT_TRUE(rect.ok()) << rect.status().ToString();
  EXPECT_NEAR(rect->baseline_m, 0.12, 1e-12);
  // A fisheye pair: the rectified (perspective) view of the central part.
  Cahvore fl = testing::TestCahvore();
  Cahvore fr = fl;
  const Eigen::Vector3d x = (fl.h - fl.a.dot(fl.h) * fl.a).normalized();
  fr.c += 0.1 * x;
  RectifyOptions options;
  options.focal_px = 400.0;
  const auto fish = RectifyStereoPair(Must(CameraModel::Create(fl, 1024, 1024)),
                                      Must(CameraModel::Create(fr, 1024, 1024)), options);
  ASSERT_TRUE(fish.ok()) << fish.status().ToString();
  EXPECT_NEAR(fish->baseline_m, 0.1, 1e-12);
  for (const float v : fish->left_map_x) EXPECT_NE(v, kUnmappedPixel);
}

TEST(RectifyStereoPair, MarksPixelsBeyondTheSourceModelAsUnmapped) {
  PinholeRadial pl = testing::TestPinholeRadial();
  pl.k1 = -0.5;  // folds at r = 0.82, about 39 deg off axis
  pl.k2 = 0.0;
  pl.k3 = 0.0;
  PinholeRadial pr = pl;
  pr.pose.translation() += pl.pose.linear().col(0) * 0.2;
  RectifyOptions options;
  options.focal_px = 200.0;  // 116 deg horizontal field: beyond the fold
  const auto rect =
      RectifyStereoPair(Must(CameraModel::Create(pl)), Must(CameraModel::Create(pr)), options);
  ASSERT_TRUE(rect.ok());
  EXPECT_EQ(rect->left_map_x.front(), kUnmappedPixel);
  const std::size_t centre = static_cast<std::size_t>(240 * 640 + 320);
  EXPECT_NE(rect->left_map_x[centre], kUnmappedPixel);
}

TEST(RectifyStereoPair, RejectsDegenerateGeometry) {
  const Pair pair = NonParallelPair();
  const auto same = RectifyStereoPair(pair.left, pair.left);
  ASSERT_FALSE(same.ok());
  EXPECT_NE(same.status().message().find("baseline"), std::string::npos);
  // The right camera straight ahead of the left one.
  const Cahv l = *Must(CameraModel::Create(
                           MakeCahv(CameraPose({0, 0, 1}, 0, 0, 0), 500, 500, 320, 240), 640, 480))
                      .As<Cahv>();
  Cahv ahead = l;
  ahead.c += 0.3 * l.a;
  EXPECT_FALSE(RectifyStereoPair(Must(CameraModel::Create(l, 640, 480)),
                                 Must(CameraModel::Create(ahead, 640, 480)))
                   .ok());
  RectifyOptions bad;
  bad.focal_px = -1.0;
  EXPECT_FALSE(bad.Validate().ok());
  EXPECT_FALSE(RectifyStereoPair(pair.left, pair.right, bad).ok());
}

}  // namespace
}  // namespace rover::geometry
