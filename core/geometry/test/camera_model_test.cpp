#include "rover/geometry/camera_model.hpp"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "test/test_models.hpp"

namespace rover::geometry {
namespace {

using testing::AllTestModels;
using testing::Must;
using testing::PointsInView;
using testing::TestCahv;
using testing::TestCahvor;
using testing::TestCahvore;
using testing::TestPinholeRadial;

std::string Name(const CameraModel& m) {
  std::string name(KindName(m.kind()));
  if (const auto* e = m.As<Cahvore>()) name += " L=" + std::to_string(e->Linearity());
  return name;
}

TEST(CameraModel, UnprojectThenProjectIsSubMicroPixel) {
  for (const CameraModel& m : AllTestModels()) {
    double worst = 0.0;
    for (int j = 0; j < 33; ++j) {
      for (int i = 0; i < 33; ++i) {
        const Eigen::Vector2d px((m.width() - 1.0) * i / 32.0, (m.height() - 1.0) * j / 32.0);
        const auto ray = m.Unproject(px);
        ASSERT_TRUE(ray) << Name(m) << " pixel " << px.transpose();
        EXPECT_NEAR(ray->direction.norm(), 1.0, 1e-14);
        for (const double t : {0.2, 3.0, 75.0}) {
          const auto back = m.Project(ray->origin + t * ray->direction);
          ASSERT_TRUE(back) << Name(m) << " pixel " << px.transpose() << " t " << t;
          worst = std::max(worst, (*back - px).norm());
        }
      }
    }
    EXPECT_LT(worst, 1e-6) << Name(m);
    RecordProperty(Name(m) + " round trip max error px", ::testing::PrintToString(worst));
  }
}

TEST(CameraModel, ProjectThenUnprojectRecoversTheRay) {
  for (const CameraModel& m : AllTestModels()) {
    for (const Eigen::Vector3d& p : PointsInView(m, 500, 42)) {
      const auto px = m.Project(p);
      ASSERT_TRUE(px) << Name(m);
      const auto ray = m.Unproject(*px);
      ASSERT_TRUE(ray) << Name(m);
      const Eigen::Vector3d q = p - ray->origin;
      // Distance of the point from the ray, relative to its range.
      EXPECT_LT(q.cross(ray->direction).norm() / q.norm(), 1e-10) << Name(m);
      EXPECT_GT(q.dot(ray->direction), 0.0) << Name(m);
    }
  }
}

TEST(CameraModel, PointsBehindTheCameraDoNotProject) {
  for (const CameraModel& m : AllTestModels()) {
    const auto ray = m.Unproject({0.5 * (m.width() - 1), 0.5 * (m.height() - 1)});
    ASSERT_TRUE(ray);
    const auto* e = m.As<Cahvore>();
    if (e != nullptr && e->Linearity() <= 0.5) {
      // Fisheye-like CAHVORE models are defined up to 180 deg off O: a point behind the camera
      // projects, far outside the image.
      const auto behind = m.ProjectDirection(-ray->direction);
      ASSERT_TRUE(behind) << Name(m);
      EXPECT_FALSE(m.InImage(*behind)) << Name(m);
      EXPECT_FALSE(m.ProjectDirection(-e->o)) << Name(m);
    } else {
      EXPECT_FALSE(m.Project(ray->origin - 5.0 * ray->direction)) << Name(m);
      EXPECT_FALSE(m.ProjectDirection(-ray->direction)) << Name(m);
    }
    EXPECT_FALSE(m.Project(Eigen::Vector3d(std::numeric_limits<double>::quiet_NaN(), 0, 0)));
    EXPECT_FALSE(m.Unproject({std::numeric_limits<double>::infinity(), 0.0}));
  }
}

TEST(CameraModel, ProjectDirectionIsThePointAtInfinity) {
  for (const CameraModel& m : AllTestModels()) {
    for (const Eigen::Vector3d& p : PointsInView(m, 100, 3)) {
      const Eigen::Vector3d d = p - m.Center();
      const auto far = m.Project(m.Center() + 1e7 * d);
      const auto dir = m.ProjectDirection(d);
      ASSERT_EQ(far.has_value(), dir.has_value()) << Name(m);
      ASSERT_TRUE(dir) << Name(m);
      EXPECT_LT((*far - *dir).norm(), 1e-6) << Name(m);
      if (m.kind() != CameraModel::Kind::kCahvore) {
        // Without a moving pupil any point along the direction projects the same.
        EXPECT_LT((*m.Project(p) - *dir).norm(), 1e-9) << Name(m);
      }
    }
  }
}

TEST(CameraModel, CahvoreWithUnitLinearityAndNoPupilShiftIsCahvor) {
  const Cahvor r = TestCahvor();
  Cahvore e;
  e.c = r.c;
  e.a = r.a;
  e.h = r.h;
  e.v = r.v;
  e.o = r.o;
  e.r = r.r;
  e.type = CahvoreType::kPerspective;
  const CameraModel mr = Must(CameraModel::Create(r, 1024, 768));
  const CameraModel me = Must(CameraModel::Create(e, 1024, 768));
  for (const Eigen::Vector3d& p : PointsInView(mr, 500, 9)) {
    EXPECT_LT((*mr.Project(p) - *me.Project(p)).norm(), 1e-9);
  }
  // A general model with L = 1 is the perspective one.
  e.type = CahvoreType::kGeneral;
  e.parameter = 1.0;
  const CameraModel mg = Must(CameraModel::Create(e, 1024, 768));
  for (const Eigen::Vector3d& p : PointsInView(mr, 100, 10)) {
    EXPECT_LT((*mr.Project(p) - *mg.Project(p)).norm(), 1e-9);
  }
}

TEST(CameraModel, CahvoreFisheyeSeesBeyondNinetyDegreesPerspectiveDoesNot) {
  const Cahvore fisheye = TestCahvore();
  const CameraModel m = Must(CameraModel::Create(fisheye, 1024, 1024));
  // A direction 100 deg off O.
  const Eigen::Vector3d side = fisheye.o.cross(Eigen::Vector3d::UnitZ()).normalized();
  const double angle = 100.0 * std::numbers::pi / 180.0;
  const Eigen::Vector3d d = std::cos(angle) * fisheye.o + std::sin(angle) * side;
  const auto px = m.ProjectDirection(d);
  ASSERT_TRUE(px);
  const auto ray = m.Unproject(*px);
  ASSERT_TRUE(ray);
  EXPECT_LT((ray->direction - d).norm(), 1e-9);
  Cahvore perspective = fisheye;
  perspective.type = CahvoreType::kPerspective;
  EXPECT_FALSE(Must(CameraModel::Create(perspective, 1024, 1024)).ProjectDirection(d));
  // The pupil moves forward off axis: the ray origin is C + s O with s > 0 here.
  EXPECT_GT((ray->origin - fisheye.c).dot(fisheye.o), 0.0);
  EXPECT_LT((ray->origin - fisheye.c).cross(fisheye.o).norm(), 1e-12);
}

TEST(CameraModel, JacobianMatchesFiniteDifferences) {
  for (const CameraModel& m : AllTestModels()) {
    for (const Eigen::Vector3d& p : PointsInView(m, 50, 21)) {
      Eigen::Matrix<double, 2, 3> jac;
      const auto px = m.Project(p, &jac);
      ASSERT_TRUE(px);
      EXPECT_EQ(*px, *m.Project(p));
      const double h = 1e-5 * std::max(1.0, (p - m.Center()).norm());
      for (int k = 0; k < 3; ++k) {
        const Eigen::Vector3d dp = h * Eigen::Vector3d::Unit(k);
        const Eigen::Vector2d num = (*m.Project(p + dp) - *m.Project(p - dp)) / (2 * h);
        EXPECT_LT((jac.col(k) - num).norm(), 1e-5 * (1.0 + num.norm()))
            << Name(m) << " column " << k << ": " << jac.col(k).transpose() << " vs "
            << num.transpose();
      }
    }
  }
}

TEST(CameraModel, IntrinsicsOfASyntheticCahv) {
  const Cahv c = TestCahv();
  const Intrinsics in = ComputeIntrinsics(c);
  EXPECT_NEAR(in.hc, 515.3, 1e-9);
  EXPECT_NEAR(in.vc, 380.7, 1e-9);
  EXPECT_NEAR(in.hs, 1236.0, 1e-9);
  EXPECT_NEAR(in.vs, 1234.5, 1e-9);
  EXPECT_NEAR(in.theta, std::numbers::pi / 2, 1e-12);
  // A point on the axis projects to the principal point.
  const CameraModel m = Must(CameraModel::Create(c, 1024, 768));
  EXPECT_LT((*m.Project(c.c + 7.0 * c.a) - Eigen::Vector2d(in.hc, in.vc)).norm(), 1e-9);
  // A mirrored model (V flipped about A) has theta = -pi/2.
  Cahv mirrored = c;
  mirrored.v = -(c.v - in.vc * c.a) + in.vc * c.a;
  EXPECT_NEAR(ComputeIntrinsics(mirrored).theta, -std::numbers::pi / 2, 1e-12);
  // Skew: V' rotated towards H' by 0.01 rad gives theta = pi/2 - 0.01.
  Cahv skewed = c;
  const Eigen::Vector3d hp = (c.h - in.hc * c.a) / in.hs;
  const Eigen::Vector3d vp = (c.v - in.vc * c.a) / in.vs;
  skewed.v = in.vs * (std::cos(0.01) * vp + std::sin(0.01) * hp) + in.vc * c.a;
  EXPECT_NEAR(ComputeIntrinsics(skewed).theta, std::numbers::pi / 2 - 0.01, 1e-12);
}

TEST(CameraModel, PinholeProjectionFormula) {
  PinholeRadial p;
  p.fx = 500;
  p.fy = 510;
  p.cx = 320;
  p.cy = 240;
  p.k1 = 0.1;
  p.k2 = -0.02;
  p.k3 = 0.003;
  p.width = 640;
  p.height = 480;
  const CameraModel m = Must(CameraModel::Create(p));
  const Eigen::Vector3d pc(0.3, -0.2, 2.0);
  const double xn = 0.15;
  const double yn = -0.1;
  const double r2 = xn * xn + yn * yn;
  const double s = 1 + 0.1 * r2 - 0.02 * r2 * r2 + 0.003 * r2 * r2 * r2;
  const auto px = m.Project(pc);
  ASSERT_TRUE(px);
  EXPECT_NEAR(px->x(), 500 * xn * s + 320, 1e-12);
  EXPECT_NEAR(px->y(), 510 * yn * s + 240, 1e-12);
}

TEST(CameraModel, DistortionBeyondItsFoldIsRejected) {
  PinholeRadial p = TestPinholeRadial();
  p.pose = Eigen::Isometry3d::Identity();
  p.k1 = -0.5;  // r (1 - 0.5 r^2) folds at r = sqrt(2/3)
  p.k2 = 0.0;
  p.k3 = 0.0;
  const CameraModel m = Must(CameraModel::Create(p));
  EXPECT_TRUE(m.Project({0.5, 0.0, 1.0}));
  EXPECT_TRUE(m.Project({0.8, 0.0, 1.0}));
  EXPECT_FALSE(m.Project({0.83, 0.0, 1.0}));
  EXPECT_FALSE(m.Project({1.0, 1.0, 1.0}));
  // The largest distorted radius is sqrt(2/3) (1 - 1/3) = 0.544.
  EXPECT_TRUE(m.Unproject({p.cx + 0.54 * p.fx, p.cy}));
  EXPECT_FALSE(m.Unproject({p.cx + 0.55 * p.fx, p.cy}));
  // Same for CAHVOR: tangent t (1 + r1 t^2) with r1 = -0.5.
  Cahvor r = TestCahvor();
  r.o = r.a;
  r.r = Eigen::Vector3d(0.0, -0.5, 0.0);
  const CameraModel mr = Must(CameraModel::Create(r, 1024, 768));
  const Eigen::Vector3d side = r.h.cross(r.a).cross(r.a).normalized();
  EXPECT_TRUE(mr.ProjectDirection(r.a + 0.8 * side));
  EXPECT_FALSE(mr.ProjectDirection(r.a + 0.83 * side));
}

TEST(CameraModel, InImageUsesPixelCentres) {
  const CameraModel m = Must(CameraModel::Create(TestCahv(), 1024, 768));
  EXPECT_TRUE(m.InImage({-0.5, -0.5}));
  EXPECT_TRUE(m.InImage({1023.49, 767.49}));
  EXPECT_FALSE(m.InImage({1023.5, 0.0}));
  EXPECT_FALSE(m.InImage({0.0, 767.5}));
  EXPECT_FALSE(m.InImage({-0.51, 0.0}));
}

TEST(CameraModel, CreateRejectsBadModels) {
  Cahv c = TestCahv();
  EXPECT_TRUE(CameraModel::Create(c, 1024, 768).ok());
  EXPECT_EQ(CameraModel::Create(c, 0, 768).status().code(), StatusCode::kInvalidArgument);
  Cahv bad = c;
  bad.a *= 1.1;
  auto r = CameraModel::Create(bad, 10, 10);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("|A|"), std::string::npos) << r.status().ToString();
  bad = c;
  bad.v = bad.h + 3.0 * bad.a;
  r = CameraModel::Create(bad, 10, 10);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("coplanar"), std::string::npos);
  bad = c;
  bad.c.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(CameraModel::Create(bad, 10, 10).ok());

