#include "rover/geometry/transforms.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <numbers>
#include <random>

#include "rover/base/units.hpp"

namespace rover::geometry {
namespace {

Eigen::Matrix3d RandomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  return Eigen::Quaterniond(n(rng), n(rng), n(rng), n(rng)).normalized().toRotationMatrix();
}

TEST(Rpy, ConventionMatchesRoverFrame) {
  // Yaw +90 deg turns forward (x) into left (y).
  EXPECT_TRUE((RotationFromRpy(0, 0, kPi / 2) * Eigen::Vector3d::UnitX())
                  .isApprox(Eigen::Vector3d::UnitY(), 1e-12));
  // Positive pitch puts the nose down (x gets a negative z component).
  const Eigen::Vector3d nose = RotationFromRpy(0, 0.1, 0) * Eigen::Vector3d::UnitX();
  EXPECT_NEAR(nose.z(), -std::sin(0.1), 1e-12);
  // Positive roll lifts the left side (y gets a positive z component).
  const Eigen::Vector3d left = RotationFromRpy(0.1, 0, 0) * Eigen::Vector3d::UnitY();
  EXPECT_NEAR(left.z(), std::sin(0.1), 1e-12);
  // ZYX order: R = Rz Ry Rx.
  const Eigen::Matrix3d expected = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()) *
                                   Eigen::AngleAxisd(-0.2, Eigen::Vector3d::UnitY()) *
                                   Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitX()).matrix();
  EXPECT_TRUE(RotationFromRpy(0.1, -0.2, 0.3).isApprox(expected, 1e-12));
  EXPECT_TRUE(RotationFromRpy(Rpy(0.1, -0.2, 0.3)).isApprox(expected, 1e-12));
}

TEST(Rpy, RoundTripsThroughRotationAndQuaternion) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-kPi + 1e-9, kPi);
  std::uniform_real_distribution<double> pitch(-kPi / 2 + 1e-6, kPi / 2 - 1e-6);
  for (int i = 0; i < 1000; ++i) {
    const Rpy rpy(angle(rng), pitch(rng), angle(rng));
    const Rpy back = RpyFromRotation(RotationFromRpy(rpy));
    EXPECT_NEAR(back.x(), rpy.x(), 1e-9);
    EXPECT_NEAR(back.y(), rpy.y(), 1e-9);
    EXPECT_NEAR(back.z(), rpy.z(), 1e-9);
    const Eigen::Quaterniond q = QuaternionFromRpy(rpy);
    EXPECT_GE(q.w(), 0.0);
    EXPECT_NEAR(q.norm(), 1.0, 1e-15);
    EXPECT_TRUE(q.toRotationMatrix().isApprox(RotationFromRpy(rpy), 1e-12));
    const Rpy from_q = RpyFromQuaternion(q);
    EXPECT_TRUE(RotationFromRpy(from_q).isApprox(RotationFromRpy(rpy), 1e-12));
  }
}

TEST(Rpy, GimbalLockSetsRollToZeroAndKeepsTheRotation) {
  for (const double pitch : {kPi / 2, -kPi / 2}) {
    const Eigen::Matrix3d r = RotationFromRpy(0.3, pitch, 0.5);
    const Rpy rpy = RpyFromRotation(r);
    EXPECT_EQ(rpy.x(), 0.0);
    EXPECT_NEAR(rpy.y(), pitch, 1e-7);
    EXPECT_TRUE(RotationFromRpy(rpy).isApprox(r, 1e-9));
  }
}

TEST(WrapAngle, MapsToHalfOpenInterval) {
  EXPECT_EQ(WrapAngle(0.0), 0.0);
  EXPECT_EQ(WrapAngle(kPi), kPi);
  EXPECT_NEAR(WrapAngle(-kPi), kPi, 1e-15);
  EXPECT_NEAR(WrapAngle(3 * kPi), kPi, 1e-12);
  EXPECT_NEAR(WrapAngle(2 * kPi), 0.0, 1e-15);
  EXPECT_NEAR(WrapAngle(-1.5 * kPi), 0.5 * kPi, 1e-12);
  EXPECT_NEAR(WrapAngle(1.5 * kPi), -0.5 * kPi, 1e-12);
  EXPECT_EQ(WrapAngle(-1.0), -1.0);
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1e4, 1e4);
  for (int i = 0; i < 1000; ++i) {
    const double a = u(rng);
    const double w = WrapAngle(a);
    EXPECT_GT(w, -kPi);
    EXPECT_LE(w, kPi);
    EXPECT_NEAR(std::remainder(a - w, 2 * kPi), 0.0, 1e-9);
  }
  EXPECT_TRUE(std::isnan(WrapAngle(std::numeric_limits<double>::quiet_NaN())));
}

