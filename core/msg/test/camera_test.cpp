#include "rover/msg/camera.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <string>
#include <vector>

#include "rover/base/units.hpp"

namespace rover::msg {
namespace {

// Camera (x right, y down, z forward) at `position` in the rover frame, pitched down by `pitch`.
Eigen::Isometry3d MountPose(double pitch, const Eigen::Vector3d& position) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  const Eigen::Vector3d z(std::cos(pitch), 0.0, -std::sin(pitch));
  const Eigen::Vector3d x(0.0, -1.0, 0.0);
  t.linear().col(0) = x;
  t.linear().col(1) = z.cross(x);
  t.linear().col(2) = z;
  t.translation() = position;
  return t;
}

geometry::PinholeRadial HazcamPinhole(double k1 = 0.0) {
  geometry::PinholeRadial p;
  p.fx = 150.0;
  p.fy = 151.0;
  p.cx = 127.5 + 1.3;
  p.cy = 95.5 - 0.7;
  p.k1 = k1;
  p.pose = MountPose(45.0 * kDegree, {0.52, 0.05, 0.5});
  p.width = 256;
  p.height = 192;
  return p;
}

geometry::CameraModel CahvCamera() {
  auto cahv = geometry::ToCahv(HazcamPinhole());
  EXPECT_TRUE(cahv.ok());
  auto m = geometry::CameraModel::Create(*cahv, 256, 192);
  EXPECT_TRUE(m.ok()) << m.status().ToString();
  return *m;
}

geometry::CameraModel CahvorCamera() {
  geometry::Cahvor m;
  const Eigen::Isometry3d pose = MountPose(30.0 * kDegree, {0.2, -0.1, 1.5});
  const Eigen::Vector3d x = pose.linear().col(0), y = pose.linear().col(1);
  m.c = pose.translation();
  m.a = pose.linear().col(2);
  m.h = 300.0 * x + 130.2 * m.a;
  m.v = 300.0 * y + 94.1 * m.a;
  m.o = (m.a + 0.003 * x - 0.002 * y).normalized();
  m.r = Eigen::Vector3d(0.0, -0.03, 0.005);
  auto model = geometry::CameraModel::Create(m, 256, 192);
  EXPECT_TRUE(model.ok()) << model.status().ToString();
  return *model;
}

// Largest pixel distance between two models' projections of points in front of `a`.
double MaxProjectionDifference(const geometry::CameraModel& a, const geometry::CameraModel& b) {
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> px(0.0, 255.0), py(0.0, 191.0), depth(0.5, 20.0);
  double worst = 0.0;
  for (int i = 0; i < 200; ++i) {
    const auto ray = a.Unproject({px(rng), py(rng)});
    EXPECT_TRUE(ray.has_value());
    if (!ray) continue;
    const Eigen::Vector3d p = ray->origin + depth(rng) * ray->direction;
    const auto pa = a.Project(p);
    const auto pb = b.Project(p);
    EXPECT_TRUE(pa.has_value() && pb.has_value());
    if (pa && pb) worst = std::max(worst, (*pa - *pb).norm());
  }
  return worst;
}

TEST(CameraModelFields, CahvRoundTripsExactly) {
  const geometry::CameraModel cam = CahvCamera();
  auto fields = CameraModelFieldsFromModel(cam);
  ASSERT_TRUE(fields.ok()) << fields.status().ToString();
  EXPECT_TRUE(fields->HasCahvor());
  EXPECT_TRUE(fields->HasPinhole());
  EXPECT_EQ(fields->r, (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_EQ(fields->o, fields->a);  // CAHV: O = A
  EXPECT_EQ(fields->width, 256);
  EXPECT_EQ(fields->height, 192);

  const CameraModelFields back = *fields;

  auto model = CameraModelFromFields(back);
  ASSERT_TRUE(model.ok()) << model.status().ToString();
  EXPECT_EQ(model->kind(), geometry::CameraModel::Kind::kCahv);
  EXPECT_LT(MaxProjectionDifference(cam, *model), 1e-9);
  // The pinhole part is the same camera: its pose is the mount.
  const Eigen::Isometry3d mount = HazcamPinhole().pose;
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(back.position[static_cast<std::size_t>(i)], mount.translation()[i], 1e-12);
  EXPECT_NEAR(back.fx, 150.0, 1e-9);
  EXPECT_NEAR(back.fy, 151.0, 1e-9);
}

TEST(CameraModelFields, CahvorKeepsItsDistortion) {
  const geometry::CameraModel cam = CahvorCamera();
  auto fields = CameraModelFieldsFromModel(cam);
  ASSERT_TRUE(fields.ok()) << fields.status().ToString();
  EXPECT_NE(fields->r[1], 0.0);
  auto model = CameraModelFromFields(*fields);
  ASSERT_TRUE(model.ok()) << model.status().ToString();
  EXPECT_EQ(model->kind(), geometry::CameraModel::Kind::kCahvor);
  EXPECT_LT(MaxProjectionDifference(cam, *model), 1e-9);
}

TEST(CameraModelFields, PinholePartAloneIsUsedWhenTheCahvorVectorsAreZero) {
  const geometry::PinholeRadial pin = HazcamPinhole(-0.05);
  auto cam = geometry::CameraModel::Create(pin);
  ASSERT_TRUE(cam.ok());
  auto fields = CameraModelFieldsFromModel(*cam);
  ASSERT_TRUE(fields.ok()) << fields.status().ToString();
  // The CAHVOR part of a distorted pinhole is ToCahvor's (exact with k3 = 0).
  auto from_cahvor = CameraModelFromFields(*fields);
  ASSERT_TRUE(from_cahvor.ok()) << from_cahvor.status().ToString();
  EXPECT_EQ(from_cahvor->kind(), geometry::CameraModel::Kind::kCahvor);
  EXPECT_LT(MaxProjectionDifference(*cam, *from_cahvor), 1e-6);

  CameraModelFields only_pinhole = *fields;
  only_pinhole.c = only_pinhole.a = only_pinhole.h = only_pinhole.v = only_pinhole.o =
      only_pinhole.r = {0.0, 0.0, 0.0};
  EXPECT_FALSE(only_pinhole.HasCahvor());
  auto from_pinhole = CameraModelFromFields(only_pinhole);
  ASSERT_TRUE(from_pinhole.ok()) << from_pinhole.status().ToString();
  EXPECT_EQ(from_pinhole->kind(), geometry::CameraModel::Kind::kPinholeRadial);
  EXPECT_LT(MaxProjectionDifference(*cam, *from_pinhole), 1e-9);
}

TEST(CameraModelFields, MissingModelIsAnError) {
  CameraModelFields f;
  f.width = 256;
  f.height = 192;
  const auto r = CameraModelFromFields(f);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.status().code(), StatusCode::kInvalidArgument);
  EXPECT_NE(r.status().message().find("missing"), std::string::npos) << r.status().message();
}

TEST(CameraModelFields, SingularNonFiniteAndEmptyModelsAreErrorsNamingTheProblem) {
  auto good = CameraModelFieldsFromModel(CahvCamera());
  ASSERT_TRUE(good.ok());

  CameraModelFields singular = *good;  // H along A: H, V, A coplanar
  singular.h = singular.a;
  singular.fx = singular.fy = 0.0;  // CAHVOR part only
  auto r = CameraModelFromFields(singular);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("CAHVOR part"), std::string::npos) << r.status().message();

  CameraModelFields nan = *good;
  nan.v[2] = std::numeric_limits<double>::quiet_NaN();
  r = CameraModelFromFields(nan);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("'v'"), std::string::npos) << r.status().message();

