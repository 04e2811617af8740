#include "rover/dl/mast/look_at.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "rover/geometry/camera_model.hpp"
#include "rover/geometry/transforms.hpp"

namespace rover::dl::mast {
namespace {

using Eigen::Vector3d;
using hwconfig::RoverDescription;

// A 512 x 512 CAHV camera of the NAVCAM pair in the mast-head frame, as deploy/config/
// cameras.yaml gives the pair: centre at the mount's camera centre, A along the pair's x,
// H to the image right (-y of the pair), V image down (-z).
geometry::CameraModel HeadModel(const RoverDescription& rover, int side) {
  const Eigen::Matrix3d r = rover.navcam.Pose().linear();
  const Vector3d a = r * Vector3d::UnitX();
  const double f = 400.0, c = 255.5;
  geometry::Cahv m;
  m.c = rover.navcam.CameraCentre(side);
  m.a = a;
  m.h = f * (r * -Vector3d::UnitY()) + c * a;
  m.v = f * (r * -Vector3d::UnitZ()) + c * a;
  auto model = geometry::CameraModel::Create(m, 512, 512);
  EXPECT_TRUE(model.ok()) << model.status().message();
  return *model;
}

// Points the mast at `target`, moves the head-frame models by the mast angles (the camera
// driver's transform, rover_from_head = MastDescription::HeadPose) and by the rover pose, and
// checks that the pair's boresight passes through the target.
void ExpectBoresightThrough(const RoverDescription& rover, const Eigen::Isometry3d& site_from_rover,
                            const Vector3d& target) {
  SCOPED_TRACE("target " + std::to_string(target.x()) + ", " + std::to_string(target.y()) + ", " +
               std::to_string(target.z()));
  auto angles = LookAtAngles(rover, site_from_rover, target, MastOptions{});
  ASSERT_TRUE(angles.ok()) << angles.status().message();
  const Eigen::Isometry3d site_from_head =
      site_from_rover * rover.mast.HeadPose(angles->pan, angles->tilt);
  const geometry::CameraModel left =
      geometry::Transform(HeadModel(rover, hwconfig::kLeft), site_from_head);
  const geometry::CameraModel right =
      geometry::Transform(HeadModel(rover, hwconfig::kRight), site_from_head);
  const auto* l = left.As<geometry::Cahv>();
  const auto* r = right.As<geometry::Cahv>();
  ASSERT_NE(l, nullptr);
  ASSERT_NE(r, nullptr);
  const Vector3d origin = 0.5 * (l->c + r->c);
  const Vector3d to = target - origin;
  EXPECT_GT(to.dot(l->a), 0.0);                   // in front
  EXPECT_LT(to.cross(l->a).norm(), 1e-7);         // on the boresight
  EXPECT_LT((l->a - r->a).norm(), 1e-12);
  // Seen by both cameras on the middle row, symmetric about the middle column.
  const auto pl = left.Project(target);
  const auto pr = right.Project(target);
  ASSERT_TRUE(pl.has_value() && pr.has_value());
  EXPECT_NEAR(pl->y(), 255.5, 1e-5);
  EXPECT_NEAR(pr->y(), 255.5, 1e-5);
  EXPECT_NEAR(pl->x() - 255.5, 255.5 - pr->x(), 1e-5);
  EXPECT_LT(pr->x(), pl->x());  // positive disparity: the left camera sees it to its right
}

Eigen::Isometry3d SomePose() {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = geometry::QuaternionFromRpy(-0.03, 0.05, 0.7).toRotationMatrix();
  t.translation() = Vector3d(10.0, -4.0, 0.2);
  return t;
}

TEST(LookAt, ClosedFormOnTheDefaultRover) {
  const RoverDescription rover;
  const Eigen::Isometry3d id = Eigen::Isometry3d::Identity();
  auto a = LookAtAngles(rover, id, Vector3d(5.35, 0.0, 1.5), MastOptions{});
  ASSERT_TRUE(a.ok()) << a.status().message();
  EXPECT_NEAR(a->pan, 0.0, 1e-9);
  EXPECT_NEAR(a->tilt, 0.0, 1e-9);
  a = LookAtAngles(rover, id, Vector3d(0.35, 3.0, 1.5), MastOptions{});
  ASSERT_TRUE(a.ok());
  EXPECT_NEAR(a->pan, M_PI / 2, 1e-9);
  a = LookAtAngles(rover, id, Vector3d(2.35, 0.0, -0.5), MastOptions{});
  ASSERT_TRUE(a.ok());
  EXPECT_NEAR(a->tilt, -M_PI / 4, 1e-9);  // 2 m ahead, 2 m below the head
}

TEST(LookAt, RoundTripPutsTheTargetOnTheNavcamBoresight) {
  const RoverDescription rover;
  const Eigen::Isometry3d pose = SomePose();
  for (const Vector3d& rover_point :
       {Vector3d(4.0, 0.0, 0.0), Vector3d(2.0, 1.5, 0.1), Vector3d(1.5, -2.0, -0.2),
        Vector3d(-3.0, 2.0, 0.0), Vector3d(8.0, -1.0, 3.0), Vector3d(0.9, 0.2, 0.0)}) {
    ExpectBoresightThrough(rover, pose, pose * rover_point);
  }
}

TEST(LookAt, RoundTripWithAnOffsetYawedAndDepressedMount) {
  RoverDescription rover;
  rover.navcam.position = Vector3d(0.06, 0.04, 0.09);
  rover.navcam.yaw = 6.0 * kDegree;
  rover.navcam.depression = 12.0 * kDegree;
  ASSERT_TRUE(rover.Validate().ok());
  const Eigen::Isometry3d pose = SomePose();
  for (const Vector3d& rover_point :
       {Vector3d(4.0, 0.0, 0.0), Vector3d(2.0, 1.5, 0.1), Vector3d(-2.5, -2.0, 0.3),
        Vector3d(6.0, 3.0, 2.5)}) {
    ExpectBoresightThrough(rover, pose, pose * rover_point);
  }
}

TEST(LookAt, RefusesWhatTheMastCannotReachNamingTheValue) {
  const RoverDescription rover;
  const Eigen::Isometry3d id = Eigen::Isometry3d::Identity();
  const MastOptions o;
  // Straight behind the mast: pan 180 deg is outside [-175, 175].
  auto a = LookAtAngles(rover, id, Vector3d(-3.0, 0.0, 1.5), o);
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.status().message().find("needs pan = 180 deg"), std::string::npos)
      << a.status().message();
  // Steeply below the head (tilt -84 deg < -80 deg).
  a = LookAtAngles(rover, id, Vector3d(0.5, 0.0, 0.0), o);
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.status().message().find("needs tilt = -84"), std::string::npos)
      << a.status().message();
  // On the pan axis, too near, not finite.
  a = LookAtAngles(rover, id, Vector3d(0.35, 0.0, -2.0), o);
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.status().message().find("pan axis"), std::string::npos) << a.status().message();
  a = LookAtAngles(rover, id, Vector3d(0.45, 0.0, 1.5), o);
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.status().message().find("min_look_distance"), std::string::npos);
  a = LookAtAngles(rover, id, Vector3d(std::nan(""), 0.0, 0.0), o);
  ASSERT_FALSE(a.ok());
  EXPECT_NE(a.status().message().find("not finite"), std::string::npos);
}

