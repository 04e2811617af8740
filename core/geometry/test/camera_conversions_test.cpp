#include <cmath>
#include <numbers>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "rover/geometry/camera_model.hpp"
#include "test/test_models.hpp"

namespace rover::geometry {
namespace {

using testing::AllTestModels;
using testing::CameraPose;
using testing::MakeCahv;
using testing::Must;
using testing::PointsInView;
using testing::TestCahv;
using testing::TestCahvor;
using testing::TestPinholeRadial;

TEST(ToPinholeRadial, CahvIsExactlyAPinhole) {
  const Eigen::Isometry3d pose = CameraPose({0.8, 0.3, 1.9}, 0.2, 0.44, 0.01);
  const CameraModel cahv = Must(CameraModel::Create(TestCahv(), 1024, 768));
  const auto fit = ToPinholeRadial(cahv);
  ASSERT_TRUE(fit.ok()) << fit.status().ToString();
  const PinholeRadial& p = fit->model;
  EXPECT_NEAR(p.fx, 1236.0, 1e-8);
  EXPECT_NEAR(p.fy, 1234.5, 1e-8);
  EXPECT_NEAR(p.cx, 515.3, 1e-8);
  EXPECT_NEAR(p.cy, 380.7, 1e-8);
  EXPECT_NEAR(p.k1, 0.0, 1e-12);
  EXPECT_NEAR(p.k2, 0.0, 1e-12);
  EXPECT_NEAR(p.k3, 0.0, 1e-12);
  EXPECT_TRUE(p.pose.matrix().isApprox(pose.matrix(), 1e-12));
  EXPECT_EQ(p.width, 1024);
  EXPECT_EQ(p.height, 768);
  EXPECT_LT(fit->max_error_px, 1e-9);
  // Same pixels for the same points.
  const CameraModel pin = Must(CameraModel::Create(p));
  for (const Eigen::Vector3d& x : PointsInView(cahv, 200, 1)) {
    EXPECT_LT((*cahv.Project(x) - *pin.Project(x)).norm(), 1e-9);
  }
  // And back: ToCahv reproduces C, A, H, V.
  const auto back = ToCahv(p);
  ASSERT_TRUE(back.ok());
  const Cahv c = TestCahv();
  EXPECT_LT((back->c - c.c).norm(), 1e-12);
  EXPECT_LT((back->a - c.a).norm(), 1e-12);
  EXPECT_LT((back->h - c.h).norm(), 1e-8);
  EXPECT_LT((back->v - c.v).norm(), 1e-8);
}

TEST(ToPinholeRadial, SkewedCahvReportsItsResidual) {
  Cahv c = TestCahv();
  const Intrinsics in = ComputeIntrinsics(c);
  const Eigen::Vector3d hp = (c.h - in.hc * c.a) / in.hs;
  const Eigen::Vector3d vp = (c.v - in.vc * c.a) / in.vs;
  const double skew = 1e-4;  // rad
  c.v = in.vs * (std::cos(skew) * vp + std::sin(skew) * hp) + in.vc * c.a;
  const auto fit = ToPinholeRadial(Must(CameraModel::Create(c, 1024, 768)));
  ASSERT_TRUE(fit.ok());
  // The unrepresentable skew costs about skew/2 * f * (corner offset / f) ~ 0.03 px.
  EXPECT_GT(fit->max_error_px, 1e-3);
  EXPECT_LT(fit->max_error_px, 0.05);
}

TEST(ToPinholeRadial, CahvorWithOEqualAIsExact) {
  Cahvor r = TestCahvor();
  r.o = r.a;
  r.r = Eigen::Vector3d(0.01, -0.03, 0.02);
  const auto fit = ToPinholeRadial(Must(CameraModel::Create(r, 1024, 768)));
  ASSERT_TRUE(fit.ok()) << fit.status().ToString();
  EXPECT_LT(fit->max_error_px, 1e-8);
  EXPECT_NEAR(fit->model.fx, 1236.0 * 1.01, 1e-6);
  EXPECT_NEAR(fit->model.k1, -0.03 / 1.01, 1e-9);
  EXPECT_NEAR(fit->model.k2, 0.02 / 1.01, 1e-9);
  EXPECT_NEAR(fit->model.k3, 0.0, 1e-9);
}

TEST(ToPinholeRadial, CahvorWithTiltedOpticalAxisFitsWithinATenthOfAPixel) {
  // O is 0.5 deg off A: the distortion centre is ~11 px from the principal point, which the
  // Brown model (centred on cx, cy) cannot follow exactly. Bound: 0.1 px max over 1024 x 768.
  const CameraModel m = Must(CameraModel::Create(TestCahvor(), 1024, 768));
  const auto fit = ToPinholeRadial(m);
  ASSERT_TRUE(fit.ok()) << fit.status().ToString();
  EXPECT_LT(fit->max_error_px, 0.1);
  EXPECT_LT(fit->rms_error_px, 0.05);
  RecordProperty("cahvor_tilted_fit_max_px", ::testing::PrintToString(fit->max_error_px));
  RecordProperty("cahvor_tilted_fit_rms_px", ::testing::PrintToString(fit->rms_error_px));
  // The fitted pinhole reproduces projections to the same accuracy.
  const CameraModel pin = Must(CameraModel::Create(fit->model));
  for (const Eigen::Vector3d& x : PointsInView(m, 200, 2)) {
    EXPECT_LT((*m.Project(x) - *pin.Project(x)).norm(), 0.1);
  }
}

TEST(ToPinholeRadial, PinholeIsReturnedUnchanged) {
  const auto fit = ToPinholeRadial(Must(CameraModel::Create(TestPinholeRadial())));
  ASSERT_TRUE(fit.ok());
  EXPECT_EQ(fit->model.k1, TestPinholeRadial().k1);
  EXPECT_EQ(fit->max_error_px, 0.0);
}

TEST(ToPinholeRadial, RejectsMirroredModelsWideFisheyesAndBadOptions) {
  Cahv c = TestCahv();
  const Intrinsics in = ComputeIntrinsics(c);
  c.v = -(c.v - in.vc * c.a) + in.vc * c.a;
  EXPECT_FALSE(ToPinholeRadial(Must(CameraModel::Create(c, 1024, 768))).ok());
  const auto fisheye =
      ToPinholeRadial(Must(CameraModel::Create(testing::TestCahvore(), 1024, 1024)));
  ASSERT_FALSE(fisheye.ok());
  EXPECT_NE(fisheye.status().message().find("90 deg"), std::string::npos)
      << fisheye.status().ToString();
  FitOptions bad;
  bad.grid_cols = 2;
  EXPECT_FALSE(bad.Validate().ok());
  EXPECT_FALSE(ToPinholeRadial(Must(CameraModel::Create(TestCahv(), 1024, 768)), bad).ok());
}

TEST(ToCahvor, PinholeWithoutK3IsExact) {
  PinholeRadial p = TestPinholeRadial();
  p.k3 = 0.0;
  const auto fit = ToCahvor(p);
  ASSERT_TRUE(fit.ok()) << fit.status().ToString();
  EXPECT_LT(fit->max_error_px, 1e-8);
  EXPECT_EQ(fit->model.r, Eigen::Vector3d(0.0, p.k1, p.k2));
  EXPECT_TRUE(fit->model.o.isApprox(fit->model.a));
}

TEST(ToCahvor, PinholeWithK3IsFittedByLeastSquares) {
  // k3 r^6 with k3 = -0.01 at the corner (r = 0.57) is 0.34 px; R absorbs most of it.
  const PinholeRadial p = TestPinholeRadial();
  const auto fit = ToCahvor(p);
  ASSERT_TRUE(fit.ok()) << fit.status().ToString();
  EXPECT_LT(fit->max_error_px, 0.1);
  RecordProperty("pinhole_k3_to_cahvor_max_px", ::testing::PrintToString(fit->max_error_px));
  // Without the fit (R = (0, k1, k2)) the error would be the full k3 term.
  Cahvor naive = fit->model;
  naive.r = Eigen::Vector3d(0.0, p.k1, p.k2);
  const CameraModel src = Must(CameraModel::Create(p));
  const CameraModel dst = Must(CameraModel::Create(naive, p.width, p.height));
  const Eigen::Vector2d corner(0.0, 0.0);
  const double naive_err =
      (*dst.ProjectDirection(src.Unproject(corner)->direction) - corner).norm();
  EXPECT_GT(naive_err, fit->max_error_px);
}

TEST(ToCahv, RejectsDistortion) {
  const auto r = ToCahv(TestPinholeRadial());
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("k1"), std::string::npos);
}

TEST(Scale, MapsPixelsByTheStatedConvention) {
  for (const CameraModel& m : AllTestModels()) {
    const std::vector<std::pair<double, double>> factors = {
        {0.25, 0.25}, {0.5, 0.5}, {2.0, 2.0}, {0.5, 0.25}};
    for (const auto& [sx, sy] : factors) {
      const CameraModel s = Scale(m, sx, sy);
      EXPECT_EQ(s.kind(), m.kind());
      EXPECT_EQ(s.width(), static_cast<int>(std::lround(m.width() * sx)));
      EXPECT_EQ(s.height(), static_cast<int>(std::lround(m.height() * sy)));
      for (const Eigen::Vector3d& p : PointsInView(m, 100, 17)) {
        const Eigen::Vector2d old_px = *m.Project(p);
        const Eigen::Vector2d expected(sx * (old_px.x() + 0.5) - 0.5,
                                       sy * (old_px.y() + 0.5) - 0.5);
        const auto new_px = s.Project(p);
        ASSERT_TRUE(new_px);
        EXPECT_LT((*new_px - expected).norm(), 1e-9) << KindName(m.kind());
        // Rays are unchanged.
        const auto r0 = m.Unproject(old_px);
        const auto r1 = s.Unproject(expected);
        ASSERT_TRUE(r0 && r1);
        EXPECT_LT((r0->direction - r1->direction).norm(), 1e-11);
        EXPECT_LT((r0->origin - r1->origin).norm(), 1e-11);
      }
    }
    // The image corners (outer pixel edges) map onto each other.
    const CameraModel q = Scale(m, 0.25);
    const Eigen::Vector3d far_corner = m.Unproject({m.width() - 0.5, m.height() - 0.5})->direction;
    EXPECT_LT((*q.ProjectDirection(far_corner) - Eigen::Vector2d(q.width() - 0.5, q.height() - 0.5))
                  .norm(),
              1e-9);
    // Composition: 0.5 twice is 0.25.
    const CameraModel twice = Scale(Scale(m, 0.5), 0.5);
    for (const Eigen::Vector3d& p : PointsInView(m, 20, 4)) {
      EXPECT_LT((*twice.Project(p) - *q.Project(p)).norm(), 1e-9);
    }
  }
}

TEST(Scale, Navcam1024To256) {
  // A 1024 x 1024 CAHV with the centre at 511.5 becomes 256 x 256 with the centre at 127.5.
  const Cahv c = MakeCahv(CameraPose({0, 0, 1.9}, 0, 0.5, 0), 1224.0, 1224.0, 511.5, 511.5);
  const CameraModel s = Scale(Must(CameraModel::Create(c, 1024, 1024)), 0.25);
  const Intrinsics in = ComputeIntrinsics(*s.As<Cahv>());
  EXPECT_NEAR(in.hc, 127.5, 1e-9);
  EXPECT_NEAR(in.vc, 127.5, 1e-9);
  EXPECT_NEAR(in.hs, 306.0, 1e-9);
  EXPECT_NEAR(in.vs, 306.0, 1e-9);
  EXPECT_EQ(s.width(), 256);
}

TEST(Transform, MovesTheModelWithItsFrame) {
  Eigen::Isometry3d new_from_old = Eigen::Isometry3d::Identity();
  new_from_old.linear() = RotationFromRpy(0.1, -0.3, 1.2);
  new_from_old.translation() = Eigen::Vector3d(0.5, -2.0, 1.0);
  for (const CameraModel& m : AllTestModels()) {
    const CameraModel t = Transform(m, new_from_old);
    EXPECT_EQ(t.kind(), m.kind());
    EXPECT_EQ(t.width(), m.width());
    EXPECT_TRUE(t.Center().isApprox(new_from_old * m.Center(), 1e-12));
    for (const Eigen::Vector3d& p : PointsInView(m, 100, 8)) {
      const auto a = m.Project(p);
      const auto b = t.Project(new_from_old * p);
      ASSERT_TRUE(a && b);
      EXPECT_LT((*a - *b).norm(), 1e-9) << KindName(m.kind());
      const auto ra = m.Unproject(*a);
      const auto rb = t.Unproject(*a);
      EXPECT_LT((new_from_old.linear() * ra->direction - rb->direction).norm(), 1e-12);
      EXPECT_LT((new_from_old * ra->origin - rb->origin).norm(), 1e-12);
    }
    // And back.
    const CameraModel back = Transform(t, new_from_old.inverse());
    for (const Eigen::Vector3d& p : PointsInView(m, 10, 9)) {
      EXPECT_LT((*back.Project(p) - *m.Project(p)).norm(), 1e-9);
    }
  }
}

}  // namespace
}  // namespace rover::geometry