  CameraModelFields inf = *good;
  inf.k2 = std::numeric_limits<double>::infinity();
  r = CameraModelFromFields(inf);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("'k2'"), std::string::npos) << r.status().message();

  CameraModelFields empty = *good;
  empty.height = 0;
  r = CameraModelFromFields(empty);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("256x0"), std::string::npos) << r.status().message();

  CameraModelFields not_unit = *good;
  not_unit.a = {0.0, 0.0, 0.0};
  not_unit.h = not_unit.v = {0.0, 0.0, 0.0};  // pinhole only, with a bad quaternion
  not_unit.orientation = {0.9, 0.1, 0.0, 0.0};
  r = CameraModelFromFields(not_unit);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("unit quaternion"), std::string::npos)
      << r.status().message();
}

TEST(CameraModelFields, DisagreeingPartsAreRejectedAsCorrupt) {
  auto good = CameraModelFieldsFromModel(CahvCamera());
  ASSERT_TRUE(good.ok());
  CameraModelFields moved = *good;
  moved.position[0] += 0.01;  // 1 cm: more than 1 mm
  auto r = CameraModelFromFields(moved);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("disagree"), std::string::npos) << r.status().message();

  CameraModelFields turned = *good;  // pinhole pose turned 1 deg about its x axis
  const Eigen::Quaterniond q(turned.orientation[0], turned.orientation[1], turned.orientation[2],
                             turned.orientation[3]);
  const Eigen::Quaterniond q2 =
      q * Eigen::Quaterniond(Eigen::AngleAxisd(kDegree, Eigen::Vector3d::UnitX()));
  turned.orientation = {q2.w(), q2.x(), q2.y(), q2.z()};
  r = CameraModelFromFields(turned);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.status().message().find("disagree"), std::string::npos) << r.status().message();

  CameraModelFields small = *good;  // 0.1 mm is within tolerance
  small.position[2] += 1e-4;
  EXPECT_TRUE(CameraModelFromFields(small).ok());
}