TEST(LookAt, TheRoverPoseCounts) {
  // A target 5 m north of a rover facing west (yaw +90 deg) is to its right: pan -90 deg.
  const RoverDescription rover;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  pose.linear() = geometry::QuaternionFromRpy(0.0, 0.0, M_PI / 2).toRotationMatrix();
  const Vector3d head = pose * (rover.mast.pan_joint + Vector3d(0, 0, rover.mast.head_height));
  auto a = LookAtAngles(rover, pose, head + Vector3d(5.0, 0.0, 0.0), MastOptions{});
  ASSERT_TRUE(a.ok()) << a.status().message();
  EXPECT_NEAR(a->pan, -M_PI / 2, 1e-9);
  EXPECT_NEAR(a->tilt, 0.0, 1e-9);
}

TEST(LookAt, CheckMastLimitsNamesTheField) {
  const MastOptions o;
  EXPECT_TRUE(CheckMastLimits({0.1, -0.2}, o, "pan", "tilt").ok());
  const Status s = CheckMastLimits({0.0, 1.5}, o, "pan", "tilt");
  ASSERT_FALSE(s.ok());
  EXPECT_EQ(s.message().rfind("tilt = 85.94 deg, outside [-80, 80] deg", 0), 0u) << s.message();
  EXPECT_FALSE(CheckMastLimits({std::nan(""), 0.0}, o, "pan", "tilt").ok());
}

}  // namespace
}  // namespace rover::dl::mast