TEST(Skew, IsTheCrossProduct) {
  const Eigen::Vector3d v(0.3, -1.2, 2.5);
  const Eigen::Vector3d w(-4.0, 0.5, 1.0);
  EXPECT_TRUE((Skew(v) * w).isApprox(v.cross(w), 1e-15));
  EXPECT_TRUE((Skew(v) + Skew(v).transpose()).isZero(0.0));
}

TEST(So3, ExpLogRoundTripIncludingSmallAndNearPi) {
  std::mt19937_64 rng(11);
  for (int i = 0; i < 500; ++i) {
    const Eigen::Matrix3d r = RandomRotation(rng);
    EXPECT_TRUE(ExpSo3(LogSo3(r)).isApprox(r, 1e-12));
    EXPECT_LE(LogSo3(r).norm(), kPi + 1e-12);
  }
  const Eigen::Vector3d axis = Eigen::Vector3d(1, -2, 0.5).normalized();
  for (const double a : {0.0, 1e-12, 1e-7, 1e-3, 1.0, 3.0, kPi - 1e-7}) {
    const Eigen::Vector3d phi = a * axis;
    EXPECT_LE((LogSo3(ExpSo3(phi)) - phi).norm(), 1e-9 * std::max(1.0, a)) << "angle " << a;
  }
  // Exactly pi: either sign of the axis.
  const Eigen::Vector3d phi = LogSo3(ExpSo3(kPi * axis));
  EXPECT_NEAR(phi.norm(), kPi, 1e-9);
  EXPECT_NEAR(std::abs(phi.normalized().dot(axis)), 1.0, 1e-9);
}

// exp of the 4x4 twist matrix by its Taylor series, an independent reference.
Eigen::Matrix4d ExpTwistSeries(const Vector6d& xi) {
  Eigen::Matrix4d x = Eigen::Matrix4d::Zero();
  x.topLeftCorner<3, 3>() = Skew(xi.tail<3>());
  x.topRightCorner<3, 1>() = xi.head<3>();
  Eigen::Matrix4d sum = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d term = Eigen::Matrix4d::Identity();
  for (int k = 1; k < 60; ++k) {
    term = term * x / k;
    sum += term;
  }
  return sum;
}

TEST(Se3, ExpMatchesMatrixExponentialAndLogInvertsIt) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < 300; ++i) {
    Vector6d xi;
    for (int k = 0; k < 6; ++k) xi(k) = 3.0 * u(rng);
    if (xi.tail<3>().norm() >= kPi) xi.tail<3>() *= 0.9 * kPi / xi.tail<3>().norm();
    const Eigen::Isometry3d t = ExpSe3(xi);
    EXPECT_TRUE(t.matrix().isApprox(ExpTwistSeries(xi), 1e-10));
    EXPECT_LE((LogSe3(t) - xi).norm(), 1e-9);
  }
  // Small rotations and pure translations.
  Vector6d xi;
  xi << 1.0, 2.0, 3.0, 0.0, 0.0, 0.0;
  EXPECT_TRUE(ExpSe3(xi).translation().isApprox(Eigen::Vector3d(1, 2, 3), 1e-15));
  xi << 1.0, 2.0, 3.0, 1e-9, -2e-9, 3e-9;
  EXPECT_LE((LogSe3(ExpSe3(xi)) - xi).norm(), 1e-14);
  // Random poses: Exp(Log(T)) == T.
  for (int i = 0; i < 300; ++i) {
    Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
    t.linear() = RandomRotation(rng);
    t.translation() = Eigen::Vector3d(u(rng), u(rng), u(rng)) * 10.0;
    EXPECT_TRUE(ExpSe3(LogSe3(t)).matrix().isApprox(t.matrix(), 1e-10));
  }
}

TEST(Se3, JacobianInverse) {
  for (const double a : {0.0, 1e-6, 0.5, 2.0, 3.1}) {
    const Eigen::Vector3d phi = a * Eigen::Vector3d(0.2, 0.9, -0.4).normalized();
    EXPECT_TRUE((LeftJacobianSo3(phi) * InverseLeftJacobianSo3(phi))
                    .isApprox(Eigen::Matrix3d::Identity(), 1e-12));
  }
}

TEST(Se3, PoseErrorOfEqualPosesIsZero) {
  const Eigen::Isometry3d a = ExpSe3((Vector6d() << 1, 2, 3, 0.1, 0.2, 0.3).finished());
  EXPECT_LE(LogSe3(a.inverse() * a).norm(), 1e-15);
}

}  // namespace
}  // namespace rover::geometry