// A NAVCAM-like CAHVOR (1024 x 768, 45 deg, mild barrel distortion) looking along +z, with the
// optical axis O slightly off A.
geometry::CameraModel NavcamCahvor() {
  geometry::Cahvor m;
  m.a = Eigen::Vector3d::UnitZ();
  const double f = 1236.0, cx = 511.5 + 3.2, cy = 383.5 - 2.1;
  m.h = f * Eigen::Vector3d::UnitX() + cx * m.a;
  m.v = f * Eigen::Vector3d::UnitY() + cy * m.a;
  m.o = Eigen::Vector3d(0.002, -0.001, 1.0).normalized();
  m.r = Eigen::Vector3d(0.0, -0.02, 0.004);
  return *geometry::CameraModel::Create(m, 1024, 768);
}

TEST(CameraModelFields, CahvIsExactBothWays) {
  geometry::Cahv m;
  m.c = Eigen::Vector3d(0.1, 0.2, 1.5);
  m.a = Eigen::Vector3d::UnitZ();
  m.h = 300.0 * Eigen::Vector3d::UnitX() + 127.5 * m.a;
  m.v = 300.0 * Eigen::Vector3d::UnitY() + 95.5 * m.a;
  const auto model = *geometry::CameraModel::Create(m, 256, 192);
  PinholeFit fit;
  auto f = CameraModelFieldsFromModel(model, &fit);
  ASSERT_TRUE(f.ok()) << f.status().ToString();
  EXPECT_EQ(f->width, 256);
  EXPECT_EQ(f->height, 192);
  EXPECT_EQ(f->o, f->a);
  EXPECT_EQ(f->r, (std::array<double, 3>{0.0, 0.0, 0.0}));
  EXPECT_NEAR(f->fx, 300.0, 1e-9);
  EXPECT_NEAR(f->cx, 127.5, 1e-9);
  EXPECT_NEAR(f->cy, 95.5, 1e-9);
  EXPECT_NEAR(f->k1, 0.0, 1e-12);
  EXPECT_LT(fit.max_error_px, 1e-6);
  EXPECT_LT((Eigen::Vector3d(f->position[0], f->position[1], f->position[2]) - m.c).norm(), 1e-12);
}

