#include "rover/geometry/transforms.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "rover/base/units.hpp"

namespace rover::geometry {

Eigen::Matrix3d RotationFromRpy(double roll, double pitch, double yaw) {
  return QuaternionFromRpy(roll, pitch, yaw).toRotationMatrix();
}

Eigen::Quaterniond QuaternionFromRpy(double roll, double pitch, double yaw) {
  const Eigen::Quaterniond q = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) *
                               Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitY()) *
                               Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX());
  return q.w() < 0.0 ? Eigen::Quaterniond(-q.coeffs()) : q.normalized();
}

Rpy RpyFromRotation(const Eigen::Matrix3d& r) {
  // R = Rz(y) Ry(p) Rx(r):
  //   R(2,0) = -sin p,  R(2,1) = cos p sin r,  R(2,2) = cos p cos r,
  //   R(1,0) = sin y cos p,  R(0,0) = cos y cos p.
  const double sp = std::clamp(-r(2, 0), -1.0, 1.0);
  const double cp = std::hypot(r(0, 0), r(1, 0));
  const double pitch = std::atan2(sp, cp);
  double roll = 0.0;
  double yaw = 0.0;
  if (cp > 1e-12) {
    roll = std::atan2(r(2, 1), r(2, 2));
    yaw = std::atan2(r(1, 0), r(0, 0));
  } else {
    // Gimbal lock (pitch = +-pi/2): only yaw -+ roll is observable. With roll = 0 the middle
    // column of R is (-sin yaw, cos yaw, 0) for both signs of pitch.
    yaw = std::atan2(-r(0, 1), r(1, 1));
  }
  return {WrapAngle(roll), pitch, WrapAngle(yaw)};
}

Rpy RpyFromQuaternion(const Eigen::Quaterniond& q) {
  return RpyFromRotation(q.normalized().toRotationMatrix());
}

double WrapAngle(double angle) {
  if (!std::isfinite(angle)) return angle;
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  if (angle > -kPi && angle <= kPi) return angle;
  double a = std::fmod(angle + kPi, kTwoPi);  // (-2pi, 2pi)
  if (a <= 0.0) a += kTwoPi;                  // (0, 2pi]
  return a - kPi;                             // (-pi, pi]
}

Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d s;
  s << 0.0, -v.z(), v.y(),  //
      v.z(), 0.0, -v.x(),   //
      -v.y(), v.x(), 0.0;
  return s;
}

Eigen::Matrix3d ExpSo3(const Eigen::Vector3d& phi) {
  const double a = phi.norm();
  if (a < 1e-12) return Eigen::Matrix3d::Identity() + Skew(phi);
  return Eigen::AngleAxisd(a, phi / a).toRotationMatrix();
}

Eigen::Vector3d LogSo3(const Eigen::Matrix3d& r) {
  // Through the quaternion: robust at small angles and near pi.
  Eigen::Quaterniond q(r);
  q.normalize();
  if (q.w() < 0.0) q.coeffs() = -q.coeffs();
  const Eigen::Vector3d v = q.vec();
  const double sin_half = v.norm();
  if (sin_half < 1e-12) return 2.0 * v / q.w();  // first order, w ~ 1
  const double angle = 2.0 * std::atan2(sin_half, q.w());
  return angle / sin_half * v;
}

Eigen::Matrix3d LeftJacobianSo3(const Eigen::Vector3d& phi) {
  const double a = phi.norm();
  const Eigen::Matrix3d k = Skew(phi);
  double c1 = 0.0;  // (1 - cos a) / a^2
  double c2 = 0.0;  // (a - sin a) / a^3
  if (a < 1e-4) {
    const double a2 = a * a;
    c1 = 0.5 - a2 / 24.0 + a2 * a2 / 720.0;
    c2 = 1.0 / 6.0 - a2 / 120.0 + a2 * a2 / 5040.0;
  } else {
    c1 = (1.0 - std::cos(a)) / (a * a);
    c2 = (a - std::sin(a)) / (a * a * a);
  }
  return Eigen::Matrix3d::Identity() + c1 * k + c2 * k * k;
}

Eigen::Matrix3d InverseLeftJacobianSo3(const Eigen::Vector3d& phi) {
  const double a = phi.norm();
  const Eigen::Matrix3d k = Skew(phi);
  // J^-1 = I - K/2 + c K^2,  c = (1 - (a/2) cot(a/2)) / a^2.
  double c = 0.0;
  if (a < 1e-4) {
    const double a2 = a * a;
    c = 1.0 / 12.0 + a2 / 720.0 + a2 * a2 / 30240.0;
  } else {
    const double h = 0.5 * a;
    c = (1.0 - h * std::cos(h) / std::sin(h)) / (a * a);
  }
  return Eigen::Matrix3d::Identity() - 0.5 * k + c * k * k;
}

Eigen::Isometry3d ExpSe3(const Vector6d& xi) {
  const Eigen::Vector3d rho = xi.head<3>();
  const Eigen::Vector3d phi = xi.tail<3>();
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.linear() = ExpSo3(phi);
  t.translation() = LeftJacobianSo3(phi) * rho;
  return t;
}

Vector6d LogSe3(const Eigen::Isometry3d& t) {
  const Eigen::Vector3d phi = LogSo3(t.linear());
  Vector6d xi;
  xi.head<3>() = InverseLeftJacobianSo3(phi) * t.translation();
  xi.tail<3>() = phi;
  return xi;
}

}  // namespace rover::geometry