  Cahvor o = TestCahvor();
  o.o *= 0.9;
  r = CameraModel::Create(o, 10, 10);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("|O|"), std::string::npos);
  o = TestCahvor();
  o.r.x() = -1.0;
  EXPECT_FALSE(CameraModel::Create(o, 10, 10).ok());
  // A slightly non-unit O (as printed in labels) is accepted and normalised.
  o = TestCahvor();
  o.o *= 1.0 + 1e-5;
  r = CameraModel::Create(o, 10, 10);
  ASSERT_TRUE(r.ok());
  EXPECT_NEAR(r->As<Cahvor>()->o.norm(), 1.0, 1e-15);

  Cahvore e = TestCahvore();
  e.type = static_cast<CahvoreType>(7);
  EXPECT_FALSE(CameraModel::Create(e, 10, 10).ok());
  e = TestCahvore();
  e.e.z() = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(CameraModel::Create(e, 10, 10).ok());

  PinholeRadial p = TestPinholeRadial();
  p.fx = 0.0;
  EXPECT_FALSE(CameraModel::Create(p).ok());
  p = TestPinholeRadial();
  p.pose.linear() *= 2.0;
  EXPECT_FALSE(CameraModel::Create(p).ok());
  p = TestPinholeRadial();
  p.pose.linear().col(0) *= -1.0;  // reflection
  EXPECT_FALSE(CameraModel::Create(p).ok());
  p = TestPinholeRadial();
  p.height = 0;
  EXPECT_FALSE(CameraModel::Create(p).ok());
}