TEST(CameraModelFields, CahvorKeepsItsVectorsAndFitsAPinhole) {
  const geometry::CameraModel model = NavcamCahvor();
  PinholeFit fit;
  auto f = CameraModelFieldsFromModel(model, &fit);
  ASSERT_TRUE(f.ok());
  const auto* m = model.As<geometry::Cahvor>();
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(f->h, (std::array<double, 3>{m->h.x(), m->h.y(), m->h.z()}));
  EXPECT_EQ(f->r, (std::array<double, 3>{m->r.x(), m->r.y(), m->r.z()}));
  EXPECT_LT(fit.max_error_px, 0.2);
  EXPECT_GT(f->fx, 1200.0);
}

TEST(CameraModelFields, ScaledModelFieldsFollowTheResampling) {
  const geometry::CameraModel model = NavcamCahvor();
  auto full = CameraModelFieldsFromModel(model);
  auto small = CameraModelFieldsFromModel(geometry::Scale(model, 0.25));
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
  auto f = CameraModelFieldsFromModel(model);
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

TEST(CameraModelFields, PinholeOrientationHasAPositiveW) {
  geometry::PinholeRadial p;
  p.fx = p.fy = 200.0;
  p.cx = 63.5;
  p.cy = 47.5;
  p.width = 128;
  p.height = 96;
  p.pose.linear() =
      Eigen::AngleAxisd(3.0, Eigen::Vector3d(0.2, 1.0, 0.1).normalized()).toRotationMatrix();
  auto f = CameraModelFieldsFromModel(*geometry::CameraModel::Create(p));
  ASSERT_TRUE(f.ok()) << f.status().ToString();
  EXPECT_GE(f->orientation[0], 0.0);
  const Eigen::Quaterniond q(f->orientation[0], f->orientation[1], f->orientation[2],
                             f->orientation[3]);
  EXPECT_LT((q.toRotationMatrix() - p.pose.linear()).norm(), 1e-9);
}

TEST(Cameras, NamesAndIds) {
  EXPECT_STREQ(CameraName(CameraId::kFrontHazcam), "front_hazcam");
  EXPECT_STREQ(CameraName(static_cast<CameraId>(7)), "unknown");
  EXPECT_FALSE(IsKnownCamera(static_cast<CameraId>(3)));
  EXPECT_FALSE(IsKnownCamera(static_cast<CameraId>(-1)));
  for (int i = 0; i < kNumCameras; ++i) {
    const auto c = static_cast<CameraId>(i);
    auto back = CameraFromName(CameraName(c));
    ASSERT_TRUE(back.ok());
    EXPECT_EQ(*back, c);
  }
  auto bad = CameraFromName("pancam");
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.status().message().find("'pancam'"), std::string::npos);
}

// A frame of w x h images whose models are only sized.
struct Frame {
  Frame(int w, int h) : left(static_cast<std::size_t>(w * h), 1), right(left.size(), 2) {
    f.stamp = Time{5'000'000'000};
    f.width = w;
    f.height = h;
    f.left_model.width = f.right_model.width = w;
    f.left_model.height = f.right_model.height = h;
    Attach();
  }
  void Attach() {
    f.left = left;
    f.right = right;
  }
  StereoFrame f;
  std::vector<std::uint8_t> left, right;
};

TEST(StereoFrames, WrongByteCountSizeOrStampIsAnError) {
  Frame good(16, 8);
  EXPECT_TRUE(CheckStereoFrame(good.f).ok());

  Frame f(16, 8);
  f.right.pop_back();
  f.Attach();
  Status s = CheckStereoFrame(f.f);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("right image has 127 bytes; expected 16x8 = 128"), std::string::npos)
      << s.message();

  Frame g(16, 8);
  g.f.right_model.width = 32;
  s = CheckStereoFrame(g.f);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("right camera model is for 32x8"), std::string::npos) << s.message();

  Frame e(16, 8);
  e.f.width = 0;
  e.f.left = e.f.right = {};
  s = CheckStereoFrame(e.f);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("empty"), std::string::npos) << s.message();

  Frame t(16, 8);
  t.f.stamp = Time{0};
  s = CheckStereoFrame(t.f);
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.message().find("stamp"), std::string::npos) << s.message();
}

}  // namespace
}  // namespace rover::msg
