#include "rover/ddl/camera/camera_model_fields.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "test_models.hpp"

namespace rover::ddl {
namespace {

TEST(CameraModelFields, CahvIsExactBothWays) {
  geometry::Cahv m;
  m.c = Eigen::Vector3d(0.1, 0.2, 1.5);
  m.a = Eigen::Vector3d::UnitZ();
  m.h = 300.0 * Eigen::Vector3d::UnitX() + 127.5 * m.a;
  m.v = 300.0 * Eigen::Vector3d::UnitY() + 95.5 * m.a;
  const auto model = *geometry::CameraModel::Create(m, 256, 192);
  auto f = ToCameraModelFields(model);
  ASSERT_TRUE(f.ok()) << f.status().ToString();
  EXPECT_EQ(f->width, 256);
  EXPECT_EQ(f->height, 192);
  EXPECT_EQ(f->o, f->a);
  EXPECT_EQ(f->r, (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_NEAR(f->fx, 300.0, 1e-9);
  EXPECT_NEAR(f->cx, 127.5, 1e-9);
  EXPECT_NEAR(f->cy, 95.5, 1e-9);
  EXPECT_NEAR(f->k1, 0.0, 1e-12);
  EXPECT_LT(f->pinhole_max_error_px, 1e-6);
  EXPECT_LT((f->pose.translation() - m.c).norm(), 1e-12);
}

TEST(CameraModelFields, CahvorKeepsItsVectorsAndFitsAPinhole) {
  const geometry::CameraModel model = test::NavcamCahvor();
  auto f = ToCameraModelFields(model);
  ASSERT_TRUE(f.ok());
  const auto* m = model.As<geometry::Cahvor>();
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(f->h, (std::array<double, 3>{m->h.x(), m->h.y(), m->h.z()}));
  EXPECT_EQ(f->r, (std::array<double, 3>{m->r.x(), m->r.y(), m->r.z()}));
  EXPECT_LT(f->pinhole_max_error_px, 0.2);
  EXPECT_GT(f->fx, 1200.0);
}

TEST(CameraModelFields, ScaledModelFieldsFollowTheResampling) {
  const geometry::CameraModel model = test::NavcamCahvor();
  auto full = ToCameraModelFields(model);
  auto small = ToCameraModelFields(geometry::Scale(model, 0.25));
  ASSERT_TRUE(full.ok() && small.ok());
  EXPECT_EQ(small->width, 256);
  EXPECT_NEAR(small->fx, 0.25 * full->fx, 1e-3);
  EXPECT_NEAR(small->cx, 0.25 * (full->cx + 0.5) - 0.5, 1e-3);
  EXPECT_NEAR(small->k1, full->k1, 1e-6);
}

TEST(CameraModelFields, PinholeGetsAnEquivalentCahvor) {
  geometry::PinholeRadial p;
  p.fx = 500.0;
  p.fy = 502.0;
  p.cx = 319.5;
  p.cy = 239.5;
  p.k1 = -0.05;
  p.k2 = 0.01;
  p.width = 640;
  p.height = 480;
  const auto model = *geometry::CameraModel::Create(p);
  auto f = ToCameraModelFields(model);
  ASSERT_TRUE(f.ok()) << f.status().ToString();
  EXPECT_NEAR(f->fx, 500.0, 1e-9);
  EXPECT_NEAR(f->k1, -0.05, 1e-12);
  geometry::Cahvor cv;
  cv.c = Eigen::Vector3d(f->c[0], f->c[1], f->c[2]);
  cv.a = Eigen::Vector3d(f->a[0], f->a[1], f->a[2]);
  cv.h = Eigen::Vector3d(f->h[0], f->h[1], f->h[2]);
  cv.v = Eigen::Vector3d(f->v[0], f->v[1], f->v[2]);
  cv.o = Eigen::Vector3d(f->o[0], f->o[1], f->o[2]);
  cv.r = Eigen::Vector3d(f->r[0], f->r[1], f->r[2]);
  const auto back = *geometry::CameraModel::Create(cv, 640, 480);
  const Eigen::Vector3d pt(0.5, -0.3, 2.0);
  EXPECT_LT((*back.Project(pt) - *model.Project(pt)).norm(), 1e-6);
}

}  // namespace
}  // namespace rover::ddl