TEST(CameraModel, KindAndAccessors) {
  const auto models = AllTestModels();
  EXPECT_EQ(models[0].kind(), CameraModel::Kind::kCahv);
  EXPECT_EQ(models[1].kind(), CameraModel::Kind::kCahvor);
  EXPECT_EQ(models[2].kind(), CameraModel::Kind::kCahvore);
  EXPECT_EQ(models[5].kind(), CameraModel::Kind::kPinholeRadial);
  EXPECT_NE(models[1].As<Cahvor>(), nullptr);
  EXPECT_EQ(models[1].As<Cahv>(), nullptr);
  EXPECT_EQ(KindName(models[2].kind()), "CAHVORE");
  EXPECT_EQ(models[5].width(), 640);
  EXPECT_EQ(models[5].height(), 480);
  EXPECT_TRUE(models[5].Center().isApprox(TestPinholeRadial().pose.translation()));
  EXPECT_EQ(TestCahvore(CahvoreType::kGeneral, 0.4).Linearity(), 0.4);
  EXPECT_EQ(TestCahvore(CahvoreType::kFisheye, 0.4).Linearity(), 0.0);
  EXPECT_EQ(TestCahvore(CahvoreType::kPerspective, 0.4).Linearity(), 1.0);
}

}  // namespace
}  // namespace rover::geometry
